"""The machinery of calibrate: a Calibration holds a model's parameters and measures them back (melts, thermodynamics,
the bulk modulus, the heat capacity, the transport coefficients by waves and steady flows), and iterates a parameter
on its measured response (iterate, steady_correction; pressure_step for pi0). The command, its stages and its report
are calibrate.py; the module docstring there says the method."""


import dataclasses
import math

import numpy as np
import openmm
from openmm import unit

from ..analysis.density import mean_density_on_frames
from ..analysis.statistics import correlated_mean
from ..analysis.thermodynamics import (
    ThermodynamicProbe,
    bath_heat_capacity,
    configurational_heat_capacity,
    heat_capacity_per_particle,
    self_diffusion,
)
from ..analysis.transport import heat_flux_conductivity, poiseuille_viscosity
from ..api import GenDPDEIntegrator, estimator_of
from ..internal import forked
from ..models.fluid import KB
from ..models.melting import switch_after_melting
from .results import (
    coverage,
)

#: The run-to-run response of n-bar to f_cut over the response on frames at fixed structure (measured: see
#: Calibration.tune_cutoff_scaling).
STRUCTURE_RESPONSE = 0.5


@dataclasses.dataclass(frozen=True)
class Plan:
    """Run lengths (steps of dt* = time_step in the model's reduced time)."""
    particles: int = 2048
    time_step: float = 0.01
    melt: int = 1000              # Isothermal steps before each measurement run, at least (Calibration.melt)
    melt_block: int = 500         # then blocks of this many steps until n-bar is stationary
    melt_limit: int = 8000        # ... or this many steps in all
    frames: int = 200             # frames (every `interval` steps) per f_cut iteration and per thermodynamic run
    interval: int = 50
    tuning_iterations: int = 4
    density_step: float = 0.05    # delta of the bulk-modulus boxes
    replicas: int = 4             # per transport coefficient
    wave_steps: int = 1500        # steps of a decaying wave, at least
    wave_decays: float = 2.0      # ... and this many decay times (from the target coefficient)
    pressure_rounds: int = 3      # rounds of (f_cut tuned, pressure measured, pi0 moved) at most
    bulk_runs: int = 3            # measurements of n dP/dn while iterating B_T, at most
    transport_runs: int = 4       # measurements per transport coefficient while iterating gamma or kappa, at most
    steady_cells: tuple = (4, 4, 16)   # the box of the waves and steady flows: FCC cells, elongated in z
    steady_time: float = 1.0      # their run lengths, as a multiple of transport.py's defaults


QUICK = Plan(particles=500, melt=400, melt_block=500, frames=60, interval=25, tuning_iterations=3, replicas=3,
             wave_steps=600, pressure_rounds=2, bulk_runs=2, transport_runs=3, steady_cells=(3, 3, 12), steady_time=0.4)


@dataclasses.dataclass
class Measured:
    """A measured value and its standard error; ``samples``: the independent samples the error rests on (N/g of
    a time series, or the replicas), None where it is derived from other measurements."""
    value: float
    error: float
    samples: float = None


#: The smallest C_V (kJ/mol/K) match_heat_capacity sets: k_B. Each eps_i/(k_B T) follows a Gamma law of shape
#: C_V/k_B + 1; below k_B the internal energies reach near zero often and the Ito term k_B/(2 C_V) of the
#: integrator's friction passes 1/2 (docs/integrator.md).
MIN_INTERNAL_HEAT_CAPACITY = KB


#: The tolerance of the iterations (relative to the target), widened to one standard error (_settled).
TOLERANCE = 0.05


#: The largest factor by which an iteration moves its parameter in one run.
MAX_STEP = 3.0


#: What to change when an iteration cannot reach its target (Calibration.iterate).
FAILURE_ADVICE = {
    "friction": "coarse-grain differently (molecules per particle) or change the neighbours within the cutoff",
    "heat_conduction": "coarse-grain differently (molecules per particle) or change the neighbours within the cutoff",
    "bulk_modulus": ("the particle densities do not follow the true density closely enough for B_T to reach the "
                     "fluid's compressibility; where the particles are under tension (pi0 < 0 without a background "
                     "pressure) give them one (fluid.background_pressure_for, docs/theory.md section 12), else use "
                     "more neighbours within the cutoff (docs/fluids.md)"),
}


class _StepCounter:
    """A progress that counts the steps (Calibration.side_by_side: a run's steps reach the bar from its process)."""

    def __init__(self):
        self.steps = 0

    def advance(self, steps):
        self.steps += steps


class Calibration:
    """The simulations of one fluid model on one platform."""

    def __init__(self, parameters, estimator, plan, platform, seed=1, report=print, progress=None, workers=1):
        self.parameters = parameters.for_estimator(estimator)   # (f_cut is tuned for it from this start)
        self.workers = workers   # processes for independent runs side by side (side_by_side(); the CPU platform only)
        self.estimator = estimator
        self.plan = plan
        self.platform = openmm.Platform.getPlatformByName(platform)
        self.seed = seed
        self.report = report
        self.progress = progress
        self.melt_steps = []   # the Isothermal steps each melt took to reach its criterion (melt())
        self._melted = {}      # box shape -> (positions in nm, density in nm^-3) of the last liquid melted in it
        self.runs = 0          # simulations run (Contexts made)
        #: c_U per particle (kJ/mol/K, Measured), from the last thermodynamics() at n0 (heat_capacity())
        self.configurational_heat_capacity = None

    def _step(self, integrator, steps):
        integrator.step(steps)
        if self.progress is not None:
            self.progress.advance(steps)

    def melt(self, model, context, first=True):
        """Isothermal steps until the structure is stationary: plan.melt steps, then blocks of plan.melt_block
        steps (n-bar, the mean particle density, sampled 10 times per block) until the last two block means differ
        by less than 2 standard errors of their difference (each from correlated_mean), at most plan.melt_limit
        steps in all. n-bar is the slow variable: water (4 molecules per particle, 500 particles) melted from the
        lattice takes ~2500 steps of dt* = 0.01 (25 time units) for n-bar to rise from 7.97 to its plateau 8.5
        nm^-3, while the potential energy settles within its noise in a few hundred; a fixed melt of 10 time units
        tuned f_cut on a structure still forming. Returns the steps taken and whether the criterion held."""
        block = max(10, self.plan.melt_block) // 10 * 10
        steps = self.plan.melt if first else 0
        self._step(model.integrator, steps)
        means = []
        while True:
            densities = []
            for _ in range(10):
                self._step(model.integrator, block // 10)
                densities.append(float(np.mean(model.force.getParticleDensities(context).value_in_unit(
                    unit.nanometer**-3))))
            steps += block
            means.append(correlated_mean(densities))
            if len(means) >= 2:
                difference = abs(means[-1].mean - means[-2].mean)
                if difference < 2 * math.hypot(means[-1].standard_error, means[-2].standard_error):
                    return steps, True
            if steps + block > self.plan.melt_limit:
                return steps, False

    def _model(self, density=None, cells=None):
        self.seed += 1
        return self.parameters.liquid(None if cells else self.plan.particles, self.estimator,
                                      mode=GenDPDEIntegrator.Isothermal, time_step=self.plan.time_step,
                                      seed=self.seed, density=density, cells=cells)

    def _start(self, model, density):
        """Where a run starts: the last melted liquid scaled to this density (its box is the model's, scaled
        alike), or the model's lattice for the first run."""
        box = _box_edges(model)
        if box not in self._melted:
            return model.positions
        positions, melted_density = self._melted[box]
        return positions * (melted_density / (density or self.parameters.density)) ** (1 / 3)

    def _equilibrated(self, density=None, cells=None):
        """A Context melted with the DPD thermostat at T0, then isoenergetic with theta_i drawn at T0 (a cube of
        plan.particles, or ``cells`` FCC cells)."""
        model = self._model(density, cells)
        context = model.context(self.platform, self.parameters.temperature, self.seed,
                                positions=self._start(model, density))
        self.runs += 1
        steps, stationary = self.melt(model, context, first=_box_edges(model) not in self._melted)
        self.melt_steps.append((steps, stationary))
        self._melted[_box_edges(model)] = (model_positions(context), density or self.parameters.density)
        switch_after_melting(model.integrator, self.parameters.temperature, self.seed)
        self._step(model.integrator, self.plan.melt // 2)
        return model, context

    def side_by_side(self, count, work):
        """[work(index) for index in range(count)], independent runs (each makes its own Contexts through
        _equilibrated): each from the same start (the liquids melted before the call) with the seeds one after
        another, in self.workers processes at once (forked.fork_map, one CPU thread each; the CPU platform only). A
        process's bookkeeping (runs, melts, the liquids it melted, its steps) comes back with its result: the
        calibration is the same as in one process, to the last bit on the CPU platform, whose results do not depend
        on its thread count."""
        seed, melted = self.seed, dict(self._melted)

        def one(index):
            self.seed, self._melted = seed + index, dict(melted)
            runs, melts = self.runs, len(self.melt_steps)
            progress, counter = self.progress, _StepCounter()
            self.progress = counter
            try:
                result = work(index)
            finally:
                self.progress = progress
            return result, (self.runs - runs, self.melt_steps[melts:], self._melted, counter.steps)

        workers = self.workers if self.platform.getName() == "CPU" else 1
        results = forked.fork_map(one, count, workers)
        for _, (runs, melts, _, steps) in results:
            if workers > 1:
                self.runs += runs
                self.melt_steps += melts
            if self.progress is not None:
                self.progress.advance(steps)
        self.seed, self._melted = seed + count, results[-1][1][2]
        return [result for result, _ in results]

    def replicas(self, cells):
        """The runner of plan.replicas replicas that transport.py's methods and the waves take: run(one) returns
        [one(index, model, context)] (side_by_side), each model equilibrated (_equilibrated) in a box of ``cells``
        from the last liquid melted in that box (the first time, one melted here from the lattice first)."""
        def run(one):
            if _box_edges(self.parameters.liquid(None, self.estimator, cells=cells)) not in self._melted:
                self._equilibrated(cells=cells)   # the lattice melted once here, not in every replica
            return self.side_by_side(self.plan.replicas, lambda index: one(index, *self._equilibrated(cells=cells)))
        return run

    def tune_cutoff_scaling(self, iterations=None):
        """f_cut such that n-bar = n0 (V-B); returns it (or the given one for an estimator that f_cut does not change,
        V-A). Each run measures n-bar on its frames at f_cut and at f_cut (1 -+ 2%); the step to the next f_cut uses
        half that slope: the structure follows f_cut and halves its effect (water, 2048 particles: n-bar moved by 2.7
        nm^-3 per unit of f_cut from run to run where the frames, structure held fixed, said 5.1), and a secant
        between runs is too noisy at the lengths of --quick."""
        if not estimator_of(self.estimator).reads_cutoff_scaling:
            return self.parameters.cutoff_scaling
        scaling = self.parameters.cutoff_scaling
        for iteration in range(self.plan.tuning_iterations if iterations is None else iterations):
            self.parameters = self.parameters.with_cutoff_scaling(scaling)
            model, context = self._equilibrated()
            frames = []
            for _ in range(self.plan.frames):
                self._step(model.integrator, self.plan.interval)
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

    def thermodynamics(self, density=None, pressure_error=None, diffusion=True):
        """The means of n-bar, P, T_kin and T_harm of an isoenergetic run, each with its standard error from
        correlated_mean (plan.frames frames), and with ``diffusion`` the self-diffusion coefficient (the frames'
        positions kept for it). With ``pressure_error`` (kJ/mol/nm^3) the run goes on, plan.frames/2 frames at a
        time, until the pressure's standard error is at most that, or 4 plan.frames frames."""
        model, context = self._equilibrated(density)
        probe = ThermodynamicProbe(model.system)
        samples, positions, potential = [], [], []

        def sample(frames):
            for _ in range(frames):
                self._step(model.integrator, self.plan.interval)
                state = context.getState(getEnergy=True, getVelocities=True, getPositions=diffusion)
                samples.append(probe.sample(state, context, model.integrator))
                potential.append(state.getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole))
                if diffusion:
                    positions.append(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer))

        def average(name, unit_):
            result = correlated_mean([getattr(s, name).value_in_unit(unit_) for s in samples])
            return Measured(result.mean, result.standard_error, result.independent_samples)

        sample(self.plan.frames)
        pressure_unit = unit.kilojoule_per_mole / unit.nanometer**3
        while (pressure_error is not None and average("pressure", pressure_unit).error > pressure_error
               and len(samples) < 4 * self.plan.frames):
            sample(self.plan.frames // 2)
        result = {
            "density": average("density", unit.nanometer**-3),
            "pressure": average("pressure", pressure_unit),
            "kinetic_temperature": average("kinetic_temperature", unit.kelvin),
            "harmonic_temperature": average("harmonic_temperature", unit.kelvin),
        }
        particles = model.system.getNumParticles()
        value, error, independent = configurational_heat_capacity(
            potential, result["harmonic_temperature"].value,
            bath_heat_capacity(particles, self.parameters.heat_capacity))
        result["configurational_heat_capacity"] = Measured(value / particles, error / particles, independent)
        if density is None:
            self.configurational_heat_capacity = result["configurational_heat_capacity"]
            result["heat_capacity"] = self.heat_capacity()
        if diffusion:
            result["self_diffusion"] = Measured(*self_diffusion(
                [s.time.value_in_unit(unit.picosecond) for s in samples], positions))
        return result

    def correct_reference_pressure(self, reference_pressure):
        """Set pi0 (kJ/mol/nm^3). With n-bar = n0 the particles' density fluctuations raise <pi(n_i)> above pi(n0)
        (pi is convex: by ~gamma_T (gamma_T - 1) B_T Var(n_i)/(2 n0^2)); a shift of pi0 moves the pressure of a
        fixed configuration one to one, but in equilibrium the structure follows pi0 and restores most of it
        until f_cut is tuned again (docs/fluids.md, "pi0 is a weak handle"): calibrate moves pi0 and tunes f_cut
        in rounds (pressure_step)."""
        self.parameters = self.parameters.replace(reference_pressure=reference_pressure)

    def bulk_modulus(self):
        """n dP/dn at n0 by a central difference between boxes at n0 (1 -+ delta), and the response of the particle
        densities, (n0/n-bar) d n-bar/d n: 1 if the n_i followed the true density n, so that the Tait pressure's
        n dpi/dn = gamma_T B_T = 1/kappa_T reached the fluid."""
        delta = self.plan.density_step
        low, high = self.side_by_side(2, lambda index: self.thermodynamics(
            self.parameters.density * (1 + (2 * index - 1) * delta), diffusion=False))
        value = (high["pressure"].value - low["pressure"].value) / (2 * delta)
        modulus = Measured(value, math.hypot(high["pressure"].error, low["pressure"].error) / (2 * delta))
        mean = (high["density"].value + low["density"].value) / 2
        response = Measured((high["density"].value - low["density"].value) / (2 * delta * mean),
                            math.hypot(high["density"].error, low["density"].error) / (2 * delta * mean))
        return modulus, response

    def heat_capacity(self):
        """The model's isochoric heat capacity per particle (kJ/mol/K, Measured), what a temperature change at fixed
        density costs in K + U + sum eps_i: C_V + k_B (each eps_i/(k_B T) follows a Gamma law of shape C_V/k_B + 1,
        docs/theory.md section 8) + 3 k_B/2 (the motion) + c_U, the configurational part, measured from the
        fluctuation of U (thermodynamics.configurational_heat_capacity) in the last thermodynamics() run at n0 (one
        is run if there was none). The Tait energy depends on the configuration only, but the configurations
        depend on the temperature: c_U = 0.40 k_B for argon (5 atoms per particle, 20 neighbours; d<U>/dT from
        runs at T0 (1 -+ 5%): 0.40 k_B, docs/fluids.md). c_U does not depend on C_V (the configurations are
        distributed at T whatever C_V is), so a new C_V changes c by as much."""
        if self.configurational_heat_capacity is None:
            self.thermodynamics(diffusion=False)
        configurational = self.configurational_heat_capacity
        value = heat_capacity_per_particle(self.parameters.heat_capacity, configurational.value)
        return Measured(value, configurational.error, configurational.samples)

    def match_heat_capacity(self, target):
        """Set C_V so that heat_capacity() is ``target`` (kJ/mol/K per particle): C_V + (target - c), exact in one
        step since c_U does not depend on C_V. Returns None, or a failure message (C_V kept) when that C_V would be
        below MIN_INTERNAL_HEAT_CAPACITY: the particle's motion and configuration alone carry more than the fluid's
        c_v."""
        measured = self.heat_capacity()
        needed = self.parameters.heat_capacity + target - measured.value
        if needed < MIN_INTERNAL_HEAT_CAPACITY:
            carried = (measured.value - self.parameters.heat_capacity) / KB
            return (f"heat capacity: C_V would have to be {needed / KB:.3g} k_B for c_v = {target / KB:.4g} k_B per "
                    f"particle (the motion and the configuration carry {carried:.3g} k_B "
                    f"+ k_B of the internal energy's Gamma law), below {MIN_INTERNAL_HEAT_CAPACITY / KB:g} k_B; "
                    f"C_V kept at {self.parameters.heat_capacity / KB:.4g} k_B; put more molecules in a particle")
        self.parameters = self.parameters.replace(heat_capacity=needed)
        return None

    def _wave_rate(self, amplitude_of, perturb, diffusivity):
        """The decay rate (1/ps) of a wave along z of the box of plan.steady_cells (the steady flows' box, so that
        both methods see the same wavelength, the longest that box has): the replicas' amplitudes averaged, then a
        least-squares line through log(amplitude) over the times where the mean amplitude exceeds 1/e^2 of its
        start; error from the replicas' individual rates. The run covers plan.wave_decays decay times
        1/(diffusivity k^2) (``diffusivity``, nm^2/ps, from the target: eta/(n0 m) or lambda/(n0 c)), at least
        plan.wave_steps steps: a shorter run, a third of the decay time in a long box, read the conductivity ~50%
        high (docs/transport.md). In a 500-particle cube (k R = 1.3 for water) the transverse wave read the
        viscosity ~0.7 of the 2048-particle cube's, and in that cube (k R = 0.83) it read 0.77 of the Poiseuille
        flow's in the long box once the friction was doubled: the dissipative stress is spread over R, so a wave
        much longer than R is needed for the macroscopic coefficient."""
        def one(index, model, context):
            edge = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
            k = 2 * math.pi / edge
            step = model.integrator.getStepSize().value_in_unit(unit.picosecond)
            steps = max(self.plan.wave_steps, round(self.plan.wave_decays / (diffusivity * k**2) / step))
            interval = max(1, steps // 150)
            perturb(model, context, k)
            times, amplitudes = [], []
            for n in range(steps // interval + 1):
                if n:
                    self._step(model.integrator, interval)
                state = context.getState(getPositions=True, getVelocities=True, getEnergy=True)
                times.append(state.getTime().value_in_unit(unit.picosecond))
                amplitudes.append(amplitude_of(model, context, state, k))
            times, amplitudes = np.array(times) - times[0], np.array(amplitudes)
            return times, amplitudes, _decay_rate(times, amplitudes), k

        runs = self.replicas(self.plan.steady_cells)(one)
        times, k = runs[-1][0], runs[-1][3]
        curves, rates = [run[1] for run in runs], [run[2] for run in runs]
        mean_rate = _decay_rate(times, np.mean(curves, axis=0))
        return mean_rate, float(np.std(rates, ddof=1) / math.sqrt(len(rates))), k, len(rates)

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

        mass_density = p.density * p.mass
        rate, error, k, replicas = self._wave_rate(amplitude, perturb,
                                                   p.targets()["shear_viscosity"] / mass_density)
        return Measured(rate * mass_density / k**2, error * mass_density / k**2, replicas)

    def thermal_conductivity(self):
        """lambda from the decay of a wave theta_i -> theta_i (1 + 0.2 sin(k z_i)), read from the energy wave
        sum (eps_i + K_i). Each theta_i is scaled, not set: setting every theta_i to T0 (1 + 0.2 sin(k z)) took away
        the equilibrium spread of the eps_i, the harmonic mean of theta fell by 7% (argon) within 500 steps, and the
        conduction term, which goes as 1/theta^2, read the conductivity ~16% high (docs/transport.md)."""
        p = self.parameters
        heat_capacity = self.heat_capacity().value

        def perturb(model, context, k):
            z = model_positions(context)[:, 2]
            theta = np.asarray(model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
            model.integrator.setParticleTemperatures(list(theta * (1 + 0.2 * np.sin(k * z))))

        def amplitude(model, context, state, k):
            z = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[:, 2]
            v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
            kinetic = 0.5 * p.mass * np.sum(v * v, axis=1)
            energies = np.asarray(model.integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))
            return 2 * np.mean((energies + kinetic) * np.sin(k * z))

        rate, error, k, replicas = self._wave_rate(
            amplitude, perturb, p.targets()["thermal_conductivity"] / (p.density * heat_capacity))
        factor = p.density * heat_capacity / k**2
        return Measured(rate * factor, error * factor, replicas)


    def steady_viscosity(self):
        """eta by periodic Poiseuille flow (transport.poiseuille_viscosity) in boxes of plan.steady_cells."""
        time = self.plan.steady_time
        result = poiseuille_viscosity(self.parameters, self.replicas(self.plan.steady_cells), developed=3.0 * time,
                                      measured=5.0 * time, report=self.report)
        return Measured(result.value, result.error, len(result.replica_values))

    def steady_conductivity(self):
        """lambda by a steady heat flux between slabs (transport.heat_flux_conductivity) in plan.steady_cells."""
        time = self.plan.steady_time
        result = heat_flux_conductivity(self.parameters, self.replicas(self.plan.steady_cells), developed=2.0 * time,
                                        measured=6.0 * time, report=self.report)
        return Measured(result.value, result.error, len(result.replica_values))

    def steady_correction(self, attribute, measure_steady, measure_wave, history, target, name, failure=None):
        """The steady flow's measurement of the coefficient that ``attribute`` sets, and, if it misses the target by
        more than max(TOLERANCE target, one standard error) (_settled), one more step on it: the parameter times
        (target/measured)^(1/e), e = d ln(coefficient)/d ln(parameter) of the wave iteration (1 if not measured;
        the step at most MAX_STEP), then the wave and the steady flow measured again. The steady flows are the
        more precise (water's heat flux 3% where its wave was 19%) and see the same wavelength. Returns (the steady
        measurement, the new wave measurement or None, ``failure``, the wave iteration's, or None where this step
        moved the parameter away from the one that failure kept: both methods are then measured again and judged by
        CRITERIA; water's energy waves read kappa 12367 -> 22526 as no move and kept 22526, the heat flux then took
        kappa to 31360, where both methods reached the target, and the stale failure failed the calibration); the new
        wave joins ``history``."""
        steady = measure_steady()
        if _settled(steady, target):
            return steady, None, failure
        value = getattr(self.parameters, attribute)
        factor = min(MAX_STEP, max(1 / MAX_STEP, (target / steady.value) ** (1 / _elasticity(history))))
        self.parameters = self.parameters.replace(**{attribute: value * factor})
        self.report(f"  {name} by the steady flow: {steady.value:.5g} +- {steady.error:.2g} (target {target:.5g}): "
                    f"{attribute} {value:.5g} -> {value * factor:.5g}, both methods measured again")
        if failure:
            self.report(f"  (superseded: {failure.split(';')[0]})")
        wave = measure_wave()
        history.append((value * factor, wave))
        return measure_steady(), wave, None

    def iterate(self, attribute, measure, target, name, runs):
        """Move the parameter ``attribute`` ('friction', 'heat_conduction' or 'bulk_modulus') until ``measure()``
        is within max(TOLERANCE target, one standard error) of ``target`` (_settled): the first step assumes the
        measured property proportional to the parameter, later ones are secant steps on the last two measurements
        when their difference is a measured response (more than 2 standard errors of it), else proportional again.
        The result is judged afterwards with its 95% interval (_reached, CRITERIA). It stops
        with a failure, saying what to change (FAILURE_ADVICE), when the measured response is not positive (the
        parameter does not move the property), or when the secant's intercept, the property of the model without
        the parameter (for gamma and kappa the kinetic and conservative parts), lies above the target. Returns (the
        last measurement, the history [(parameter, Measured)], a failure message or None); at most ``runs``
        measurements: one that has not converged by then keeps the parameter measured closest to the target among the
        first and those that measurably moved the property (water's B_T x 9 read 0.158 of the target against 0.092
        as mapped, within 2 standard errors: the mapped B_T is kept), and fails, saying what to change, if its last
        step did not move the property; the result is judged by CRITERIA like any other."""
        history = []

        def give_up(message):
            # The closest to the target among the first (mapped) parameter and those whose measurement differs
            # measurably from its: a move whose effect was not measured is not kept.
            first = history[0]
            candidates = [first] + [entry for entry in history[1:] if _measured_difference(first[1], entry[1])]
            best_value, best = min(candidates, key=lambda entry: abs(entry[1].value - target))
            self.parameters = self.parameters.replace(**{attribute: best_value})
            return best, history, (message + f"; {attribute} kept at {best_value:.4g}; {FAILURE_ADVICE[attribute]}"
                                   if message else None)

        for run in range(runs):
            value = getattr(self.parameters, attribute)
            measured = measure()
            history.append((value, measured))
            self.report(f"  {name} run {run + 1}: {attribute} = {value:.5g} -> {measured.value:.5g} +- "
                        f"{measured.error:.2g} (target {target:.5g}, model/target {measured.value / target:.3f})")
            if _settled(measured, target):
                return measured, history, None
            if run + 1 == runs:
                break
            proposal = value * target / measured.value
            if len(history) >= 2:
                (x1, m1), (x2, m2) = history[-2:]
                slope = (m2.value - m1.value) / (x2 - x1)
                if _measured_difference(m1, m2):
                    if slope <= 0:
                        return give_up(f"{name}: {attribute} {x1:.4g} -> {x2:.4g} moved it {m1.value:.4g} -> "
                                       f"{m2.value:.4g} (target {target:.4g}): a response of the wrong sign, no "
                                       f"{attribute} reaches the target")
                    floor = m2.value - slope * x2
                    if floor > target + 2 * math.hypot(m1.error, m2.error):
                        return give_up(f"{name}: the model's {name} without its {attribute} is {floor:.4g} (the "
                                       f"secant's intercept), above the target {target:.4g}: no {attribute} reaches "
                                       f"it")
                    proposal = x2 + (target - m2.value) / slope
            if not proposal > 0:
                return give_up(f"{name}: the next {attribute} would be {proposal:.4g} <= 0: no {attribute} reaches "
                               f"the target {target:.4g}")
            # At most a factor MAX_STEP per run: a response that is not measured (water's n dP/dn does not follow
            # B_T) must not throw the parameter far (B_T went x11 twice before this limit).
            proposal = min(MAX_STEP * value, max(value / MAX_STEP, proposal))
            self.parameters = self.parameters.replace(**{attribute: proposal})
        # Out of runs: keep the best parameter measured, and say so if the last step did not move the property.
        failure = None
        if len(history) >= 2:
            (x1, m1), (x2, m2) = history[-2:]
            moved = (m2.value - m1.value) * (x2 - x1) > 0 and _measured_difference(m1, m2)
            # A step too small for its expected effect (the property proportional to the parameter) to stand out
            # of the noise says nothing (water's friction 8855 -> 8059: 593 +- 52 -> 596 +- 11 read no move).
            resolvable = abs(m1.value * (x2 / x1 - 1)) > 2 * math.hypot(m1.error, m2.error)
            if resolvable and not moved:
                failure = (f"{name}: {attribute} {x1:.4g} -> {x2:.4g} did not move it ({m1.value:.4g} +- "
                           f"{m1.error:.2g} -> {m2.value:.4g} +- {m2.error:.2g}, target {target:.4g})")
        return give_up(failure)


def _reached(measured, target):
    """Whether a Measured value is within max(TOLERANCE target, its 95% interval, coverage) of ``target``."""
    return abs(measured.value - target) <= max(TOLERANCE * target, coverage(measured.samples) * measured.error)


def _settled(measured, target):
    """Whether an iteration stops at a Measured value: within max(TOLERANCE target, one standard error) of
    ``target``. Not the judgement's 95% interval (_reached): with 4 replicas that spans 3.18 standard errors, and
    water's first energy wave, 1.74 +- 0.27 of the target, lay inside it; a step on a miss of more than a standard
    error is a step towards the target on average, a smaller one is within what the measurement resolves."""
    return abs(measured.value - target) <= max(TOLERANCE * target, measured.error)


def _measured_difference(a, b):
    """Whether two Measured values differ by more than 2 standard errors of their difference."""
    return abs(b.value - a.value) > 2 * math.hypot(a.error, b.error)


def _elasticity(history):
    """d ln(property)/d ln(parameter) from the last two entries of an iteration's history [(parameter, Measured)]
    when their difference is measured (more than 2 standard errors) and positive, within [1/3, 3]; else 1."""
    if len(history) >= 2:
        (x1, m1), (x2, m2) = history[-2:]
        if x1 != x2 and _measured_difference(m1, m2) and m1.value > 0 < m2.value:
            elasticity = math.log(m2.value / m1.value) / math.log(x2 / x1)
            if elasticity > 0:
                return min(3.0, max(1 / 3, elasticity))
    return 1.0


def _box_edges(model):
    """The particles and the shape of ``model``'s box (edges over the z edge), the same at every density: the key
    of a melted liquid."""
    vectors = model.system.getDefaultPeriodicBoxVectors()
    edges = [vectors[k][k].value_in_unit(unit.nanometer) for k in range(3)]
    return model.num_particles, round(edges[0] / edges[2], 9), round(edges[1] / edges[2], 9)


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


def pressure_step(pressures, target):
    """The move of pi0 (kJ/mol/nm^3) for the next round from the rounds so far, [(pi0, Measured P)] with f_cut tuned
    in each: P0 - P if there is one round, or if the last two differ by less than 2 standard errors (no measured
    response); else a secant step (P0 - P)/(dP/dpi0), the response clipped to [0.25, 4] (a noisy secant must not
    throw pi0 far)."""
    pi0, pressure = pressures[-1]
    response = 1.0
    if len(pressures) >= 2:
        previous_pi0, previous = pressures[-2]
        if _measured_difference(previous, pressure):
            response = min(4.0, max(0.25, (pressure.value - previous.value) / (pi0 - previous_pi0)))
    return (target - pressure.value) / response
