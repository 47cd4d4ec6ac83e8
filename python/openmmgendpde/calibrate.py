"""Set up any fluid from its physical properties and measure the model back (`calibrate`; docs/fluids.md).

1. The mapping (openmmgendpde.fluid.coarse_grain) gives every parameter; they are printed in OpenMM and reduced units.
2. V-B's f_cut is tuned until the mean particle density n-bar equals n0 (as tune-fcut does for argon): on frames of an
   isoenergetic run n-bar is evaluated at f_cut and at two trial values around it (f_cut (1 -+ 2%)), and every step
   follows half that slope, since the structure follows f_cut and halves its effect (a secant between runs is too
   noisy at the lengths of --quick; V-A has no f_cut).
3. With the tuned model, measured side by side with the targets, each with its standard error (block averages, or
   the scatter of independent replicas):
   - n-bar, the virial pressure P (kinetic term included), the kinetic temperature and the harmonic mean of theta_i;
     then pi0 is shifted by P0 - P (the particles' density fluctuations raise the mean Tait pressure) and all of
     these measured again;
   - the bulk modulus n dP/dn, from runs in boxes at n0 (1 -+ delta) (a central difference), and from the same runs
     how the particle densities follow the true one, (n/n-bar) d n-bar/d n (1 would let the Tait modulus through);
   - the shear viscosity, from the decay of a transverse velocity wave v_x = V0 sin(k z) (k = 2 pi/L) laid on the
     equilibrium velocities: its amplitude decays as exp(-eta k^2 t/(n0 m)) (momentum-conserving dynamics);
   - the thermal conductivity, from the decay of a wave of the internal temperatures theta = T0 (1 + e sin(k z)):
     the energy wave decays as exp(-lambda k^2 t/(n0 c)), c = C_V + 3 k_B/2 the heat capacity per particle at
     fixed density (the Tait energy does not depend on temperature); the amplitude is read from sum eps_i + K_i.
   Where the model cannot reach a target, the output says so: the bulk modulus that a cutoff and f_cut allow differ
   from 1/kappa_T because the particle densities n_i do not follow the true density one to one.
4. The results are judged (CRITERIA): n-bar within 2% of n0, P within 0.01/kappa_T of P0 after the shift of pi0,
   both temperatures within 2% of T0, each transport coefficient within a factor 2 of its target, each allowing
   2 standard errors of the measurement as well. A calibration that misses one of them says which, by how much,
   and exits with status 1 (after writing --json). The bulk modulus is reported, not judged (see above).

--quick: 500 particles and short runs (a functional check in about a minute); the default: 2048 particles.
"""

import dataclasses
import json
import math
import sys

import numpy as np
import openmm
from openmm import unit

from . import ESTIMATOR_NAMES, GenDPDEIntegrator
from .cli import add_platform, platform_description
from .fluid import ARGON, WATER, CONDUCTIVITY, VISCOSITY, coarse_grain
from .statistics import block_average
from .thermodynamics import ThermodynamicProbe
from .tune_fcut import mean_density_on_frames
from .units import BOLTZMANN

FLUIDS = {"water": WATER, "argon": ARGON}
#: The run-to-run response of n-bar to f_cut over the response on frames at fixed structure (measured: see
#: Calibration.tune_cutoff_scaling).
STRUCTURE_RESPONSE = 0.5
KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


@dataclasses.dataclass(frozen=True)
class Plan:
    """Run lengths (steps of dt* = time_step in the model's reduced time)."""
    particles: int = 2048
    time_step: float = 0.01
    melt: int = 1000              # Isothermal steps before each measurement run
    frames: int = 200             # frames (every `interval` steps) per f_cut iteration and per thermodynamic run
    interval: int = 50
    tuning_iterations: int = 4
    density_step: float = 0.05    # delta of the bulk-modulus boxes
    replicas: int = 4             # per transport coefficient
    wave_steps: int = 1500        # steps of a decaying wave
    wave_interval: int = 10


QUICK = Plan(particles=500, melt=400, frames=60, interval=25, tuning_iterations=3, replicas=3, wave_steps=600)


@dataclasses.dataclass
class Measured:
    value: float
    error: float


#: What a calibration must reach, by row of the results: (kind, tolerance). 'relative': |model/target - 1| <= the
#: tolerance; 'pressure': |P - P0| <= the tolerance times the bulk modulus 1/kappa_T (P0 may be ~0); 'factor':
#: model/target within [1/tolerance, tolerance] (gamma and kappa come from kinetic theory and are not iterated:
#: docs/fluids.md measures 0.70 to 1.37 of the targets). Each range is widened by 2 standard errors of the model.
CRITERIA = {
    "density n-bar (nm^-3)": ("relative", 0.02),
    "pressure, pi0 shifted (MPa)": ("pressure", 0.01),
    "kinetic temperature (K)": ("relative", 0.02),
    "harmonic mean of theta_i (K)": ("relative", 0.02),
    "shear viscosity (mPa s)": ("factor", 2.0),
    "thermal conductivity (W/(m K))": ("factor", 2.0),
}
BULK_MODULUS_ROW = "bulk modulus n dP/dn (MPa)"


def comparison(name, target, model, bulk_modulus):
    """How ``model`` compares with ``target`` in the row ``name``: (P - P0) kappa_T for a pressure (P0 may be ~0),
    else model/target."""
    if name.startswith("pressure"):
        return f"(P - P0) kappa_T = {(model - target) / bulk_modulus:.4f}"
    return f"model/target = {model / target:.3f}"


def misses(results):
    """One line for each result of CRITERIA that missed it, saying by how much; ``results`` as run returns them
    (row name -> target, model, error; the pressures in the unit of the bulk modulus row's target)."""
    bulk_modulus = results[BULK_MODULUS_ROW]["target"]
    lines = []
    for name, (kind, tolerance) in CRITERIA.items():
        target, model, error = (results[name][key] for key in ("target", "model", "error"))
        if kind == "factor":
            low, high = target / tolerance, target * tolerance
        else:
            width = tolerance * (bulk_modulus if kind == "pressure" else abs(target))
            low, high = target - width, target + width
        if not low - 2 * error <= model <= high + 2 * error:
            lines.append(f"{name}: {model:.5g} +- {error:.2g} against the target {target:.5g} "
                         f"({comparison(name, target, model, bulk_modulus)}); allowed {low:.5g} to {high:.5g}, "
                         f"widened by 2 standard errors")
    return lines


class Calibration:
    """The simulations of one fluid model on one platform."""

    def __init__(self, parameters, estimator, plan, platform, seed=1, report=print):
        self.parameters = parameters
        self.estimator = estimator
        self.plan = plan
        self.platform = openmm.Platform.getPlatformByName(platform)
        self.seed = seed
        self.report = report

    def _model(self, density=None):
        self.seed += 1
        return self.parameters.liquid(self.plan.particles, self.estimator, mode=GenDPDEIntegrator.Isothermal,
                                      time_step=self.plan.time_step, seed=self.seed, density=density)

    def _equilibrated(self, density=None):
        """A Context melted with the DPD thermostat at T0, then isoenergetic with theta_i drawn at T0."""
        model = self._model(density)
        context = openmm.Context(model.system, model.integrator, self.platform)
        context.setPositions(model.positions)
        context.setVelocitiesToTemperature(self.parameters.temperature, self.seed)
        model.integrator.step(self.plan.melt)
        model.integrator.setMode(GenDPDEIntegrator.Isoenergetic)
        model.integrator.setInternalEnergiesToTemperature(self.parameters.temperature, self.seed)
        model.integrator.step(self.plan.melt // 2)
        return model, context

    def tune_cutoff_scaling(self):
        """f_cut such that n-bar = n0 (V-B); returns it (or the given one for V-A). Each run measures n-bar on its
        frames at f_cut and at f_cut (1 -+ 2%); the step to the next f_cut uses half that slope: the structure
        follows f_cut and halves its effect (water, 2048 particles: n-bar moved by 2.7 nm^-3 per unit of f_cut from
        run to run where the frames, structure held fixed, said 5.1), and a secant between runs is too noisy at
        the lengths of --quick."""
        if self.estimator == "VA":
            return self.parameters.cutoff_scaling
        scaling = self.parameters.cutoff_scaling
        for iteration in range(self.plan.tuning_iterations):
            self.parameters = self.parameters.with_cutoff_scaling(scaling)
            model, context = self._equilibrated()
            frames = []
            for _ in range(self.plan.frames):
                model.integrator.step(self.plan.interval)
                frames.append(model_positions(context))
            trial = [scaling * 0.98, scaling * 1.02]
            densities = [mean_density_on_frames(model.force, context, frames, f, units=None) for f in trial]
            current = mean_density_on_frames(model.force, context, frames, scaling, units=None)
            slope = STRUCTURE_RESPONSE*(densities[1] - densities[0])/(trial[1] - trial[0])
            next_scaling = scaling + (self.parameters.density - current)/slope
            self.report(f"  f_cut iteration {iteration + 1}: n-bar = {current:.4f} nm^-3 at f_cut = {scaling:.4f} "
                        f"(n0 = {self.parameters.density:.4f}), d n-bar/d f_cut = {slope:.3f} nm^-3: f_cut -> "
                        f"{next_scaling:.4f}")
            scaling = next_scaling
        self.parameters = self.parameters.with_cutoff_scaling(scaling)
        return scaling

    def thermodynamics(self, density=None):
        """Block averages of n-bar, P, T_kin and T_harm of an isoenergetic run."""
        model, context = self._equilibrated(density)
        probe = ThermodynamicProbe(model.system)
        samples = []
        for _ in range(self.plan.frames):
            model.integrator.step(self.plan.interval)
            state = context.getState(getEnergy=True, getVelocities=True)
            samples.append(probe.sample(state, context, model.integrator))
        def average(name, unit_):
            values = [getattr(s, name).value_in_unit(unit_) for s in samples]
            result = block_average(values, 5, name=f"{name} at n = {density or self.parameters.density:.4g} nm^-3")
            return Measured(result.mean, result.standard_error)
        return {
            "density": average("density", unit.nanometer**-3),
            "pressure": average("pressure", unit.kilojoule_per_mole / unit.nanometer**3),
            "kinetic_temperature": average("kinetic_temperature", unit.kelvin),
            "harmonic_temperature": average("harmonic_temperature", unit.kelvin),
        }

    def correct_reference_pressure(self, measured_pressure, target_pressure):
        """pi0 shifted by P0 - P: with n-bar = n0 the particles' density fluctuations raise <pi(n_i)> above pi(n0)
        (pi is convex: by ~gamma_T (gamma_T - 1) B_T Var(n_i)/(2 n0^2)), which a constant shift of pi0 removes."""
        shift = target_pressure - measured_pressure
        self.parameters = dataclasses.replace(self.parameters,
                                              reference_pressure=self.parameters.reference_pressure + shift)
        return shift

    def bulk_modulus(self):
        """n dP/dn at n0 by a central difference between boxes at n0 (1 -+ delta), and the response of the particle
        densities, (n0/n-bar) d n-bar/d n: 1 if the n_i followed the true density n, so that the Tait pressure's
        n dpi/dn = gamma_T B_T = 1/kappa_T reached the fluid."""
        delta = self.plan.density_step
        low = self.thermodynamics(self.parameters.density * (1 - delta))
        high = self.thermodynamics(self.parameters.density * (1 + delta))
        value = (high["pressure"].value - low["pressure"].value) / (2 * delta)
        modulus = Measured(value, math.hypot(high["pressure"].error, low["pressure"].error) / (2 * delta))
        mean = (high["density"].value + low["density"].value) / 2
        response = Measured((high["density"].value - low["density"].value) / (2 * delta * mean),
                            math.hypot(high["density"].error, low["density"].error) / (2 * delta * mean))
        return modulus, response

    def _wave_rate(self, amplitude_of, perturb):
        """The decay rate (1/ps) of a wave: the replicas' amplitudes averaged, then a least-squares line through
        log(amplitude) over the times where the mean amplitude exceeds 1/e^2 of its start; error from the replicas'
        individual rates."""
        rates, curves = [], []
        for _ in range(self.plan.replicas):
            model, context = self._equilibrated()
            edge = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
            k = 2 * math.pi / edge
            perturb(model, context, k)
            times, amplitudes = [], []
            for n in range(self.plan.wave_steps // self.plan.wave_interval + 1):
                if n:
                    model.integrator.step(self.plan.wave_interval)
                state = context.getState(getPositions=True, getVelocities=True, getEnergy=True)
                times.append(state.getTime().value_in_unit(unit.picosecond))
                amplitudes.append(amplitude_of(model, context, state, k))
            times, amplitudes = np.array(times) - times[0], np.array(amplitudes)
            curves.append(amplitudes)
            rates.append(_decay_rate(times, amplitudes))
        mean_rate = _decay_rate(times, np.mean(curves, axis=0))
        return mean_rate, float(np.std(rates, ddof=1) / math.sqrt(len(rates))), k

    def shear_viscosity(self):
        """eta from the decay of v_x = V0 sin(k z), V0 = the thermal velocity sqrt(k_B T0/m)."""
        p = self.parameters
        v0 = math.sqrt(KB * p.temperature / p.mass)

        def perturb(model, context, k):
            z = model_positions(context)[:, 2]
            velocities = context.getState(getVelocities=True).getVelocities(asNumpy=True).value_in_unit(
                unit.nanometer / unit.picosecond)
            velocities[:, 0] += v0 * np.sin(k * z)
            context.setVelocities(velocities)

        def amplitude(model, context, state, k):
            z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
            vx = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[:, 0]
            return 2 * np.mean(vx * np.sin(k * z))

        rate, error, k = self._wave_rate(amplitude, perturb)
        mass_density = p.density * p.mass
        return Measured(rate * mass_density / k**2, error * mass_density / k**2)

    def thermal_conductivity(self):
        """lambda from the decay of theta_i = T0 (1 + 0.2 sin(k z_i)), read from the energy wave sum (eps_i + K_i)."""
        p = self.parameters
        heat_capacity = p.heat_capacity + 1.5 * KB

        def perturb(model, context, k):
            z = model_positions(context)[:, 2]
            model.integrator.setParticleTemperatures(list(p.temperature * (1 + 0.2 * np.sin(k * z))))

        def amplitude(model, context, state, k):
            z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
            v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
            kinetic = 0.5 * p.mass * np.sum(v * v, axis=1)
            energies = np.asarray(model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))
            return 2 * np.mean((energies + kinetic) * np.sin(k * z))

        rate, error, k = self._wave_rate(amplitude, perturb)
        factor = p.density * heat_capacity / k**2
        return Measured(rate * factor, error * factor)


def model_positions(context):
    return context.getState(getPositions=True).getPositions(asNumpy=True).value_in_unit(unit.nanometer)


def _decay_rate(times, amplitudes):
    """Least-squares slope of -log(amplitude) over the leading times where the amplitude exceeds e^-2 of its start
    (later the thermal noise dominates)."""
    start = amplitudes[0]
    keep = np.nonzero(amplitudes / start < math.exp(-2))[0]
    end = keep[0] if len(keep) else len(amplitudes)
    end = max(end, 3)
    slope = np.polyfit(times[:end], np.log(np.abs(amplitudes[:end] / start)), 1)[0]
    return -slope


def run(arguments):
    fluid = FLUIDS[arguments.fluid]
    neighbors = arguments.neighbors if arguments.cutoff is None else None
    cutoff = None if arguments.cutoff is None else arguments.cutoff * unit.nanometer
    plan = QUICK if arguments.quick else Plan()
    if arguments.particles is not None:
        plan = dataclasses.replace(plan, particles=arguments.particles)
    try:   # every argument checked before the runs: a model built once checks the particles against the cutoff
        parameters = coarse_grain(fluid, arguments.molecules_per_particle, neighbors=neighbors, cutoff=cutoff)
        parameters.liquid(plan.particles, arguments.estimator)
    except ValueError as error:
        raise SystemExit(f"error: calibrate: {error}")
    print(f"{fluid.name}: {arguments.molecules_per_particle:g} molecules per particle, {parameters.neighbors:.1f} "
          f"neighbours within R, {arguments.estimator}, {plan.particles} particles, {platform_description(arguments)}")
    print("Parameters (OpenMM units; reduced: mass of a particle, L = n0^(-1/3), energy L^3/kappa_T, k_B = 1):")
    reduced = parameters.reduced()
    rows = [("n0 (nm^-3)", parameters.density, "n0*"), ("pi0 (kJ/mol/nm^3)", parameters.reference_pressure, "pi0*"),
            ("B_T (kJ/mol/nm^3)", parameters.bulk_modulus, "B_T*"), ("gamma_T", parameters.tait_exponent, "gamma_T"),
            ("cutoff R (nm)", parameters.cutoff, "R*"), ("friction (amu/ps)", parameters.friction, "gamma*"),
            ("heat conduction (kJ K/(mol ps))", parameters.heat_conduction, "kappa*"),
            ("C_V per particle (kJ/mol/K)", parameters.heat_capacity, "C_V*"),
            ("mass (amu)", parameters.mass, None), ("T0 (K)", parameters.temperature, "T0*")]
    print("| parameter | value | reduced |\n|---|---|---|")
    for name, value, key in rows:
        print(f"| {name} | {value:.6g} | {reduced[key]:.6g} |" if key else f"| {name} | {value:.6g} | 1 |")
    calibration = Calibration(parameters, arguments.estimator, plan, arguments.platform, seed=arguments.seed)
    print(f"Tuning f_cut ({arguments.estimator}) so that n-bar = n0:")
    scaling = calibration.tune_cutoff_scaling()
    print(f"f_cut = {scaling:.4f} (first estimate {parameters.cutoff_scaling:.4f})")
    targets = calibration.parameters.targets()
    mapped = calibration.thermodynamics()
    shift = calibration.correct_reference_pressure(mapped["pressure"].value, targets["pressure"])
    print(f"pi0 shifted by {shift:.4g} kJ/mol/nm^3 ({_mpa(shift):.4g} MPa) so that P = P0: pi0 = "
          f"{calibration.parameters.reference_pressure:.6g} kJ/mol/nm^3")
    thermo = calibration.thermodynamics()
    bulk, response = calibration.bulk_modulus()
    viscosity = calibration.shear_viscosity()
    conductivity = calibration.thermal_conductivity()
    target_rows = [
        ("density n-bar (nm^-3)", targets["density"], thermo["density"]),
        ("pressure, pi0 as mapped (MPa)", _mpa(targets["pressure"]), _scaled(mapped["pressure"], _mpa(1.0))),
        ("pressure, pi0 shifted (MPa)", _mpa(targets["pressure"]), _scaled(thermo["pressure"], _mpa(1.0))),
        ("bulk modulus n dP/dn (MPa)", _mpa(targets["bulk_modulus"]), _scaled(bulk, _mpa(1.0))),
        ("particle-density response (n/n-bar) dn-bar/dn", 1.0, response),
        ("kinetic temperature (K)", targets["temperature"], thermo["kinetic_temperature"]),
        ("harmonic mean of theta_i (K)", targets["temperature"], thermo["harmonic_temperature"]),
        ("shear viscosity (mPa s)", _mpa_s(targets["shear_viscosity"]), _scaled(viscosity, _mpa_s(1.0))),
        ("thermal conductivity (W/(m K))", _w_mk(targets["thermal_conductivity"]),
         _scaled(conductivity, _w_mk(1.0))),
    ]
    print("Targets and what the model gives (standard errors):")
    print("| property | target | model | model/target |\n|---|---|---|---|")
    results = {}
    bulk_target = _mpa(targets["bulk_modulus"])
    for name, target, measured in target_rows:
        print(f"| {name} | {target:.5g} | {measured.value:.5g} +- {measured.error:.2g} | "
              f"{comparison(name, target, measured.value, bulk_target).removeprefix('model/target = ')} |")
        results[name] = {"target": target, "model": measured.value, "error": measured.error}
    missed = misses(results)
    print("Notes: the bulk modulus that the model reaches is set by how the particle densities n_i follow the true "
          "density (V-B's f_cut is tuned at n0 only), not by B_T alone; the transport coefficients include the "
          "kinetic and conservative contributions that the kinetic-theory mapping of gamma and kappa leaves out.")
    if arguments.json:
        with open(arguments.json, "w") as stream:
            json.dump({"fluid": fluid.name, "molecules_per_particle": arguments.molecules_per_particle,
                       "estimator": arguments.estimator, "particles": plan.particles, "cutoff_scaling": scaling,
                       "reference_pressure_shift": shift, "parameters": reduced,
                       "calibrated": calibration.parameters.reduced(), "results": results, "missed": missed},
                      stream, indent=1)
    if missed:
        print(f"error: calibrate: the calibration failed, {len(missed)} of the judged results missed (CRITERIA, "
              f"docs/fluids.md):\n  " + "\n  ".join(missed), file=sys.stderr)
        raise SystemExit(1)
    print(f"Every judged result within its tolerance ({', '.join(CRITERIA)}).")
    return results


def _mpa(value):
    """kJ/mol/nm^3 -> MPa."""
    return (value * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(
        unit.megapascal)


def _mpa_s(value):
    """amu/(nm ps) -> mPa s."""
    return (value * VISCOSITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.pascal * unit.second) * 1e3


def _w_mk(value):
    """kJ/(mol ps nm K) -> W/(m K)."""
    return (value * CONDUCTIVITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.watt / (unit.meter * unit.kelvin))


def _scaled(measured, factor):
    return Measured(measured.value * factor, measured.error * factor)


def add_arguments(parser):
    parser.add_argument("--fluid", choices=sorted(FLUIDS), default="water", help="the fluid (default water)")
    parser.add_argument("--molecules-per-particle", type=float, default=4.0,
                        help="coarse-graining level (default 4)")
    parser.add_argument("--neighbors", type=float, default=20.0,
                        help="particles within the cutoff at n0 (default 20), unless --cutoff is given")
    parser.add_argument("--cutoff", type=float, help="the cutoff R in nm (instead of --neighbors)")
    parser.add_argument("--estimator", choices=list(ESTIMATOR_NAMES.values()), default="VB",
                        help="the density estimator (default VB; VC is VB with free surfaces)")
    parser.add_argument("--particles", type=int, help="4 m^3 particles (default 2048; --quick 500)")
    parser.add_argument("--quick", action="store_true", help="500 particles and short runs (a functional check)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--json", help="also write the parameters and results to this JSON file")
    add_platform(parser)
    parser.set_defaults(run=run)
