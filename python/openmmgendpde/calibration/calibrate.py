"""Set up any fluid from its physical properties and measure the model back (`calibrate`; docs/fluids.md).

1. The mapping (openmmgendpde.models.fluid.coarse_grain) gives every parameter; they are printed in OpenMM and
   reduced units.
2. Rounds of f_cut and pi0 (at most plan.pressure_rounds): V-B's f_cut is tuned until the mean particle density
   n-bar equals n0 (on frames of an isoenergetic run n-bar is evaluated at f_cut and at f_cut (1 -+ 2%), and every
   step follows half that slope, since the structure follows f_cut and halves its effect; V-A has no f_cut), then
   n-bar, the virial pressure P (kinetic term included) and both temperatures are measured; while P misses P0 by
   more than 0.01/kappa_T (or 2 standard errors), pi0 moves by (P0 - P)/(dP/dpi0), the response measured between
   rounds (pressure_step; 1 at first), and f_cut is tuned again: pi0 alone barely moves the pressure, the
   structure follows it until f_cut brings n-bar back (docs/fluids.md). Every run melts until n-bar is stationary
   (Calibration.melt), each after the first in its box from the last melted liquid.
3. The heat capacity: the model's c_v per particle is C_V + k_B (the Gamma law of the internal energies) + 3 k_B/2
   (the motion) + c_U (the configurations, measured from the fluctuation of U: Calibration.heat_capacity); C_V is
   set so that it is the fluid's N_m c_v (match_heat_capacity, one exact step).
4. The bulk modulus n dP/dn, from runs in boxes at n0 (1 -+ delta) (a central difference), and from the same runs
   how the particle densities follow the true one, (n/n-bar) d n-bar/d n (1 would let the Tait modulus through);
   B_T iterated on it (Calibration.iterate), then f_cut and pi0 again if B_T moved. Where the response is small
   (water at 20 neighbours without its background pressure: ~0.2) B_T does not move it, and the iteration fails
   saying what to change (FAILURE_ADVICE).
5. The transport coefficients, iterated (Calibration.iterate: a proportional step, then secant steps on the
   measured responses, until within 5% or one standard error (_settled); at most plan.transport_runs measurements;
   a secant whose intercept, the coefficient without the pair term, lies above the target stops the iteration: no
   friction or conduction reaches it):
   - the shear viscosity (friction gamma), from the decay of a transverse velocity wave v_x = V0 sin(k z)
     (k = 2 pi/L) laid on the equilibrium velocities: its amplitude decays as exp(-eta k^2 t/(n0 m));
   - the thermal conductivity (heat conduction kappa), from the decay of a wave theta_i -> theta_i (1 + e sin(k z)):
     the energy wave decays as exp(-lambda k^2 t/(n0 c)), c the model's heat capacity per particle at fixed
     density (step 3); the amplitude is read from sum eps_i + K_i. Not for a fluid with thermal expansion: at fixed
     volume its energy wave is also a sound wave, and the decay read argon's conductivity at 11x the target whatever
     kappa was (docs/thermal.md). Its kappa is iterated on the steady heat flux instead, and no wave is read.
   Then each is measured again by a method of another kind (transport.py, in boxes of plan.steady_cells): periodic
   Poiseuille flow, and a steady heat flux between thermostatted slabs.
   Every mean of a time series has the standard error of correlated_mean (sqrt(g s^2/N), the independent samples
   N/g in the table), a transport coefficient the scatter of its replicas.
6. The results are judged (CRITERIA; --quick: QUICK_CRITERIA): n-bar within 2% of n0, P within 0.01/kappa_T of P0,
   c_v and both temperatures within 2%, each transport coefficient by both methods within 5% of its target
   (a fluid that expands: its conductivity by the heat flux alone; --quick: a factor 2), each allowing the 95%
   interval of the measurement as well (coverage: 2 standard errors, Student's t for few replicas). A calibration
   that misses one of them says which, by how much, and exits with status 1 (after writing --json and --output).
   The number of runs and the wall time are printed.

--fluid takes a built-in name or a fluid file (fluid_files); --output writes the calibrated model as a model file.
--quick: 500 particles and short runs (a functional check in about a minute); the default: 2048 particles.
"""

import dataclasses
import json
import math
import os
import sys
import time

import numpy as np
import openmm
from openmm import unit

from ..api import ESTIMATOR_NAMES
from ..cli.fluids import add_fluid_arguments, parameters_from_arguments
from ..cli.options import (
    POSITIVE,
    SEED,
    add_json,
    add_platform,
    add_progress,
    checked_model,
    failure_message,
    fcc_particles,
    platform_description,
    writable_file,
    writable_stem,
)
from ..cli.progress import Progress
from ..internal.files import atomic_write
from ..models.fluid import CONDUCTIVITY, KB, VISCOSITY
from ..models.fluid_files import save_parameters
from . import expansion
from .calibration import (
    QUICK,
    Calibration,
    Measured,
    Plan,
    _settled,
    pressure_step,
)
from .results import (
    CRITERIA,
    PRESSURE_ROWS,
    QUICK_CRITERIA,
    Miss,
    Property,
    comparison,
    missed_properties,
    misses,
)

#: Fewer independent samples than this make a standard error itself uncertain by more than ~16%
#: (1/sqrt(2 N/g)): calibrate's table says so beside the row.
FEW_SAMPLES = 20


#: A property the model is not fitted to, measured back (the particles' self-diffusion against the molecules').
UNFITTED_DIFFUSION_ROW = "not fitted: self-diffusion (1e-9 m^2/s)"
#: The standard error the pressure runs go on to reach, times 1/kappa_T: a quarter of the pressure's tolerance.
PRESSURE_ERROR = 0.0025


#: Measurements of the thermal expansion at most: as mapped, then beta corrected (expansion.iterated) until alpha is
#: within 5% or one standard error of the target.
EXPANSION_RUNS = 4


def thermal_expansion_rows(calibration, plan, platform, seed):
    """The rows of the thermal expansion coefficient alpha = kappa_T (dP/dT)_V (1e-3/K), as mapped and after beta was
    iterated on the measured slope (expansion.measure, expansion.iterated: at least one correction, then more until
    alpha is within 5% or one standard error (_settled), at most EXPANSION_RUNS measurements; the last beta is kept
    in the calibration's parameters): (name, target, Measured) each."""
    runs = dict(num_particles=plan.particles, melt_steps=plan.melt, steps=plan.frames * plan.interval,
                sample_every=plan.interval, platform=platform, seed=seed, estimator=calibration.estimator,
                time_step=plan.time_step)
    history = [expansion.measure(calibration.parameters, **runs)]
    while len(history) < EXPANSION_RUNS:
        last = history[-1]
        if len(history) > 1 and _settled(Measured(last.alpha, last.alpha_error), last.target_alpha):
            break
        calibration.parameters = expansion.iterated(calibration.parameters, history)
        history.append(expansion.measure(calibration.parameters, **runs))
    first, last = history[0], history[-1]
    steps = " -> ".join(f"{1e3 * h.alpha:.4g} +- {1e3 * h.alpha_error:.2g} (beta {h.thermal_pressure:.5g})"
                        for h in history)
    print(f"  alpha (1e-3/K, beta in kJ/mol/nm^3/K): {steps} (target {1e3 * first.target_alpha:.4g})")
    return [("thermal expansion alpha, beta as mapped (1e-3/K)", 1e3 * first.target_alpha,
             Measured(1e3 * first.alpha, 1e3 * first.alpha_error)),
            (Property.THERMAL_EXPANSION, 1e3 * last.target_alpha, Measured(1e3 * last.alpha, 1e3 * last.alpha_error))]


def speed_of_sound(parameters, bulk_modulus, heat_capacity):
    """The model's speed of sound (nm/ps) from its measured isothermal n dP/dn (Measured, kJ/mol/nm^3) and its
    isochoric heat capacity per particle c (kJ/mol/K; Calibration.heat_capacity): c_s^2 = K_S/rho with
    K_S = K_T + T (dP/dT)_n^2/(n c), the kinetic (dP/dT)_n = n k_B only: the configurational part, measured for
    argon (5 atoms per particle) between T0 (1 -+ 5%), is 2x the kinetic one (0.182 MPa/K in all), and makes K_S/K_T
    1.007 instead of 1.0007 there, below the error of K_T. The error is K_T's, propagated."""
    n, t = parameters.density, parameters.temperature
    adiabatic = bulk_modulus.value + n * KB**2 * t / heat_capacity
    rho = n * parameters.mass
    value = math.sqrt(adiabatic / rho)
    return Measured(value, bulk_modulus.error / (2 * rho * value))


def estimated_steps(plan, estimator):
    """The steps a calibration takes if every melt reaches its criterion at plan.melt steps (the progress bar's
    total)."""
    equilibration = plan.melt + 2 * plan.melt_block + plan.melt // 2
    runs = plan.frames * plan.interval
    tuning = 0 if estimator == "VA" else plan.tuning_iterations * (equilibration + runs)
    waves = 2 * plan.transport_runs * plan.replicas * (equilibration + plan.wave_steps)
    return tuning + (plan.pressure_rounds + 2) * (equilibration + runs) + waves


def replica_processes(platform):
    """How many replicas run at once (Calibration.workers): on the CPU platform as many as it has threads (its
    default Threads, --threads), each process on one; elsewhere one (a GPU runs one Context at a time)."""
    if platform != "CPU":
        return 1
    return int(openmm.Platform.getPlatformByName("CPU").getPropertyDefaultValue("Threads"))


def run(arguments):
    """calibrate (the module's docstring): every argument checked before anything runs; a simulation that fails
    (openmm.OpenMMException: e.g. an internal energy that a step would take below zero) ends in a one-line error
    naming the stage it failed in."""
    stages = ["setting up"]
    try:
        return _run(arguments, stages)
    except openmm.OpenMMException as error:
        raise SystemExit(f"error: calibrate: the stage '{stages[-1]}' failed: {' '.join(str(error).split())} "
                         f"(dt* = {getattr(arguments, 'time_step_used', Plan.time_step):g}: --time-step; heat "
                         f"capacity: --molecules-per-particle)") from None


def _run(arguments, stages):
    parameters = parameters_from_arguments(arguments, "calibrate")
    fluid = parameters.fluid
    plan = QUICK if arguments.quick else Plan()
    if arguments.particles is not None:
        plan = dataclasses.replace(plan, particles=arguments.particles)
    if arguments.time_step is not None:
        plan = dataclasses.replace(plan, time_step=arguments.time_step)
    arguments.time_step_used = plan.time_step
    if arguments.output and os.path.splitext(arguments.output)[1].lower() not in (".toml", ".json"):
        raise SystemExit(f"error: calibrate: --output {arguments.output} is not allowed; it must end in .toml or .json")
    if arguments.plot:
        try:
            import matplotlib  # noqa: F401 (the optional studies dependency, needed for --plot at the end)
        except ImportError:
            raise SystemExit("error: calibrate: --plot needs matplotlib (pip install matplotlib)") from None
    # Every argument checked before the runs: a model built once checks the particles against the cutoff, and every
    # parameter against what GenDPDEForce and GenDPDEIntegrator allow.
    parameters = parameters.for_estimator(arguments.estimator)
    checked_model("calibrate", lambda: parameters.liquid(plan.particles, arguments.estimator, time_step=plan.time_step,
                                                         seed=arguments.seed),
                  "use more --particles, or fewer --neighbors (a smaller --cutoff)")
    workers = min(replica_processes(arguments.platform), plan.replicas)
    print(f"{fluid.name}: {arguments.molecules_per_particle:g} molecules per particle, {parameters.neighbors:.1f} "
          f"neighbours within R, {arguments.estimator}, {plan.particles} particles, {platform_description(arguments)}"
          + (f" (the replicas of a transport measurement {workers} at once, one thread each)" if workers > 1 else ""))
    print("Parameters (OpenMM units; reduced: mass of a particle, L = n0^(-1/3), energy L^3/kappa_T, k_B = 1):")
    reduced = parameters.reduced()
    rows = [("n0 (nm^-3)", parameters.density, "n0*"), ("pi0 (kJ/mol/nm^3)", parameters.reference_pressure, "pi0*"),
            ("B_T (kJ/mol/nm^3)", parameters.bulk_modulus, "B_T*"), ("gamma_T", parameters.tait_exponent, "gamma_T"),
            ("background pressure p_b (kJ/mol/nm^3)", parameters.background_pressure or 0.0, "p_b*"),
            ("cutoff R (nm)", parameters.cutoff, "R*"), ("friction (amu/ps)", parameters.friction, "gamma*"),
            ("heat conduction (kJ K/(mol ps))", parameters.heat_conduction, "kappa*"),
            ("C_V per particle (kJ/mol/K)", parameters.heat_capacity, "C_V*"),
            ("mass (amu)", parameters.mass, None), ("T0 (K)", parameters.temperature, "T0*")]
    print("| parameter | value | reduced |\n|---|---|---|")
    for name, value, key in rows:
        print(f"| {name} | {value:.6g} | {reduced[key]:.6g} |" if key else f"| {name} | {value:.6g} | 1 |")
    progress = Progress(estimated_steps(plan, arguments.estimator), "calibrate", always=arguments.progress)
    calibration = Calibration(parameters, arguments.estimator, plan, arguments.platform, seed=arguments.seed,
                              progress=progress, workers=workers)
    started = time.monotonic()

    def stage(text):
        print(f"[{time.monotonic() - started:6.0f} s] {text}", flush=True)
        stages.append(text.split(' (')[0])
        progress.label = f"calibrate: {stages[-1]}"

    targets = parameters.targets()
    # The pressure's error matters (pi0 is moved by it and it is judged to 0.01/kappa_T): its runs go on until the
    # standard error is a quarter of that.
    pressure_error = PRESSURE_ERROR * targets["bulk_modulus"]
    pressure_tolerance = CRITERIA[Property.PRESSURE].tolerance * targets["bulk_modulus"]
    pressures = []   # (pi0, measured P) of each round, f_cut tuned

    def pressure_rounds(rounds, first_iterations):
        """Rounds of (f_cut tuned, P measured, pi0 moved) until P is within its tolerance; the last thermodynamics
        (measured with the final parameters)."""
        for round_ in range(rounds):
            stage(f"Round {len(pressures) + 1} of f_cut and pi0: f_cut tuned so that n-bar = n0 "
                  f"({arguments.estimator}), then P measured")
            scaling = calibration.tune_cutoff_scaling(first_iterations if round_ == 0 else 2)
            thermo = calibration.thermodynamics(pressure_error=pressure_error)
            pressure = thermo["pressure"]
            pressures.append((calibration.parameters.reference_pressure, pressure))
            print(f"  f_cut = {scaling:.4f}, pi0 = {calibration.parameters.reference_pressure:.6g} kJ/mol/nm^3: P = "
                  f"{_mpa(pressure.value):.4g} +- {_mpa(pressure.error):.2g} MPa (P0 = "
                  f"{_mpa(targets['pressure']):.4g})")
            if abs(pressure.value - targets["pressure"]) <= max(pressure_tolerance, 2 * pressure.error):
                break
            if round_ + 1 < rounds:
                shift = pressure_step(pressures, targets["pressure"])
                calibration.correct_reference_pressure(calibration.parameters.reference_pressure + shift)
                print(f"  pi0 moved by {shift:.4g} kJ/mol/nm^3 ({_mpa(shift):.4g} MPa)")
        return thermo

    thermo = mapped = pressure_rounds(plan.pressure_rounds, plan.tuning_iterations)
    if len(pressures) > 1:
        mapped = {"pressure": pressures[0][1]}
    failures = []
    responses = []
    stage("Heat capacity: C_V so that the model's c_v (C_V + k_B + 3 k_B/2 + c_U, c_U from the fluctuation of U) "
          "is the fluid's")
    heat_capacity_mapped = thermo["heat_capacity"]
    failures += Miss.of_iteration(Property.HEAT_CAPACITY, calibration.match_heat_capacity(targets["heat_capacity"]))
    print(f"  c_v = {heat_capacity_mapped.value / KB:.4g} k_B per particle (c_U = "
          f"{thermo['configurational_heat_capacity'].value / KB:.3g} +- "
          f"{thermo['configurational_heat_capacity'].error / KB:.2g} k_B), target {targets['heat_capacity'] / KB:.4g} "
          f"k_B: C_V {parameters.heat_capacity / KB:.4g} -> {calibration.parameters.heat_capacity / KB:.4g} k_B")

    def measure_bulk_modulus():
        modulus, response = calibration.bulk_modulus()
        responses.append(response)
        return modulus

    stage(f"Bulk modulus: B_T iterated on n dP/dn (boxes at n0 (1 -+ {plan.density_step:g}))")
    bulk_modulus_before = calibration.parameters.bulk_modulus
    bulk, bulk_runs, failure = calibration.iterate(
        "bulk_modulus", measure_bulk_modulus, targets["bulk_modulus"], Property.BULK_MODULUS.quantity, plan.bulk_runs)
    failures += Miss.of_iteration(Property.BULK_MODULUS, failure)
    response = responses[[x for x, _ in bulk_runs].index(calibration.parameters.bulk_modulus)]   # of the B_T kept
    if calibration.parameters.bulk_modulus != bulk_modulus_before:   # the structure and the pressure follow B_T
        thermo = pressure_rounds(2, 2)
    elif calibration.parameters.heat_capacity != parameters.heat_capacity:
        stage("The thermodynamics measured again with the calibrated C_V")
        thermo = calibration.thermodynamics(pressure_error=pressure_error)
    expansion_rows = []
    if calibration.parameters.thermal_pressure is not None:
        stage(f"Thermal expansion: (dP/dT)_V at n0, runs at T0 -+ {100 * expansion.DELTA:g}%; beta iterated on the "
              f"measured slope (at most {EXPANSION_RUNS} measurements)")
        expansion_rows = thermal_expansion_rows(calibration, plan, arguments.platform, arguments.seed)
    stage(f"Shear viscosity: friction iterated on decaying transverse waves ({plan.replicas} per run)")
    viscosity, viscosity_runs, viscosity_failure = calibration.iterate(
        "friction", calibration.shear_viscosity, targets["shear_viscosity"], "shear viscosity", plan.transport_runs)
    # A fluid that expands: its energy wave at fixed volume is also a sound wave, and the wave's decay read argon's
    # conductivity at 11x whatever kappa was (docs/thermal.md); kappa is iterated on the steady heat flux instead.
    expanding = calibration.parameters.thermal_pressure is not None
    if expanding:
        conductivity = None
    else:
        stage(f"Thermal conductivity: heat conduction iterated on decaying energy waves ({plan.replicas} per run)")
        conductivity, conductivity_runs, conductivity_failure = calibration.iterate(
            "heat_conduction", calibration.thermal_conductivity, targets["thermal_conductivity"],
            "thermal conductivity", plan.transport_runs)
    stage(f"Shear viscosity by periodic Poiseuille flow ({plan.replicas} runs, {plan.steady_cells} cells)")
    poiseuille, wave, failure = calibration.steady_correction(
        "friction", calibration.steady_viscosity, calibration.shear_viscosity, viscosity_runs,
        targets["shear_viscosity"], "shear viscosity", viscosity_failure)
    failures += Miss.of_iteration(Property.VISCOSITY_FLOW, failure)
    viscosity = wave or viscosity
    if expanding:
        stage(f"Thermal conductivity: heat conduction iterated on a steady heat flux between slabs ({plan.replicas} "
              f"runs, {plan.steady_cells} cells; the energy wave of a fluid that expands is also a sound wave)")
        heat_flux, conductivity_runs, failure = calibration.iterate(
            "heat_conduction", calibration.steady_conductivity, targets["thermal_conductivity"],
            "thermal conductivity", plan.transport_runs)
    else:
        stage(f"Thermal conductivity by a steady heat flux between slabs ({plan.replicas} runs, "
              f"{plan.steady_cells} cells)")
        heat_flux, wave, failure = calibration.steady_correction(
            "heat_conduction", calibration.steady_conductivity, calibration.thermal_conductivity, conductivity_runs,
            targets["thermal_conductivity"], "thermal conductivity", conductivity_failure)
        conductivity = wave or conductivity
    failures += Miss.of_iteration(Property.CONDUCTIVITY_HEAT_FLUX, failure)
    progress.finish()
    stage(f"Done: {calibration.runs} runs")
    melts = [steps for steps, _ in calibration.melt_steps] or [0]
    unsettled = sum(not stationary for _, stationary in calibration.melt_steps)
    print(f"Melts (until n-bar is stationary, Calibration.melt): {min(melts)} to {max(melts)} steps of dt* = "
          f"{plan.time_step:g} (the first in each box from the lattice, the others from the last melted liquid)"
          + (f"; {unsettled} of {len(melts)} were not stationary after {plan.melt_limit} steps" if unsettled else ""))
    final = calibration.parameters
    print("| parameter | mapped | calibrated | calibrated/mapped |\n|---|---|---|---|")
    for name, attribute in (("f_cut", "cutoff_scaling"), ("pi0 (kJ/mol/nm^3)", "reference_pressure"),
                            ("B_T (kJ/mol/nm^3)", "bulk_modulus"), ("friction gamma (amu/ps)", "friction"),
                            ("heat conduction kappa (kJ K/(mol ps))", "heat_conduction"),
                            ("C_V (kJ/mol/K)", "heat_capacity"), ("beta (kJ/mol/nm^3/K)", "thermal_pressure")):
        first, last = getattr(parameters, attribute), getattr(final, attribute)
        if first is None:
            continue
        print(f"| {name} | {first:.6g} | {last:.6g} | {last / first if first else math.nan:.4g} |")
    scaled = {"mpa": _mpa(1.0), "mpa_s": _mpa_s(1.0), "w_mk": _w_mk(1.0)}
    target_rows = [
        (Property.DENSITY, targets["density"], thermo["density"]),
        (PRESSURE_ROWS[0], _mpa(targets["pressure"]), _scaled(mapped["pressure"], scaled["mpa"])),
        (Property.PRESSURE, _mpa(targets["pressure"]), _scaled(thermo["pressure"], scaled["mpa"])),
        ("bulk modulus n dP/dn, B_T as mapped (MPa)", _mpa(targets["bulk_modulus"]),
         _scaled(bulk_runs[0][1], scaled["mpa"])),
        (Property.BULK_MODULUS, _mpa(targets["bulk_modulus"]), _scaled(bulk, scaled["mpa"])),
        ("particle-density response (n/n-bar) dn-bar/dn", 1.0, response),
        ("isochoric heat capacity c_v, C_V as mapped (J/(kg K))", _j_kgk(targets["heat_capacity"], final),
         _scaled(heat_capacity_mapped, _j_kgk(1.0, final))),
        (Property.HEAT_CAPACITY, _j_kgk(targets["heat_capacity"], final),
         _scaled(thermo["heat_capacity"], _j_kgk(1.0, final))),
        (Property.KINETIC_TEMPERATURE, targets["temperature"], thermo["kinetic_temperature"]),
        (Property.HARMONIC_TEMPERATURE, targets["temperature"], thermo["harmonic_temperature"]),
        ("shear viscosity, wave, friction as mapped (mPa s)", _mpa_s(targets["shear_viscosity"]),
         _scaled(viscosity_runs[0][1], scaled["mpa_s"])),
        (Property.VISCOSITY_WAVE, _mpa_s(targets["shear_viscosity"]), _scaled(viscosity, scaled["mpa_s"])),
        (Property.VISCOSITY_FLOW, _mpa_s(targets["shear_viscosity"]),
         _scaled(poiseuille, scaled["mpa_s"])),
        (f"thermal conductivity, {'heat flux' if expanding else 'wave'}, kappa as mapped (W/(m K))",
         _w_mk(targets["thermal_conductivity"]), _scaled(conductivity_runs[0][1], scaled["w_mk"])),
        *([] if expanding else [(Property.CONDUCTIVITY_WAVE, _w_mk(targets["thermal_conductivity"]),
                                 _scaled(conductivity, scaled["w_mk"]))]),
        (Property.CONDUCTIVITY_HEAT_FLUX, _w_mk(targets["thermal_conductivity"]),
         _scaled(heat_flux, scaled["w_mk"])),
        *expansion_rows,
        (UNFITTED_DIFFUSION_ROW, _m2_s(targets["self_diffusion"]) if targets.get("self_diffusion") else math.nan,
         _scaled(thermo["self_diffusion"], _m2_s(1.0))),
        ("not fitted: speed of sound, from n dP/dn (m/s)",
         targets["speed_of_sound"] * 1e3 if targets.get("speed_of_sound") else math.nan,
         _scaled(speed_of_sound(final, bulk, thermo["heat_capacity"].value), 1e3)),
    ]
    print("Targets and what the model gives (standard errors; independent samples: N/g of a time series, or "
          "the replicas):")
    print("| property | target | model | model/target | independent samples |\n|---|---|---|---|---|")
    results, judged = {}, {}   # (the report's rows by label; the judged properties by Property)
    bulk_target = _mpa(targets["bulk_modulus"])
    for row, target, measured in target_rows:
        name = row.label if isinstance(row, Property) else row
        samples = "" if measured.samples is None else f"{measured.samples:.0f}"
        time_series = not name.startswith(("shear", "thermal"))   # (the annotation of the report)
        if measured.samples is not None and measured.samples < FEW_SAMPLES and time_series:
            samples += f" (few: the error is uncertain by ~{100 / math.sqrt(2 * measured.samples):.0f}%)"
        print(f"| {name} | {target:.5g} | {measured.value:.5g} +- {measured.error:.2g} | "
              f"{comparison(row, target, measured.value, bulk_target).removeprefix('model/target = ')} | "
              f"{samples} |")
        results[name] = {"target": target, "model": measured.value, "error": measured.error,
                         "samples": measured.samples}
        if isinstance(row, Property):
            judged[row] = results[name]
    missed = misses(judged, QUICK_CRITERIA if arguments.quick else CRITERIA) + failures
    print("Notes: the bulk modulus that B_T can reach is set by how the particle densities n_i follow the true "
          "density (the response above; docs/fluids.md); the transport coefficients are iterated on the wave decays "
          "and measured again by the steady flows in the same box (docs/transport.md)"
          + ("; the conductivity of a fluid that expands on the heat flux (docs/thermal.md)." if expanding else "."))
    print(f"{calibration.runs} runs in {time.monotonic() - started:.0f} s.")
    record = {"fluid": fluid.name, "molecules_per_particle": arguments.molecules_per_particle,
              "estimator": arguments.estimator, "particles": plan.particles, "cutoff_scaling": final.cutoff_scaling,
              "reference_pressure_shift": final.reference_pressure - parameters.reference_pressure,
              "parameters": reduced, "runs": calibration.runs, "wall_time_s": time.monotonic() - started,
              "pressure_rounds": [[pi0, _mpa(p.value), _mpa(p.error)] for pi0, p in pressures],
              "bulk_modulus_runs": [[x, _mpa(m.value), _mpa(m.error)] for x, m in bulk_runs],
              "friction_runs": [[x, _mpa_s(m.value), _mpa_s(m.error)] for x, m in viscosity_runs],
              "heat_conduction_runs": [[x, _w_mk(m.value), _w_mk(m.error)] for x, m in conductivity_runs],
              "calibrated": calibration.parameters.reduced(), "results": results,
              "missed": [str(miss) for miss in missed], "missed_properties": missed_properties(missed)}
    # The outputs, each written atomically (files.atomic_write) and each on its own: one that cannot be written (a
    # full disk) does not keep the others from being written, and is reported in one line at the end.
    unwritten = []

    def write(option, path, done, function, *arguments_):
        try:
            function(*arguments_)
            print(done)
        except OSError as error:
            unwritten.append(f"{option} {path} could not be written ({failure_message(error)})")

    if arguments.output:
        write("--output", arguments.output,
              f"The calibrated model is in {arguments.output} (fluid_files.load_parameters reads it).",
              save_parameters, calibration.parameters, arguments.output,
              f"{fluid.name}: calibrated by python -m openmmgendpde calibrate ({arguments.molecules_per_particle:g} "
              f"molecules per particle, {arguments.estimator}, {plan.particles} particles, seed {arguments.seed}); "
              f"{'MISSED: ' + '; '.join(map(str, missed)) if missed else 'every judged result within its tolerance'}.\n"
              f"Build it again: openmmgendpde.models.fluid_files.load_parameters(path).liquid(num_particles, "
              f"'{arguments.estimator}')")
    if arguments.json:
        write("--json", arguments.json, f"The parameters and results are in {arguments.json}.", _write_json, record,
              arguments.json)
    if arguments.plot:
        write("--plot", arguments.plot, f"Figure: {arguments.plot}.png and .pdf", plot, record, arguments.plot)
    if missed:
        properties = missed_properties(missed)
        print(f"error: calibrate: the calibration failed, {len(properties)} judged "
              f"{'property' if len(properties) == 1 else 'properties'} missed ({'; '.join(properties)}; CRITERIA, "
              f"docs/fluids.md):\n  " + "\n  ".join(map(str, missed)), file=sys.stderr)
    if unwritten:
        outputs = sum(bool(given) for given in (arguments.output, arguments.json, arguments.plot))
        raise SystemExit(f"error: calibrate: {'; '.join(unwritten)}"
                         + ("; the other outputs were written" if len(unwritten) < outputs else ""))
    if missed:
        raise SystemExit(1)
    print(f"Every judged result within its tolerance ({', '.join(prop.label for prop in CRITERIA if prop in judged)}"
          f"{'; --quick: transport within a factor 2' if arguments.quick else ''}).")
    return results


def _write_json(record, path):
    with atomic_write(path) as stream:
        json.dump(record, stream, indent=1)


def plot(record, path_stem):
    """The figure of a calibration (``record``: what --json writes) as path_stem.png and .pdf: model/target of every
    judged row with 2 standard errors, and the convergence of the iterations (the transport coefficients over their
    targets against the pair coefficient over its mapped value; the pressure, (P - P0) kappa_T, by round)."""
    from ..internal.plotting import panels, save
    figure, (table, transport, pressure) = panels(3, width=4.6)
    results = record["results"]
    names = [name for name in results if not name.startswith(("particle-density", "pressure"))
             and math.isfinite(results[name]["target"])]
    ratios = [results[name]["model"] / results[name]["target"] for name in names]
    bars = [2 * results[name]["error"] / results[name]["target"] for name in names]
    table.errorbar(ratios, range(len(names)), xerr=bars, fmt="o", color="k")
    table.axvspan(0.95, 1.05, color="0.85")
    table.axvline(1.0, color="0.5", lw=0.8)
    table.set_yticks(range(len(names)), [name.split(" (")[0] for name in names], fontsize=7)
    table.set_xlabel("model / target (2 standard errors)")
    table.invert_yaxis()
    for key, label, target in (("bulk_modulus_runs", "n dP/dn (B_T)", Property.BULK_MODULUS),
                                 ("friction_runs", "viscosity (friction)", Property.VISCOSITY_WAVE),
                                 ("heat_conduction_runs", "conductivity (kappa)", Property.CONDUCTIVITY_HEAT_FLUX)):
        runs = np.array(record[key])
        target = results[target.label]["target"]
        transport.errorbar(runs[:, 0] / runs[0, 0], runs[:, 1] / target, yerr=2 * runs[:, 2] / target, fmt="o-",
                           label=label)
    transport.axhspan(0.95, 1.05, color="0.85")
    transport.set_xlabel("parameter / mapped")
    transport.set_ylabel("measured / target")
    rounds = np.array(record["pressure_rounds"])
    modulus = results[Property.BULK_MODULUS.label]["target"]
    p0 = results[Property.PRESSURE.label]["target"]
    pressure.errorbar(np.arange(1, len(rounds) + 1), (rounds[:, 1] - p0) / modulus, yerr=2 * rounds[:, 2] / modulus,
                      fmt="o-", color="k")
    pressure.axhspan(-0.01, 0.01, color="0.85")
    pressure.set_xlabel("round of f_cut and pi0")
    pressure.set_ylabel("(P - P0) kappa_T")
    figure.suptitle(f"{record['fluid']}: {record['molecules_per_particle']:g} per particle, {record['estimator']}",
                    fontsize=9)
    save(figure, path_stem, legend_axis=transport)


def _mpa(value):
    """kJ/mol/nm^3 -> MPa."""
    return (value * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(
        unit.megapascal)


def _m2_s(value):
    """nm^2/ps -> 1e-9 m^2/s."""
    return value * 1e-18 / 1e-12 / 1e-9


def _j_kgk(value, parameters):
    """kJ/mol/K per particle -> J/(kg K) of the particle's mass."""
    return value * 1e3 / (parameters.mass * 1e-3)


def _mpa_s(value):
    """amu/(nm ps) -> mPa s."""
    return (value * VISCOSITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.pascal * unit.second) * 1e3


def _w_mk(value):
    """kJ/(mol ps nm K) -> W/(m K)."""
    return (value * CONDUCTIVITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.watt / (unit.meter * unit.kelvin))


def _scaled(measured, factor):
    return Measured(measured.value * factor, measured.error * factor, measured.samples)


def add_arguments(parser):
    add_fluid_arguments(parser)
    parser.add_argument("--estimator", choices=list(ESTIMATOR_NAMES.values()), default="VB",
                        help="the density estimator (default VB; VC is VB with free surfaces)")
    parser.add_argument("--particles", type=fcc_particles, help="4 m^3 particles (default 2048; --quick 500)")
    parser.add_argument("--quick", action="store_true", help="500 particles and short runs (a functional check)")
    parser.add_argument("--time-step", type=POSITIVE, help="dt* in the model's reduced time (default 0.01; smaller "
                        "where an internal energy would become negative: "
                        "openmmgendpde.calibration.stability.suggest_time_step gives one for a model)")
    parser.add_argument("--seed", type=SEED, default=1, help="random seed (default 1)")
    add_json(parser, "the parameters and results")
    add_progress(parser)
    parser.add_argument("--plot", metavar="STEM", type=writable_stem(),
                        help="also draw the results and the iterations to STEM.png and STEM.pdf (needs matplotlib)")
    parser.add_argument("--output", type=writable_file, help="write the calibrated model to this file (.toml or "
                        ".json), which openmmgendpde.models.fluid_files.load_parameters reads back")
    add_platform(parser)
    parser.set_defaults(run=run)
