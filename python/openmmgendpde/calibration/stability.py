# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The largest stable time step of a fluid model, measured (docs/fluids.md "Time step").

A step size passes when, from a melted liquid (Isothermal steps at dt* = 0.005), `steps` steps at that size in the
given mode run without an error (the integrator refuses a blown-up step or an internal energy <= 0) and keep their
defining quantity: the drift of the conserved energy K + U + sum eps within 1% of the energy that the mode moves
(K + sum eps in the Isoenergetic mode, K in the Conservative mode, where eps is inert), and in the Isothermal mode
the kinetic temperature averaged over the last 10 samples (50 steps apart) within 10% of T0 (the bath's; a sample's
own scatter is sqrt(2/(3N)) = 3.7% for 500 particles). Step sizes are tried on a doubling ladder from dt* = 0.01, then
the last interval is bisected twice. `suggest_time_step` returns half the smallest limit over the three modes, times
an accuracy factor for V-C (its stable_step_factor in the table of estimators).

Bonds (docs/soft-matter.md, "The time step with bonds"). Given the System, `suggest_time_step` also bounds the
highest vibrational frequency of its HarmonicBondForce and HarmonicAngleForce terms (`bonded_frequency`: Gershgorin's
bound on the mass-weighted Hessian of those terms) and takes the smaller of the fluid's limit and
BONDED_STEP_LIMIT/omega_max, BONDED_STEP_LIMIT measured with the same pass criterion on polymer melts whose bonds are
stiff enough to set the limit (devtools/bonded_step_limit.py). Any other force it cannot bound is refused by name.

The limits are measured on a bulk liquid, where V-C is V-B (its surface factor is 1 for 99% of the particles); at free
surfaces V-C's conserved-energy error at a given step is ~100 times V-B's (docs/interfaces.md, "V-C's energy error":
slab and droplet of liquid argon, second order in dt), because its surface factor makes the energy of a surface
particle much stiffer than V-B's. So V-C needs a step sqrt(100) = 10 times smaller for the same drift: measured,
V-C at dt* = 0.0067 drifts as much as V-B at its suggested 0.067 (-6.6e-5 against -6.0e-5 N k_B T0 for the slab,
-2.3e-4 against -2.4e-4 for the droplet, 40 time units from the lattice).
"""

import math

import numpy as np
import openmm
from openmm import unit

from ..analysis.thermodynamics import ThermodynamicProbe, particle_masses
from ..api import GenDPDEForce, GenDPDEIntegrator, estimator_of
from ..models.melting import melt_then_switch

MODES = {"Isoenergetic": GenDPDEIntegrator.Isoenergetic, "Isothermal": GenDPDEIntegrator.Isothermal,
         "Conservative": GenDPDEIntegrator.Conservative}


#: The largest omega_max dt (omega_max: bonded_frequency's bound) at which a System whose bonds set the limit passes
#: the criterion of largest_stable_step (measured by devtools/bonded_step_limit.py; docs/soft-matter.md, "The time
#: step with bonds"). suggest_time_step halves it, as it halves the fluid's limit.
BONDED_STEP_LIMIT = 1.0



#: The Forces that exert no force (bonded_frequency passes them by).
_WITHOUT_STIFFNESS = (openmm.CMMotionRemover, openmm.MonteCarloBarostat, openmm.MonteCarloAnisotropicBarostat,
                      openmm.MonteCarloMembraneBarostat, openmm.MonteCarloFlexibleBarostat)


def bonded_frequency(system):
    """An upper bound on the highest vibrational angular frequency (rad/ps) of ``system``'s HarmonicBondForce and
    HarmonicAngleForce terms: Gershgorin's bound on the mass-weighted Hessian M^-1/2 H M^-1/2 of those terms, with
    each 3 x 3 block bounded by its norm. A bond (k, r0) between i and j adds k (1/m_i + 1/sqrt(m_i m_j)) to row i
    (its Hessian's eigenvalues are k along the bond and k (1 - r0/r) across it, at most k in size for any r >= r0/2);
    so for equal masses omega_max <= 2 sqrt(k/m) for a bead with two bonds, sqrt(2k/m) for a dimer (exact). An angle
    (k_theta) i-j-k adds k_theta |g_a|/sqrt(m_a) sum_b |g_b|/sqrt(m_b) to row a, with |g_i| = 1/r_ij, |g_k| = 1/r_kj,
    |g_j| <= 1/r_ij + 1/r_kj the gradients of the angle at its rest geometry, the arm lengths r being the rest lengths
    of the bonds between them (an angle whose arms are not bonds of a HarmonicBondForce is refused). Massless
    (fixed) particles have no row. 0.0 for a System without bonds. Any other Force but a GenDPDEForce, a
    CMMotionRemover or a Monte Carlo barostat (no forces) raises ValueError naming it: its stiffness is not bounded
    here."""
    masses = particle_masses(system)
    rows = np.zeros(len(masses))
    bonds, angles = [], []
    for index, force in enumerate(system.getForces()):
        if isinstance(force, openmm.HarmonicBondForce):
            bonds.append(force)
        elif isinstance(force, openmm.HarmonicAngleForce):
            angles.append(force)
        elif not (GenDPDEForce.isinstance(force) or isinstance(force, _WITHOUT_STIFFNESS)):
            raise ValueError(f"force {index} ({type(force).__name__}) is not allowed: bonded_frequency bounds only "
                             f"HarmonicBondForce and HarmonicAngleForce (with a GenDPDEForce, a CMMotionRemover and "
                             f"Monte Carlo barostats), and a time step that ignores its stiffness could be unstable")
    inverse_root = np.zeros(len(masses))
    inverse_root[masses > 0] = 1 / np.sqrt(masses[masses > 0])
    rest_lengths = {}
    for force in bonds:
        for b in range(force.getNumBonds()):
            i, j, r0, k = force.getBondParameters(b)
            k = k.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**2)
            rest_lengths[frozenset((i, j))] = r0.value_in_unit(unit.nanometer)
            cross = abs(k) * inverse_root[i] * inverse_root[j]
            rows[i] += abs(k) * inverse_root[i] ** 2 + cross
            rows[j] += abs(k) * inverse_root[j] ** 2 + cross
    for force in angles:
        for a in range(force.getNumAngles()):
            i, j, k, _, stiffness = force.getAngleParameters(a)
            stiffness = abs(stiffness.value_in_unit(unit.kilojoule_per_mole / unit.radian**2))
            arms = [rest_lengths.get(frozenset(pair)) for pair in ((i, j), (k, j))]
            if None in arms or min(arms) <= 0:
                raise ValueError(f"angle {a} ({i}, {j}, {k}) of a HarmonicAngleForce is not allowed: bonded_frequency "
                                 f"needs its arms ({i}, {j}) and ({k}, {j}) to be bonds of a HarmonicBondForce with "
                                 f"rest lengths > 0, whose lengths bound the angle's gradients")
            gradients = {i: 1 / arms[0], k: 1 / arms[1], j: 1 / arms[0] + 1 / arms[1]}
            total = sum(g * inverse_root[p] for p, g in gradients.items())
            for p, g in gradients.items():
                rows[p] += stiffness * g * inverse_root[p] * total
    return float(math.sqrt(rows.max())) if len(rows) else 0.0


def _liquid_builder(parameters, particles):
    def build(estimator, seed):
        return parameters.liquid(particles, estimator, mode=GenDPDEIntegrator.Isothermal, time_step=0.005, seed=seed)
    return build


def _passes(parameters, estimator, mode, time_step, steps, particles, platform, seed, build=None):
    model = (build or _liquid_builder(parameters, particles))(estimator, seed)
    model.integrator.setMode(GenDPDEIntegrator.Isothermal)
    model.integrator.setStepSize(parameters.units.to_openmm(0.005, "time"))
    integrator = model.integrator
    context = model.context(platform, parameters.temperature, seed)
    melt_then_switch(integrator, 500, parameters.temperature, seed, MODES[mode])
    integrator.setStepSize(parameters.units.to_openmm(time_step, "time"))
    probe = ThermodynamicProbe(model.system)
    try:
        start = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
        kinetic = context.getState(getEnergy=True).getKineticEnergy().value_in_unit(unit.kilojoule_per_mole)
        internal = sum(integrator.getInternalEnergies().value_in_unit(unit.kilojoule_per_mole))
        scale = kinetic + (internal if mode == "Isoenergetic" else 0.0)
        integrator.step(steps - 500)
        temperatures = []
        for _ in range(10):
            integrator.step(50)
            state = context.getState(getEnergy=True, getVelocities=True)
            temperatures.append(probe.sample(state, context, integrator).kinetic_temperature.value_in_unit(unit.kelvin))
        end = integrator.getConservedEnergy().value_in_unit(unit.kilojoule_per_mole)
    except openmm.OpenMMException:
        return False
    if mode == "Isothermal":
        return abs(sum(temperatures) / len(temperatures) / parameters.temperature - 1) < 0.10
    return math.isfinite(end) and abs(end - start) < 0.01 * scale


def largest_stable_step(parameters, estimator="VB", mode="Isoenergetic", steps=1000, particles=500,
                        platform="CPU", seed=1, build=None, first_step=0.01):
    """The largest dt* (reduced time of the model) that passes (module docstring), to within 1/4 of a doubling, on the
    ladder from ``first_step`` (0.0 where that fails). The model run is the fluid's liquid of ``particles``, or
    ``build(estimator, seed)`` (a model.Model of ``parameters``' reduced units, e.g. a models.polymers solution)."""
    passed, failed = None, None
    step = first_step
    while step <= 1.0:
        if _passes(parameters, estimator, mode, step, steps, particles, platform, seed, build):
            passed, step = step, 2 * step
        else:
            failed = step
            break
    if passed is None:
        return 0.0
    if failed is None:
        return passed
    for _ in range(2):
        middle = math.sqrt(passed * failed)
        if _passes(parameters, estimator, mode, middle, steps, particles, platform, seed, build):
            passed = middle
        else:
            failed = middle
    return passed


def suggest_time_step(parameters, estimator="VB", system=None, **options):
    """Half the smallest measured limit over the three modes, times the estimator's stable_step_factor (the table of
    estimators, api.ESTIMATORS: for the same conserved-energy drift at free surfaces as V-B's; V-C's 0.1, measured
    for liquid argon by devtools/vc_energy_drift.py: its drift is second order in dt and ~100 times V-B's at the same
    step), in the model's reduced time, and in ps. With ``system`` (an openmm.System of this fluid holding bonds) the
    limit is at most BONDED_STEP_LIMIT/bonded_frequency(system); a Force that bonded_frequency cannot bound raises
    ValueError before anything runs."""
    bonded = None
    if system is not None:
        omega = bonded_frequency(system)
        if omega > 0:
            bonded = parameters.units.from_openmm(BONDED_STEP_LIMIT / omega, "time")
    limit = min(largest_stable_step(parameters, estimator, mode, **options) for mode in MODES)
    if bonded is not None:
        limit = min(limit, bonded)
    step = 0.5 * limit * estimator_of(estimator).stable_step_factor
    return step, parameters.units.to_openmm(step, "time")
