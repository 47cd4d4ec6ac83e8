# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Body forces that drive flows (docs/flows.md, "Body forces and channel flows"): each an openmm.CustomExternalForce to
add to a System, in its own force group.

- body_force(force, particles): the same force vector F (kJ/mol/nm) on each of the particles named, e.g. gravity or
  a pressure gradient G = n F driving a channel flow between walls;
- acceleration_force(acceleration, system, particles): the same acceleration a (nm/ps^2), F_i = m_i a;
- poiseuille_body_force(force, box_length, particles): periodic Poiseuille flow, +F along ``direction`` in the lower
  half of the box along ``axis`` (wrapped coordinate in [0, L/2)) and -F in the upper half, zero net force on a
  uniform fluid; the steady profile is analysis.flows.poiseuille_shape.

Their energies are not periodic. A uniform force's energy is -F . r with the unwrapped position r (OpenMM's
CustomExternalForce sees the positions as the Context holds them, not wrapped into the box), so it falls without bound
as the fluid flows along F, while K + (the other forces' U) + sum eps_i rises by the same work; with the group's energy
included the total is conserved. The Poiseuille force is not the gradient of any potential in a periodic box (the
flow goes round and round, each lap doing work), so its energy, -F x s(z) with s = +-1 the sign of the half, jumps by
2 F x whenever a particle crosses from one half into the other: nothing including it is conserved, and what the
dynamics conserves is K + U + sum eps_i without it, minus the work the force did (sum over steps of F_i . v_i dt).
Hence the group: leave BODY_FORCE_GROUP out of every energy (State energies with ``groups``), as
analysis.transport does. The reporters' virial pressure leaves every CustomExternalForce out
(analysis.thermodynamics.ThermodynamicProbe), so keep such forces in groups of their own.
"""

import numbers
import reprlib

import numpy as np
import openmm
from openmm import unit

#: The force group of the body forces made here: their energy is not that of the fluid (module docstring), so it is
#: kept out of group 0 and of the energies read with ``groups``.
BODY_FORCE_GROUP = 31

_FORCE = unit.kilojoule_per_mole / unit.nanometer
_ACCELERATION = unit.nanometer / unit.picosecond**2
_AXES = "xyz"


def body_force(force, particles, group=BODY_FORCE_GROUP):
    """A CustomExternalForce of the constant vector ``force`` (3 numbers in kJ/mol/nm, or a Quantity) on each particle
    in ``particles`` (an int N: particles 0 .. N - 1; or an iterable of particle indices), in force group ``group``.
    Its energy is -F . r (unwrapped r: module docstring)."""
    vector = _vector("body_force", "force", force, _FORCE, "kJ/mol/nm")
    external = _uniform("body_force", group)
    for index in _particles("body_force", particles):
        external.addParticle(index, list(vector))
    return external


def acceleration_force(acceleration, system, particles=None, group=BODY_FORCE_GROUP):
    """A CustomExternalForce that gives each particle in ``particles`` (None: every particle of ``system``; an int N:
    0 .. N - 1; or indices) the acceleration ``acceleration`` (3 numbers in nm/ps^2, or a Quantity): the force
    m_i a on particle i with its mass in ``system`` (massless particles get none), in force group ``group``. Its
    energy is -sum m_i a . r_i (unwrapped r: module docstring)."""
    vector = _vector("acceleration_force", "acceleration", acceleration, _ACCELERATION, "nm/ps^2")
    chosen = _particles("acceleration_force", system.getNumParticles() if particles is None else particles)
    if chosen and max(chosen) >= system.getNumParticles():
        raise openmm.OpenMMException(f"acceleration_force: particles names particle {max(chosen)}, but the System has "
                                     f"{system.getNumParticles()} particles")
    external = _uniform("acceleration_force", group)
    for index in chosen:
        mass = system.getParticleMass(index).value_in_unit(unit.amu)
        external.addParticle(index, list(mass * vector))
    return external


def poiseuille_body_force(force, box_length, particles, direction=0, axis=2, group=BODY_FORCE_GROUP):
    """A CustomExternalForce for periodic Poiseuille flow: +``force`` (kJ/mol/nm, a number or Quantity) along
    ``direction`` (0, 1, 2: x, y, z) on each particle in ``particles`` (an int N: 0 .. N - 1, or indices) whose
    coordinate along ``axis`` (another of 0, 1, 2), wrapped into the periodic length ``box_length`` (nm, the box's
    edge along ``axis``), is in [0, L/2), and -``force`` in [L/2, L); in force group ``group``. OpenMM differentiates
    step() and floor() as zero, so the force has no component along ``axis``; its energy is -F d s(a) with the
    unwrapped coordinate d along ``direction`` (not periodic: module docstring). The global parameters are
    poiseuille_F and poiseuille_L (Context.setParameter changes them in a running Context). The steady flow is
    v = (n F/(2 eta)) analysis.flows.poiseuille_shape(a, L) along ``direction``."""
    name = "poiseuille_body_force"
    magnitude = _number(name, "force", force, _FORCE, "kJ/mol/nm")
    length = _number(name, "box_length", box_length, unit.nanometer, "nm")
    if not length > 0:
        raise openmm.OpenMMException(f"{name}: box_length = {length!r} nm is not allowed; it must be > 0 (the box's "
                                     f"edge along the axis)")
    for label, value in (("direction", direction), ("axis", axis)):
        if not (isinstance(value, numbers.Integral) and not isinstance(value, bool) and 0 <= value <= 2):
            raise openmm.OpenMMException(f"{name}: {label} = {reprlib.repr(value)} is not allowed; it must be 0, 1 or "
                                         f"2 (x, y or z)")
    if direction == axis:
        raise openmm.OpenMMException(f"{name}: direction = axis = {axis} is not allowed; the force must be across the "
                                     f"axis along which its sign changes (e.g. direction 0 (x), axis 2 (z))")
    chosen = _particles(name, particles)
    _checked_group(name, group)
    d, a = _AXES[direction], _AXES[axis]
    external = openmm.CustomExternalForce(
        f"-poiseuille_F*{d}*(1 - 2*step({a} - poiseuille_L*floor({a}/poiseuille_L) - poiseuille_L/2))")
    external.addGlobalParameter("poiseuille_F", magnitude)
    external.addGlobalParameter("poiseuille_L", length)
    external.setForceGroup(group)
    for index in chosen:
        external.addParticle(index, [])
    return external


def _uniform(name, group):
    """The CustomExternalForce -(fx x + fy y + fz z) with per-particle fx, fy, fz, in ``group``."""
    _checked_group(name, group)
    external = openmm.CustomExternalForce("-(body_fx*x + body_fy*y + body_fz*z)")
    for component in ("body_fx", "body_fy", "body_fz"):
        external.addPerParticleParameter(component)
    external.setForceGroup(group)
    return external


def _checked_group(name, group):
    if not (isinstance(group, numbers.Integral) and not isinstance(group, bool) and 0 <= group <= 31):
        raise openmm.OpenMMException(f"{name}: group = {reprlib.repr(group)} is not allowed; it must be an integer "
                                     f"from 0 to 31 (an OpenMM force group; one of its own: docs/flows.md)")


def _plain(name, label, value, units, text, form):
    """``value`` without its unit: a Quantity converted to ``units`` (an OpenMMException naming it where they are not
    compatible), anything else as it is."""
    if unit.is_quantity(value):
        if not value.unit.is_compatible(units):
            raise openmm.OpenMMException(f"{name}: {label} = {value} is not allowed; it must be in {text} ({form} or "
                                         f"a compatible Quantity)")
        value = value.value_in_unit(units)
    return value


def _number(name, label, value, units, text):
    """``value`` (a number or a Quantity in ``units``) as a finite float, else an OpenMMException."""
    value = _plain(name, label, value, units, text, "a number")
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not np.isfinite(value):
        raise openmm.OpenMMException(f"{name}: {label} = {reprlib.repr(value)} is not allowed; it must be a finite "
                                     f"number in {text}")
    return float(value)


def _vector(name, label, value, units, text):
    """``value`` (3 numbers, a Vec3, or a Quantity of them in ``units``) as a finite numpy vector."""
    value = _plain(name, label, value, units, text, "3 numbers")
    try:
        items = list(value)
    except TypeError:
        items = []
    numeric = len(items) == 3 and all(isinstance(x, numbers.Real) and not isinstance(x, bool) for x in items)
    vector = np.array([float(x) for x in items]) if numeric else np.zeros(0)
    if not numeric or not np.all(np.isfinite(vector)):
        raise openmm.OpenMMException(f"{name}: {label} = {reprlib.repr(value)} is not allowed; it must be 3 finite "
                                     f"numbers in {text} (x, y, z)")
    return vector


def _particles(name, particles):
    """``particles`` (an int N: 0 .. N - 1; or an iterable of distinct indices >= 0) as a list."""
    if isinstance(particles, numbers.Integral) and not isinstance(particles, bool):
        if particles < 0:
            raise openmm.OpenMMException(f"{name}: particles = {particles} is not allowed; it must be a count >= 0 or "
                                         f"particle indices")
        return list(range(int(particles)))
    try:
        items = list(particles)
    except TypeError:
        items = [None]
    integral = all(isinstance(i, numbers.Integral) and not isinstance(i, bool) for i in items)
    chosen = [int(i) for i in items] if integral else []
    if not integral or min(chosen, default=0) < 0 or len(set(chosen)) != len(chosen):
        raise openmm.OpenMMException(f"{name}: particles = {reprlib.repr(particles)} is not allowed; it must be a "
                                     f"count N (particles 0 .. N - 1) or distinct particle indices >= 0")
    return chosen
