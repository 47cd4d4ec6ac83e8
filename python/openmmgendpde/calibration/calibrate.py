# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
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
   set so that it is the fluid's N_m c_v (match_heat_capacity, one exact step). A law that depends on temperature is
   fitted again at the new mean particle temperature T0 (1 + k_B/C_V), and where its pressure then moved past half
   its tolerance, f_cut and pi0 are tuned again.
4. The bulk modulus n dP/dn, from runs in boxes at n0 (1 -+ delta) (a central difference), and from the same runs
   how the particle densities follow the true one, (n/n-bar) d n-bar/d n (1 would let the Tait modulus through);
   B_T iterated on it (Calibration.iterate), then f_cut and pi0 again if B_T moved. Where the response is small
   (water at 20 neighbours without its background pressure: ~0.2) B_T does not move it, and the iteration fails
   saying what to change (FAILURE_ADVICE). A law that depends on temperature then has its beta iterated on the
   measured (dP/dT)_V (thermal_expansion_rows).
   The report is the written model's: every equilibrium number in it (n-bar, P, c_v, the temperatures, n dP/dn and
   the response) is measured on the parameters that --output writes; where a later stage moved f_cut, pi0 or beta
   after one was measured (f_cut and pi0 follow a new B_T, beta comes last), it is measured again
   (Stages.written_model). The speed of sound is derived from them: c^2 = K_S/rho with
   K_S = K_T + T (dP/dT)_n^2/(n c_v) (thermodynamics.adiabatic_bulk_modulus), K_T the measured n dP/dn, c_v the
   model's, and (dP/dT)_n the model's own thermal pressure, measured: the thermal expansion's last measurement, or
   for a law without one runs at T0 -+ 8% (Calibration.thermal_pressure: the kinetic n k_B and the structure's).
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
   Last, the speed of sound measured directly (not with --quick), beside the derived one: a standing sound wave
   v_z = A sin(k z), A = 0.05 c, laid on the equilibrium velocities of isoenergetic runs of the written model in a
   long box (plan.sound_cells, 3 x 3 x 48 FCC cells, k = 2 pi/L_z), its amplitude 2 <v_z sin(k z)> followed for two
   periods and fitted with a damped cosine (Calibration.sound_speed): c = sqrt(omega^2 + a^2)/k, a the damping rate;
   the replicas' mean and standard error (argon 648.5 +- 1.8 m/s against 645.9 +- 2.4 derived, water 1445 +- 14
   against 1445 +- 7, 6 replicas: docs/fluids.md). It adds ~1.8 min on one core (4 replicas of ~17000 steps of 1728
   particles), which would double --quick's run: --quick derives the speed only.
   Every mean of a time series has the standard error of correlated_mean (sqrt(g s^2/N), the independent samples
   N/g in the table), a transport coefficient the scatter of its replicas.
6. The results are judged (CRITERIA; --quick: QUICK_CRITERIA): n-bar within 2% of n0, P within 0.01/kappa_T of P0,
   c_v and both temperatures within 2%, each transport coefficient by both methods within 5% of its target
   (a fluid that expands: its conductivity by the heat flux alone; --quick: a factor 2), each allowing the 95%
   interval of the measurement as well (coverage: 2 standard errors, Student's t for few replicas). A calibration
   that misses one of them says which, by how much, and exits with status 1 (after writing --json and --output).
   The number of runs and the wall time are printed.

--fluid takes a built-in name or a fluid file (fluid_files); --output writes the calibrated model as a model file.
--quick: 500 particles and short runs, a functional check: 1.2-1.6 min measured here (`time python -m openmmgendpde
calibrate --quick`: water 93 s on the Reference platform, 78 s with --platform CPU; --fluid argon 71 s, the example
nitrogen 72 s; 2 cores shared with other work), more on a busier machine. The default: 2048 particles.
"""

import dataclasses
import time

import openmm

from ..api import estimator_of
from ..models.fluid import KB
from . import expansion
from .calibration import QUICK, Calibration, Measured, Plan, _settled, pressure_step  # noqa: F401 (QUICK: API)
from .report import calibration_record, calibration_rows, mpa, speed_of_sound
from .results import CRITERIA, Miss, Property, misses

#: The standard error the pressure runs go on to reach, times 1/kappa_T: a quarter of the pressure's tolerance.
PRESSURE_ERROR = 0.0025
#: How far the pressure of a law that depends on temperature may move (times 1/kappa_T) when C_V is matched before
#: f_cut and pi0 are tuned again: half the pressure's tolerance (results.CRITERIA: 0.01/kappa_T).
RETUNE_PRESSURE = 0.005
#: Measurements of the thermal expansion at most: as mapped, then beta corrected (expansion.iterated) until alpha is
#: within 5% or one standard error of the target.
EXPANSION_RUNS = 4


class StageFailure(RuntimeError):
    """A stage of calibrate whose simulation failed (an openmm.OpenMMException: e.g. an internal energy that a step
    would take below zero) or whose law could not be fitted (a ValueError): ``stage`` names it, ``error`` is the
    exception."""

    def __init__(self, stage, error):
        super().__init__(f"the stage '{stage}' failed: {' '.join(str(error).split())}")
        self.stage, self.error = stage, error


@dataclasses.dataclass
class CalibrationResult:
    """What calibrate found: the parameters it started from (``mapped``) and the calibrated ones, the rows of its
    report [(label or Property, target, Measured)] in the report's units, the results by label
    {label: {target, model, error, samples}}, the judged properties that missed (results.Miss), the record that
    --json writes, the runs (Contexts made), the Isothermal steps of each melt [(steps, stationary)], and the wall
    time (s)."""
    mapped: object
    parameters: object
    estimator: str
    plan: Plan
    rows: list
    results: dict
    missed: list
    record: dict
    runs: int
    melt_steps: list
    wall_time: float
    expanding: bool

    @property
    def succeeded(self):
        return not self.missed


def estimated_steps(plan, estimator):
    """The steps a calibration takes if every melt reaches its criterion at plan.melt steps (the progress bar's
    total)."""
    equilibration = plan.melt + 2 * plan.melt_block + plan.melt // 2
    runs = plan.frames * plan.interval
    tuning = plan.tuning_iterations * (equilibration + runs) if estimator_of(estimator).reads_cutoff_scaling else 0
    waves = 2 * plan.transport_runs * plan.replicas * (equilibration + plan.wave_steps)
    thermal_pressure = 2 * (plan.melt + plan.melt // 2 + runs)   # (written_model: (dP/dT)_n of a law without one)
    # The sound wave: a period is L_z/c, L_z = n_z 4^(1/3) in the reduced length n0^(-1/3), c ~ 1 in reduced units
    # (K_T* = 1 at the target; K_S a few % above).
    sound = (plan.replicas * (equilibration + round(plan.sound_periods * plan.sound_cells[2] * 4 ** (1 / 3)
                                                    / plan.time_step)) if plan.sound_wave else 0)
    return tuning + (plan.pressure_rounds + 2) * (equilibration + runs) + thermal_pressure + waves + sound


def thermal_expansion_rows(calibration, plan, platform, seed, report=print, history=None):
    """The rows of the thermal expansion coefficient alpha = kappa_T (dP/dT)_V (1e-3/K), as mapped and after beta was
    iterated on the measured slope (expansion.measure, expansion.iterated: at least one correction, then more until
    alpha is within 5% or one standard error (_settled), at most EXPANSION_RUNS measurements; the last beta is kept
    in the calibration's parameters): (name, target, Measured) each. ``history``: a list that receives the
    measurements (expansion.ThermalExpansion, the last of the beta kept)."""
    runs = calibration.expansion_runs(platform, seed, plan)
    history = [] if history is None else history
    history.append(expansion.measure(calibration.parameters, **runs))
    while len(history) < EXPANSION_RUNS:
        last = history[-1]
        if len(history) > 1 and _settled(Measured(last.alpha, last.alpha_error), last.target_alpha):
            break
        calibration.parameters = expansion.iterated(calibration.parameters, history)
        history.append(expansion.measure(calibration.parameters, **runs))
    first, last = history[0], history[-1]
    steps = " -> ".join(f"{1e3 * h.alpha:.4g} +- {1e3 * h.alpha_error:.2g} (beta {h.thermal_pressure:.5g})"
                        for h in history)
    report(f"  alpha (1e-3/K, beta in kJ/mol/nm^3/K): {steps} (target {1e3 * first.target_alpha:.4g})")
    return [("thermal expansion alpha, beta as mapped (1e-3/K)", 1e3 * first.target_alpha,
             Measured(1e3 * first.alpha, 1e3 * first.alpha_error)),
            (Property.THERMAL_EXPANSION, 1e3 * last.target_alpha, Measured(1e3 * last.alpha, 1e3 * last.alpha_error))]


class Stages:
    """The stages of one calibration (module docstring), in order, on a Calibration; each reports its lines through
    ``report`` and records what the report needs (pressures, failures, the runs of each iteration)."""

    def __init__(self, calibration, report=print):
        self.calibration, self.report = calibration, report
        self.plan, self.mapped = calibration.plan, calibration.parameters
        self.targets = self.mapped.targets()
        self.started = time.monotonic()
        self.stages = []       # the stages begun, the last the one running
        self.pressures = []    # (pi0, measured P) of each round, f_cut tuned
        self.failures = []     # results.Miss of the iterations that failed
        self.measured = {}     # what the report's rows need, by name
        # The parameters that the last thermodynamics and the n dP/dn kept were measured on (equilibrium(): those that
        # the equilibrium depends on), and the last measurement of the thermal expansion (ThermalExpansion).
        self.thermo_parameters = self.bulk_parameters = self.expansion = None

    def stage(self, text):
        self.report(f"[{time.monotonic() - self.started:6.0f} s] {text}")
        self.stages.append(text.split(' (')[0])
        if self.calibration.progress is not None:
            self.calibration.progress.label = f"calibrate: {self.stages[-1]}"

    def pressure_rounds(self, rounds, first_iterations):
        """Rounds of (f_cut tuned, P measured, pi0 moved) until P is within its tolerance (0.01/kappa_T, or 2
        standard errors, each run going on until its standard error is PRESSURE_ERROR/kappa_T); the last
        thermodynamics (measured with the final parameters)."""
        calibration, targets = self.calibration, self.targets
        tolerance = CRITERIA[Property.PRESSURE].tolerance * targets["bulk_modulus"]
        for round_ in range(rounds):
            self.stage(f"Round {len(self.pressures) + 1} of f_cut and pi0: f_cut tuned so that n-bar = n0 "
                       f"({calibration.estimator}), then P measured")
            scaling = calibration.tune_cutoff_scaling(first_iterations if round_ == 0 else 2)
            thermo = self.thermodynamics()
            pressure = thermo["pressure"]
            self.pressures.append((calibration.parameters.reference_pressure, pressure))
            self.report(f"  f_cut = {scaling:.4f}, pi0 = {calibration.parameters.reference_pressure:.6g} "
                        f"kJ/mol/nm^3: P = {mpa(pressure.value):.4g} +- {mpa(pressure.error):.2g} MPa (P0 = "
                        f"{mpa(targets['pressure']):.4g})")
            if abs(pressure.value - targets["pressure"]) <= max(tolerance, 2 * pressure.error):
                break
            if round_ + 1 < rounds:
                shift = pressure_step(self.pressures, targets["pressure"])
                calibration.correct_reference_pressure(calibration.parameters.reference_pressure + shift)
                self.report(f"  pi0 moved by {shift:.4g} kJ/mol/nm^3 ({mpa(shift):.4g} MPa)")
        return thermo

    def heat_capacity(self, thermo):
        """C_V matched to the fluid's c_v (Calibration.match_heat_capacity)."""
        calibration, targets = self.calibration, self.targets
        self.stage("Heat capacity: C_V so that the model's c_v (C_V + k_B + 3 k_B/2 + c_U, c_U from the fluctuation "
                   "of U) is the fluid's")
        self.measured["heat_capacity_mapped"] = thermo["heat_capacity"]
        self.failures += Miss.of_iteration(Property.HEAT_CAPACITY,
                                           calibration.match_heat_capacity(targets["heat_capacity"]))
        kb = KB
        configurational = thermo["configurational_heat_capacity"]
        self.report(f"  c_v = {thermo['heat_capacity'].value / kb:.4g} k_B per particle (c_U = "
                    f"{configurational.value / kb:.3g} +- {configurational.error / kb:.2g} k_B), target "
                    f"{targets['heat_capacity'] / kb:.4g} k_B: C_V {self.mapped.heat_capacity / kb:.4g} -> "
                    f"{calibration.parameters.heat_capacity / kb:.4g} k_B")

    def bulk_modulus(self, thermo):
        """B_T iterated on n dP/dn; then f_cut and pi0 again if B_T moved, or the thermodynamics measured again if
        only C_V did (and f_cut and pi0 again if the pressure of a law that depends on temperature moved past
        RETUNE_PRESSURE). Returns the last thermodynamics."""
        calibration, plan = self.calibration, self.plan
        responses = []

        def measure_bulk_modulus():
            modulus, response = calibration.bulk_modulus()
            responses.append(response)
            return modulus

        self.stage(f"Bulk modulus: B_T iterated on n dP/dn (boxes at n0 (1 -+ {plan.density_step:g}))")
        before = calibration.parameters.bulk_modulus
        bulk, runs, failure = calibration.iterate("bulk_modulus", measure_bulk_modulus, self.targets["bulk_modulus"],
                                                  Property.BULK_MODULUS.quantity, plan.bulk_runs)
        self.failures += Miss.of_iteration(Property.BULK_MODULUS, failure)
        kept = [x for x, _ in runs].index(calibration.parameters.bulk_modulus)   # (the response of the B_T kept)
        self.measured.update(bulk=bulk, bulk_runs=runs, response=responses[kept])
        self.bulk_parameters = equilibrium(calibration.parameters)   # (only B_T moved in the iteration)
        if calibration.parameters.bulk_modulus != before:   # the structure and the pressure follow B_T
            return self.pressure_rounds(2, 2)
        if calibration.parameters.heat_capacity != self.mapped.heat_capacity:
            self.stage("The thermodynamics measured again with the calibrated C_V")
            thermo = self.thermodynamics()
            # A law that depends on temperature feels C_V in the structure (its entropy term is dressed by 1 + k_B/C_V,
            # docs/theory.md section 11): where the pressure moved past half its tolerance, f_cut and pi0 again.
            miss = abs(thermo["pressure"].value - self.targets["pressure"]) / self.targets["bulk_modulus"]
            if calibration.parameters.thermal_pressure is not None and miss > RETUNE_PRESSURE:
                return self.pressure_rounds(2, 2)
        return thermo

    def thermal_expansion(self, seed):
        """beta iterated on the measured (dP/dT)_V, for a law that depends on temperature (thermal_expansion_rows)."""
        self.measured["expansion_rows"] = []
        if self.calibration.parameters.thermal_pressure is not None:
            self.stage(f"Thermal expansion: (dP/dT)_V at n0, runs at T0 -+ {100 * expansion.DELTA:g}%; beta iterated "
                       f"on the measured slope (at most {EXPANSION_RUNS} measurements)")
            history = []
            self.measured["expansion_rows"] = thermal_expansion_rows(
                self.calibration, self.plan, self.calibration.platform.getName(), seed, self.report, history)
            if history:
                self.expansion = (equilibrium(self.calibration.parameters), history[-1])

    def transport(self):
        """The friction and the heat conduction iterated on the wave decays (a fluid that expands: the conduction on
        the steady heat flux), then each measured again, and corrected once, by the steady flows."""
        calibration, plan, targets = self.calibration, self.plan, self.targets
        self.stage(f"Shear viscosity: friction iterated on decaying transverse waves ({plan.replicas} per run)")
        viscosity, viscosity_runs, viscosity_failure = calibration.iterate(
            "friction", calibration.shear_viscosity, targets["shear_viscosity"], "shear viscosity", plan.transport_runs)
        # A fluid that expands: its energy wave at fixed volume is also a sound wave, and the wave's decay read argon's
        # conductivity at 11x whatever kappa was (docs/thermal.md); kappa is iterated on the steady heat flux instead.
        expanding = calibration.parameters.thermal_pressure is not None
        conductivity = conductivity_runs = conductivity_failure = None
        if not expanding:
            self.stage(f"Thermal conductivity: heat conduction iterated on decaying energy waves ({plan.replicas} "
                       f"per run)")
            conductivity, conductivity_runs, conductivity_failure = calibration.iterate(
                "heat_conduction", calibration.thermal_conductivity, targets["thermal_conductivity"],
                "thermal conductivity", plan.transport_runs)
        self.stage(f"Shear viscosity by periodic Poiseuille flow ({plan.replicas} runs, {plan.steady_cells} cells)")
        poiseuille, wave, failure = calibration.steady_correction(
            "friction", calibration.steady_viscosity, calibration.shear_viscosity, viscosity_runs,
            targets["shear_viscosity"], "shear viscosity", viscosity_failure)
        self.failures += Miss.of_iteration(Property.VISCOSITY_FLOW, failure)
        viscosity = wave or viscosity
        if expanding:
            self.stage(f"Thermal conductivity: heat conduction iterated on a steady heat flux between slabs "
                       f"({plan.replicas} runs, {plan.steady_cells} cells; the energy wave of a fluid that expands is "
                       f"also a sound wave)")
            heat_flux, conductivity_runs, failure = calibration.iterate(
                "heat_conduction", calibration.steady_conductivity, targets["thermal_conductivity"],
                "thermal conductivity", plan.transport_runs)
        else:
            self.stage(f"Thermal conductivity by a steady heat flux between slabs ({plan.replicas} runs, "
                       f"{plan.steady_cells} cells)")
            heat_flux, wave, failure = calibration.steady_correction(
                "heat_conduction", calibration.steady_conductivity, calibration.thermal_conductivity,
                conductivity_runs, targets["thermal_conductivity"], "thermal conductivity", conductivity_failure)
            conductivity = wave or conductivity
        self.failures += Miss.of_iteration(Property.CONDUCTIVITY_HEAT_FLUX, failure)
        self.measured.update(viscosity=viscosity, viscosity_runs=viscosity_runs, poiseuille=poiseuille,
                             conductivity=conductivity, conductivity_runs=conductivity_runs, heat_flux=heat_flux,
                             expanding=expanding)

    def sound(self, thermo):
        """The speed of sound derived from the written model's n dP/dn, (dP/dT)_n and c_v (report.speed_of_sound),
        and, unless the plan leaves it out (--quick), measured by a standing sound wave (Calibration.sound_speed) on
        the written model, its run as long as the derived speed says."""
        calibration, m = self.calibration, self.measured
        m["sound"] = speed_of_sound(calibration.parameters, m["bulk"], m["thermal_pressure"],
                                    thermo["heat_capacity"].value)
        m["sound_wave"] = None
        if self.plan.sound_wave:
            self.stage(f"Speed of sound by a standing sound wave ({self.plan.replicas} runs, "
                       f"{self.plan.sound_periods:g} periods; derived: {1e3 * m['sound'].value:.1f} m/s)")
            m["sound_wave"] = calibration.sound_speed(m["sound"].value)

    def thermodynamics(self):
        """Calibration.thermodynamics at n0, its pressure to PRESSURE_ERROR/kappa_T, recording the parameters."""
        thermo = self.calibration.thermodynamics(pressure_error=PRESSURE_ERROR * self.targets["bulk_modulus"])
        self.thermo_parameters = equilibrium(self.calibration.parameters)
        return thermo

    def written_model(self, thermo, seed):
        """Every equilibrium property of the report measured on the parameters calibrate writes: the thermodynamics
        and n dP/dn measured again where a later stage moved a parameter that the equilibrium depends on (f_cut and
        pi0 after B_T, beta after both), and the thermal pressure coefficient (dP/dT)_n that the speed of sound needs:
        the thermal expansion's last measurement, or, for a law without a thermal pressure, measured here
        (expansion.thermal_pressure_coefficient: runs at T0 -+ 8%). Returns the thermodynamics."""
        calibration, final = self.calibration, equilibrium(self.calibration.parameters)
        again = [name for name, measured in (("the thermodynamics", self.thermo_parameters), ("n dP/dn",
                                                                                           self.bulk_parameters))
                 if measured != final]
        if again:
            self.stage(f"The written model: {' and '.join(again)} measured again (a later stage moved f_cut, pi0 or "
                       f"beta)")
        if self.thermo_parameters != final:
            thermo = self.thermodynamics()
        if self.bulk_parameters != final:
            bulk, response = calibration.bulk_modulus()
            self.report(f"  n dP/dn = {mpa(bulk.value):.5g} +- {mpa(bulk.error):.2g} MPa (the B_T iteration's, before "
                        f"the last stages: {mpa(self.measured['bulk'].value):.5g} +- "
                        f"{mpa(self.measured['bulk'].error):.2g}), response {response.value:.3f} +- "
                        f"{response.error:.3f}")
            self.measured.update(bulk=bulk, response=response)
            self.bulk_parameters = final
        if self.expansion is not None and self.expansion[0] == final:
            slope = self.expansion[1]
            per_mpa = 1 / expansion.MPA_PER_OPENMM_PRESSURE
            thermal = Measured(slope.slope * per_mpa, slope.slope_error * per_mpa)
        else:
            self.stage(f"Thermal pressure (dP/dT)_n at n0 for the speed of sound: runs at T0 -+ "
                       f"{100 * expansion.DELTA:g}%")
            thermal = calibration.thermal_pressure(seed)
        self.report(f"  (dP/dT)_n = {mpa(thermal.value):.4g} +- {mpa(thermal.error):.2g} MPa/K (kinetic n0 k_B: "
                    f"{mpa(calibration.parameters.density * KB):.4g})")
        self.measured["thermal_pressure"] = thermal
        return thermo

    def run(self, seed):
        """Every stage in order; the last thermodynamics and the first round's (the mapped pressure)."""
        thermo = mapped = self.pressure_rounds(self.plan.pressure_rounds, self.plan.tuning_iterations)
        if len(self.pressures) > 1:
            mapped = {"pressure": self.pressures[0][1]}
        self.heat_capacity(thermo)
        thermo = self.bulk_modulus(thermo)
        self.thermal_expansion(seed)
        thermo = self.written_model(thermo, seed)
        self.transport()
        self.sound(thermo)
        return thermo, mapped


def calibrate(parameters, estimator="VB", plan=Plan(), platform="Reference", seed=1, criteria=CRITERIA, workers=1,
              progress=None, report=print):
    """Calibrate the model ``parameters`` (a GenDPDEParameters: a mapping, or a model file's,
    fluid_files.load_parameters; any law of the table: the handles pi0, B_T and beta act on every law through
    ModelParameters.replace and with_thermal_pressure, a law that does not extend Tait fitted again to them) with
    ``estimator`` on ``platform`` (a name) by the stages of the module docstring (each a method of Stages), runs of
    ``plan`` (QUICK: --quick's), ``workers`` processes for the replicas (the CPU platform), and judge the results by
    ``criteria`` (results.CRITERIA, or QUICK_CRITERIA). Lines go to ``report(text)``, the steps to ``progress``
    (cli.progress.Progress) if given. Returns a CalibrationResult; a stage that fails raises StageFailure."""
    parameters = parameters.for_estimator(estimator)
    calibration = Calibration(parameters, estimator, plan, platform, seed=seed, report=report, progress=progress,
                              workers=workers)
    stages = Stages(calibration, report)
    try:
        thermo, mapped = stages.run(seed)
    except (openmm.OpenMMException, ValueError) as error:
        raise StageFailure(stages.stages[-1] if stages.stages else "setting up", error) from error
    stages.stage(f"Done: {calibration.runs} runs")
    rows = calibration_rows(stages, thermo, mapped)
    results, judged = {}, {}
    for row, target, measured in rows:
        name = row.label if isinstance(row, Property) else row
        results[name] = {"target": target, "model": measured.value, "error": measured.error,
                         "samples": measured.samples}
        if isinstance(row, Property):
            judged[row] = results[name]
    missed = misses(judged, criteria) + stages.failures
    wall_time = time.monotonic() - stages.started
    record = calibration_record(stages, results, missed, wall_time)
    return CalibrationResult(stages.mapped, calibration.parameters, estimator, plan, rows, results, missed, record,
                             calibration.runs, calibration.melt_steps, wall_time, stages.measured["expanding"])


def equilibrium(parameters):
    """The parameters that a model's equilibrium depends on: all but the friction and the heat conduction, which
    set its dynamics only (GenDPDE's equilibrium distribution does not depend on them): two models with equal
    equilibrium() have the same thermodynamics."""
    return dataclasses.replace(parameters, friction=1.0, heat_conduction=1.0)


__all__ = ["CalibrationResult", "Stages", "StageFailure", "calibrate", "estimated_steps", "thermal_expansion_rows"]
