# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Tune f_cut of the VB (or VC) estimator so that the mean density equals the imposed one (`tune-fcut`); the paper tuned
it by hand.

Self-consistent iteration: run VB at the current f_cut (openmmgendpde.models.argon_runs protocol) keeping production
frames; on those frames, evaluate n-bar at trial values of f_cut (GenDPDEForce.updateParametersInContext, no new
Context); solve n-bar(f_cut) = n0 on the straight line through them; set the new f_cut in the running Context and
continue. The structure barely depends on f_cut, so two or three iterations converge. The uncertainty of f_cut is that
of n-bar (block average) divided by |d n-bar / d f_cut|.

With --fluid NAME|FILE (calibrate's fluids and coarse-graining options: --molecules-per-particle, --neighbors or
--cutoff in nm) the model of any fluid is tuned instead, by calibrate's own iteration (Calibration.
tune_cutoff_scaling: --max-iterations runs of calibrate's plan, --quick its QUICK plan) to n-bar = n0.
"""

import dataclasses

from ..analysis.density import mean_density_on_frames
from ..analysis.statistics import block_average
from ..models.argon import ARGON_STATE, default_cutoff_scaling
from ..models.argon_runs import run_argon
from .calibration import Calibration


@dataclasses.dataclass(frozen=True)
class CutoffScalingEstimate:
    """What ``tune`` found: the f_cut that solves n-bar*(f_cut) = n0* on the straight line through the last run,
    and what that run measured."""
    cutoff_scaling: float        # the estimate of f_cut
    standard_error: float        # of cutoff_scaling: that of n-bar* divided by |d n-bar*/d f_cut|
    density: float               # n-bar* measured in the last run
    density_error: float         # its standard error (block average)
    iterations: int              # runs made
    last_cutoff_scaling: float   # f_cut of the last run, at which n-bar* was measured


def tune(cutoff, protocol, platform="Reference", start=None, tolerance=0.001, max_iterations=5, progress=None,
         report=print, estimator="VB"):
    """A CutoffScalingEstimate: f_cut of ``estimator`` ('VB' or 'VC') solving n-bar*(f_cut) = n0* on the straight
    line through the last run, with its standard error and that run's n-bar*."""
    target = ARGON_STATE.density
    cutoff_scaling = start if start is not None else default_cutoff_scaling(cutoff, estimator)
    running = None
    for iteration in range(1, max_iterations + 1):
        run = run_argon(cutoff, estimator, protocol, platform, cutoff_scaling, frames=10, progress=progress,
                        continue_from=running)
        samples, argon, simulation = run.samples, run.argon, run.simulation
        running = (argon, simulation)
        context = simulation.context
        density, density_error = block_average(samples.density, name=f"n-bar* at f_cut = {cutoff_scaling:.4f}")
        state = context.getState(getPositions=True, getVelocities=True, getIntegratorParameters=True)
        delta = 0.01
        low = mean_density_on_frames(argon.force, context, samples.frames, cutoff_scaling - delta)
        high = mean_density_on_frames(argon.force, context, samples.frames, cutoff_scaling + delta)
        context.setState(state)
        slope = (high - low) / (2 * delta)
        next_cutoff_scaling = max(1.0, cutoff_scaling + (target - density) / slope)
        report(f"iteration {iteration}: f_cut = {cutoff_scaling:.4f}: n-bar* = {density:.4f} +- {density_error:.4f}, "
               f"d n-bar*/d f_cut = {slope:.3f} -> f_cut = {next_cutoff_scaling:.4f}")
        # The estimate: where the line through the last run's measurement reaches n0.
        measured = CutoffScalingEstimate(next_cutoff_scaling, density_error / abs(slope), density, density_error,
                                         iteration, cutoff_scaling)
        if abs(density - target) <= max(tolerance, 2 * density_error):
            return measured
        cutoff_scaling = next_cutoff_scaling
        argon.force.setCutoffScaling(cutoff_scaling)
        argon.force.updateParametersInContext(context)
    report(f"not converged within {max_iterations} iterations; the estimate from the last run is reported")
    return measured


def tune_fluid(parameters, estimator, plan, platform="Reference", seed=1, iterations=5, report=print):
    """f_cut of ``estimator`` for the model ``parameters`` (any fluid's) by calibrate's own iteration
    (Calibration.tune_cutoff_scaling: ``iterations`` runs of ``plan``) to n-bar = n0; its lines go to ``report``."""
    calibration = Calibration(parameters.for_estimator(estimator), estimator, plan, platform, seed=seed,
                              report=report)
    return calibration.tune_cutoff_scaling(iterations)
