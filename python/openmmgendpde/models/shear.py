# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Reverse non-equilibrium shear flow (Mueller-Plathe, Phys. Rev. E 59, 4894 (1999)) in a periodic box, driven by
momentum exchanges: ReverseShearFlow, an OpenMM-style driver of a Simulation (a reporter that acts) or a Context
(its step()). docs/flows.md, "Shear flow and the flow curve", says the method, why not Lees-Edwards boundaries or
moving walls, and what was measured; analysis/shear.py turns what it records into a viscosity.

The box is cut into ``slabs`` equal slabs along z (by the fractional coordinate along the third box vector, so any
box in OpenMM's reduced form). Every ``exchangeInterval`` steps the particle of slab 0 (z in [0, L/slabs)) with the
most negative x velocity and the particle of slab slabs/2 (z in [L/2, L/2 + L/slabs)) with the most positive one swap
their x velocities, if that moves x momentum into slab 0 (else nothing is swapped and the exchange records 0). The
particles of a System must have one mass (massless ones are never exchanged): then the swap keeps the total momentum
and the kinetic energy exactly, and the steady flow is the zig-zag v_x(z), + near z = 0 and - near z = L/2, carrying
the momentum flux J = (sum of the momenta moved)/(2 A t) back through both halves (A the xy area of the box).

The velocities swapped are those at the positions' time. A GenDPDEIntegrator keeps velocities half a step behind
(docs/integrator.md: v + (dt/2) F/m is the on-step velocity, which its kinetic and conserved energies use): the
exchange swaps the on-step x velocities u = v + (dt/2) F_x/m and stores u_swapped - (dt/2) F_x/m. Swapping the stored
velocities instead would keep the momentum (the forces sum to zero) but change the conserved energy by
m (v_j - v_i)(a_i - a_j), a = (dt/2) F_x/m, at every exchange (tested in python/tests/test_shear.py). Setting the
velocities makes the integrator evaluate the forces again at its next step and resets the energy guard's mark
(docs/integrator.md); nothing else of its state (internal energies, sweep order, random streams) changes. Each exchange
costs one force evaluation for the State and one at the next step.

Energy: in the Isoenergetic mode E = K + U + sum eps_i stays constant (the exchange moves kinetic energy from thermal
motion into the flow, the flow's dissipation heats the fluid between the slabs, and a temperature profile forms, cold
at the slabs); in the Isothermal mode the DPD thermostat takes the viscous heat.
"""

import numbers

import numpy as np
import openmm
from openmm import unit

from ..analysis.thermodynamics import integration_groups, particle_masses
from ..api import GenDPDEIntegrator
from ..internal.reporting import checked_choice

#: The most slabs: each must hold particles to exchange; more than any box can fill (as profiles.MAX_BINS).
MAX_SLABS = 100000
_MOMENTUM = unit.amu * unit.nanometer / unit.picosecond


def _integral(value):
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def exchange_slabs(positions, box, slabs):
    """The slab index (0 .. slabs - 1) of each particle along z: its fractional coordinate along the third box vector,
    wrapped into [0, 1), times ``slabs``. positions (nm) N x 3, box three rows (nm, reduced form)."""
    fractional = np.asarray(positions, float) @ np.linalg.inv(np.asarray(box, float))
    wrapped = fractional[:, 2] - np.floor(fractional[:, 2])
    return np.minimum((wrapped * slabs).astype(int), slabs - 1)


def swap_pair(velocities, slab, slabs, mobile):
    """(i, j): the particle of slab 0 with the most negative x velocity and that of slab slabs/2 with the most positive
    one among the ``mobile`` particles (a boolean mask), or None where a slab has none or the swap would move x
    momentum out of slab 0 (velocities[j, 0] <= velocities[i, 0])."""
    low = np.flatnonzero((slab == 0) & mobile)
    high = np.flatnonzero((slab == slabs // 2) & mobile)
    if len(low) == 0 or len(high) == 0:
        return None
    i, j = low[np.argmin(velocities[low, 0])], high[np.argmax(velocities[high, 0])]
    if not velocities[j, 0] > velocities[i, 0]:
        return None
    return int(i), int(j)


class ReverseShearFlow:
    """Drives a reverse non-equilibrium shear flow (the module's docstring): every ``exchangeInterval`` steps (an
    integer >= 1) the x velocities of two particles are swapped, one in slab 0 and one in slab ``slabs``/2 of ``slabs``
    equal slabs along z (an even integer >= 4). Use it as a reporter of an ``openmm.app.Simulation``
    (``simulation.reporters.append(flow)``: it exchanges at every step count that is a multiple of the interval), or
    call ``step(context, steps)`` on a Context. The integrator must be a GenDPDEIntegrator, the System periodic and
    its moving particles of one mass (checked at the first exchange, before anything changes).

    Recorded per exchange (numpy arrays, OpenMM units): ``steps``, ``times`` (ps), ``momenta`` (amu nm/ps: the x
    momentum moved into slab 0, 0 where none was swapped); ``area`` (nm^2) is the xy area of the box at the last
    exchange. ``getExchangedMomentum()`` is their sum as a Quantity. analysis.shear.momentum_flux gives J."""

    def __init__(self, exchangeInterval, slabs=20):
        name = "ReverseShearFlow"
        checked_choice(name, "exchangeInterval", exchangeInterval, lambda k: _integral(k) and k >= 1,
                       "an integer >= 1 (steps between exchanges)")
        checked_choice(name, "slabs", slabs, lambda s: _integral(s) and 4 <= s <= MAX_SLABS and s % 2 == 0,
                       f"an even integer from 4 to {MAX_SLABS} (the exchange slabs are slab 0 and slab slabs/2)")
        self._interval, self._slabs = int(exchangeInterval), int(slabs)
        self._steps, self._times, self._momenta = [], [], []
        self.area = None
        self._context = None   # the Context whose System's masses were checked
        self._masses = None

    def getExchangeInterval(self):
        return self._interval

    def getNumSlabs(self):
        return self._slabs

    @property
    def steps(self):
        return np.array(self._steps, int)

    @property
    def times(self):
        return np.array(self._times, float)

    @property
    def momenta(self):
        return np.array(self._momenta, float)

    def getExchangedMomentum(self):
        """The x momentum moved into slab 0 by every exchange so far (a Quantity, amu nm/ps)."""
        return float(np.sum(self._momenta)) * _MOMENTUM

    def reset(self):
        """Forget the exchanges recorded so far (e.g. after the flow has developed); the flow goes on."""
        self._steps, self._times, self._momenta = [], [], []

    # --- OpenMM's reporter protocol ---------------------------------------------------------------------------------

    def describeNextReport(self, simulation):
        steps = self._interval - simulation.currentStep % self._interval
        return (steps, True, True, True, False)   # positions, velocities and forces (the on-step velocities)

    def report(self, simulation, state):
        self.exchange(simulation.context, state)

    # --- on a Context ---------------------------------------------------------------------------------------------

    def step(self, context, steps):
        """Advance ``context`` by ``steps`` steps of its integrator, exchanging whenever its step count
        (Context.getStepCount) reaches a multiple of the exchange interval."""
        checked_choice("ReverseShearFlow", "steps", steps, lambda s: _integral(s) and s >= 0, "an integer >= 0")
        left = int(steps)
        integrator = context.getIntegrator()
        while left > 0:
            chunk = min(left, self._interval - context.getStepCount() % self._interval)
            integrator.step(chunk)
            left -= chunk
            if context.getStepCount() % self._interval == 0:
                self.exchange(context)

    def exchange(self, context, state=None):
        """One exchange now (the module's docstring); returns the x momentum moved into slab 0 (amu nm/ps, a float; 0
        where none was swapped). ``state``: a State of ``context`` now with positions, velocities and forces."""
        integrator = self._checked(context)
        if state is None:
            state = context.getState(getPositions=True, getVelocities=True, getForces=True)
        box = state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer)
        positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
        velocities = np.array(state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond))
        groups = integration_groups(integrator)
        if len(groups) < 32:   # the State's forces are every group's: those the integrator kicks with
            state = context.getState(getForces=True, groups=groups)
        forces = state.getForces(asNumpy=True).value_in_unit(unit.kilojoule_per_mole / unit.nanometer)
        step = integrator.getStepSize().value_in_unit(unit.picosecond)
        mobile = self._masses > 0
        half_kick = np.zeros(len(velocities))
        half_kick[mobile] = 0.5 * step * forces[mobile, 0] / self._masses[mobile]
        on_step = velocities.copy()
        on_step[:, 0] += half_kick
        pair = swap_pair(on_step, exchange_slabs(positions, box, self._slabs), self._slabs, mobile)
        moved = 0.0
        if pair is not None:
            i, j = pair
            velocities[i, 0], velocities[j, 0] = on_step[j, 0] - half_kick[i], on_step[i, 0] - half_kick[j]
            context.setVelocities(velocities)
            moved = float(self._masses[i] * (on_step[j, 0] - on_step[i, 0]))
        self.area = abs(box[0, 0] * box[1, 1])
        self._steps.append(context.getStepCount())
        self._times.append(state.getTime().value_in_unit(unit.picosecond))
        self._momenta.append(moved)
        return moved

    def _checked(self, context):
        """The Context's GenDPDEIntegrator, after the checks of the first exchange on its System (the masses)."""
        name = "ReverseShearFlow"
        integrator = context.getIntegrator()
        checked_choice(name, "the Context's integrator", integrator,
                       lambda i: isinstance(i, GenDPDEIntegrator) or GenDPDEIntegrator.isinstance(i),
                       "a GenDPDEIntegrator (the exchange swaps its on-step velocities v + (dt/2) F/m)")
        integrator = GenDPDEIntegrator.cast(integrator) if not isinstance(integrator, GenDPDEIntegrator) \
            else integrator
        if self._context is not context:
            system = context.getSystem()
            if not system.usesPeriodicBoundaryConditions():
                raise openmm.OpenMMException(f"{name}: the System does not use periodic boundaries; the shear flow "
                                             f"needs a periodic box (a force with periodic boundary conditions)")
            masses = particle_masses(system)
            moving = np.unique(masses[masses > 0])
            if len(moving) != 1:
                raise openmm.OpenMMException(f"{name}: the System's moving particles have the masses "
                                             f"{', '.join(f'{m:g}' for m in moving[:4])}"
                                             f"{' ...' if len(moving) > 4 else ''} amu; they must have one mass (a "
                                             f"swap of velocities keeps the momentum and kinetic energy only "
                                             f"between equal masses)")
            self._context, self._masses = context, masses
        return integrator
