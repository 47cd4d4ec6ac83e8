# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The machinery of calibrate: a Calibration holds a model's parameters and measures them back (melts, thermodynamics,
the bulk modulus, the heat capacity; the transport coefficients by waves and steady flows: waves.py), and iterates a
parameter on its measured response (iterate, steady_correction; pressure_step for pi0: iteration.py). The protocol and
its stages are calibrate.py (its docstring says the method), the report report.py, the command cli/calibrate.py."""

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
from ..api import GenDPDEIntegrator, estimator_of
from ..internal import forked
from ..models.fluid import KB
from ..models.melting import switch_after_melting
from .expansion import thermal_pressure_coefficient
from .iteration import (  # noqa: F401  (the iterations' names, as this module had them)
    FAILURE_ADVICE,
    MAX_STEP,
    TOLERANCE,
    Iterations,
    _elasticity,
    _measured_difference,
    _reached,
    _settled,
    pressure_step,
)
from .results import Measured
from .waves import TransportMeasurements, _decay_rate, model_positions  # noqa: F401  (names of this module)

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
    sound_wave: bool = True       # the speed of sound measured by a sound wave (waves.sound_speed)
    sound_cells: tuple = (3, 3, 48)    # its box (waves.sound_cells: widened for the cutoff)
    sound_periods: float = 2.0    # the periods of the wave followed


QUICK = Plan(particles=500, melt=400, melt_block=500, frames=60, interval=25, tuning_iterations=3, replicas=3,
             wave_steps=600, pressure_rounds=2, bulk_runs=2, transport_runs=3, steady_cells=(3, 3, 12), steady_time=0.4,
             sound_wave=False)


#: The smallest C_V (kJ/mol/K) match_heat_capacity sets: k_B. Each eps_i/(k_B T) follows a Gamma law of shape
#: C_V/k_B + 1; below k_B the internal energies reach near zero often and the Ito term k_B/(2 C_V) of the
#: integrator's friction passes 1/2 (docs/integrator.md).
MIN_INTERNAL_HEAT_CAPACITY = KB


class _StepCounter:
    """A progress that counts the steps (Calibration.side_by_side: a run's steps reach the bar from its process)."""

    def __init__(self):
        self.steps = 0

    def advance(self, steps):
        self.steps += steps


class Calibration(TransportMeasurements, Iterations):
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

    def expansion_runs(self, platform=None, seed=None, plan=None):
        """The runs of expansion.measure and expansion.thermal_pressure_coefficient in a calibration: a cube of
        plan.particles, plan.melt steps of melt, plan.frames samples plan.interval steps apart (``plan``, default the
        calibration's), on ``platform`` (a name; default the calibration's) with ``seed`` (default the
        calibration's)."""
        plan = plan or self.plan
        return dict(num_particles=plan.particles, melt_steps=plan.melt, steps=plan.frames * plan.interval,
                    sample_every=plan.interval,
                    platform=platform or self.platform.getName(), seed=self.seed if seed is None else seed,
                    estimator=self.estimator, time_step=plan.time_step)

    def thermal_pressure(self, seed=None):
        """The thermal pressure coefficient (dP/dT)_n at n0 (kJ/mol/nm^3/K, Measured): the kinetic n k_B, the law's
        own thermal pressure and the structure's, from runs at T0 -+ 8% (expansion.thermal_pressure_coefficient,
        expansion_runs)."""
        _, _, value, error = thermal_pressure_coefficient(self.parameters, **self.expansion_runs(seed=seed))
        return Measured(value, error)

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

def _box_edges(model):
    """The particles and the shape of ``model``'s box (edges over the z edge), the same at every density: the key
    of a melted liquid."""
    vectors = model.system.getDefaultPeriodicBoxVectors()
    edges = [vectors[k][k].value_in_unit(unit.nanometer) for k in range(3)]
    return model.num_particles, round(edges[0] / edges[2], 9), round(edges[1] / edges[2], 9)


