# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""How calibrate iterates a parameter on its measured response (Calibration.iterate, steady_correction; pressure_step
for pi0), and when an iteration stops (_settled) or a result is reached (_reached)."""

import math

from .results import Measured, coverage  # noqa: F401  (Measured: what the iterations take)

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


class Iterations:
    """The iterations of a Calibration (a mix-in: it reads and sets self.parameters, and reports through
    self.report)."""

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
