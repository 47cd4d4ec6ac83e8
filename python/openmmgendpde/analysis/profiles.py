# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Profiles along one axis of a periodic box (an OpenMM reporter): what a study of a slab, a heat flow or a shear
flow reads. Each report bins the particles by their wrapped coordinate along ``axis`` (reduced box: fractional
coordinate) into ``bins`` equal slices and writes, per bin, one CSV row with the columns

    step, time (ps), bin, centre (nm), particles, density (number density, nm^-3), theta_harmonic (K),
    kinetic_temperature (K), vx, vy, vz (nm/ps), and with a GenDPDEForce given, Pxx, Pyy, Pzz, Pxy, Pxz, Pyz
    (kJ/mol/nm^3), and with particle types given, for each type t: density_type<t> (nm^-3) and
    theta_harmonic_type<t> (K), <t> the type's number, or minus<|t|> for a negative type (type -3: density_typeminus3)

Every column name is a plain identifier (letters, digits, underscores); the header line is followed by a comment line
``# units: step=1, time=ps, ...`` giving each column's units, so that
``numpy.genfromtxt(path, delimiter=",", names=True, comments="#")`` reads every column by its name.

The number density is the count over the slice volume; theta_harmonic is the harmonic mean 1/<1/theta_i> of the
slice's internal temperatures (NaN without a GenDPDEIntegrator): the thermodynamic temperature of the slice (at
equilibrium the Gamma law of eps_i makes 1/<1/theta> the bath temperature, while the arithmetic mean of theta_i is
biased high by the factor 1 + k_B/C_V; docs/theory.md section 8); the kinetic temperature is m |v - v_bin|^2
summed over the slice's particles over 3 (n_bin - 1) k_B (the slice's mean velocity removed, its 3 degrees of
freedom with it; NaN for fewer than 2 particles); v is the slice's mean velocity. The pressure tensor of a slice is (sum
over its particles of m (v - v_bin)(v - v_bin) + W_i) over the slice volume, W_i each particle's half of its pairs'
virial tensors (GenDPDEForce.getParticleVirials, from the platform's kernels; the slices' pressures average to the
system's). Only the GenDPDEForce given is in it: a body force or any other external field rightly adds nothing to the
stress (docs/flows.md), and another pair force of the System would be missing.
"""


import numbers
import reprlib

import numpy as np
import openmm
from openmm import unit

from ..api import GenDPDEForce, GenDPDEIntegrator
from ..internal.reporting import checked_choice, checked_file, checked_report_interval, open_file
from ..units import BOLTZMANN
from .pressure import virial_tensor


def profile(positions, velocities, masses, box, axis=2, bins=20, temperatures=None, virials=None, types=None):
    """The profile of one configuration as a dict of arrays (one value per bin), in OpenMM units: 'centre',
    'count', 'density', 'theta_harmonic' (the harmonic mean of theta_i, NaN without temperatures or particles),
    'kinetic_temperature', 'velocity' (bins x 3), 'pressure' (bins x 3 x 3, NaN without virials). positions (nm),
    velocities (nm/ps) N x 3 arrays; masses (amu) N; box three rows (nm, reduced form);
    temperatures theta_i (K) or None; virials the per-particle virial tensors (N x 3 x 3, kJ/mol) or None. With
    ``types`` (one integer per particle, docs/types.md) also 'types' (the distinct types, ascending),
    'type_density' (bins x types) and 'type_theta' (bins x types: each type's harmonic-mean theta, the temperature
    that is the same for every type at equilibrium; NaN without temperatures or particles)."""
    positions, velocities = np.asarray(positions, float), np.asarray(velocities, float)
    masses, box = np.asarray(masses, float), np.asarray(box, float)
    if not (0 <= axis <= 2) or bins < 1:
        raise ValueError(f"axis = {axis}, bins = {bins}: the axis must be 0, 1 or 2 and bins >= 1")
    fractional = positions @ np.linalg.inv(box)
    unit_coordinate = fractional[:, axis] - np.floor(fractional[:, axis])
    index = np.minimum((unit_coordinate * bins).astype(int), bins - 1)
    volume = abs(np.linalg.det(box)) / bins
    kb = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)
    width = box[axis, axis]
    result = {"centre": (np.arange(bins) + 0.5) * width / bins, "count": np.zeros(bins, int),
              "density": np.zeros(bins), "theta_harmonic": np.full(bins, np.nan),
              "kinetic_temperature": np.full(bins, np.nan),
              "velocity": np.full((bins, 3), np.nan), "pressure": np.full((bins, 3, 3), np.nan)}
    if types is not None:
        types = np.asarray(types)
        result["types"] = np.unique(types)
        result["type_density"] = np.zeros((bins, len(result["types"])))
        result["type_theta"] = np.full((bins, len(result["types"])), np.nan)
        for k, t in enumerate(result["types"]):
            for b in range(bins):
                members = (index == b) & (types == t)
                result["type_density"][b, k] = members.sum() / volume
                if temperatures is not None and members.any():
                    result["type_theta"][b, k] = 1 / np.mean(1 / np.asarray(temperatures, float)[members])
    for b in range(bins):
        members = index == b
        n = int(members.sum())
        result["count"][b] = n
        result["density"][b] = n / volume
        if n == 0:
            continue
        m, v = masses[members], velocities[members]
        mean_velocity = (m[:, None] * v).sum(axis=0) / m.sum()
        result["velocity"][b] = mean_velocity
        if temperatures is not None:
            result["theta_harmonic"][b] = float(1 / np.mean(1 / np.asarray(temperatures, float)[members]))
        relative = v - mean_velocity
        if n > 1:
            result["kinetic_temperature"][b] = float((m * (relative**2).sum(axis=1)).sum() / (3 * (n - 1) * kb))
        if virials is not None:
            kinetic = np.einsum("i,ia,ib->ab", m, relative, relative)
            result["pressure"][b] = (kinetic + np.asarray(virials)[members].sum(axis=0)) / volume
    return result


#: The most bins of a ProfileReporter: each report computes ~20 values per bin (the pressure tensor 9, each particle
#: type 2 more) and writes one CSV row per bin, so 10^5 bins take ~100 MB and ~10 MB of text per report at most, while
#: a count far beyond any system's particles (a typo, 10^9) would exhaust the memory at the first report. A bin needs
#: particles to mean anything: 10^5 bins of a 4-million-particle box hold 40 each.
MAX_BINS = 100000


def _checked_types(types):
    """ProfileReporter's ``types``, checked: None, one integer per particle (as an array), or a dict {particle: type}
    (GenDPDEForce.getParticleTypes: particles it leaves out have type 0)."""
    if types is None:
        return None
    if isinstance(types, dict):
        particles, values = np.asarray(list(types)), np.asarray(list(types.values()))
    else:
        particles, values = np.zeros(0, int), np.asarray(types)
    if not all(a.ndim == 1 and (a.size == 0 or np.issubdtype(a.dtype, np.integer)) for a in (particles, values)) \
            or np.any(particles < 0):
        raise openmm.OpenMMException(f"ProfileReporter: types = {reprlib.repr(types)} is not allowed; it must be "
                                     f"one integer per particle (a list or 1-D array) or a dict {{particle index >= "
                                     f"0: type}} (as GenDPDEForce.getParticleTypes returns)")
    return types if isinstance(types, dict) else values


def _per_particle_types(types, num_particles):
    """Checked ``types`` (_checked_types) as an array of one type per particle of a System of ``num_particles``."""
    if isinstance(types, dict):
        if types and max(types) >= num_particles:
            raise openmm.OpenMMException(f"ProfileReporter: types names particle {max(types)}, but the System has "
                                         f"{num_particles} particles")
        array = np.zeros(num_particles, int)
        array[list(types)] = list(types.values())
        return array
    if len(types) != num_particles:
        raise openmm.OpenMMException(f"ProfileReporter: types has {len(types)} entries, but the System has "
                                     f"{num_particles} particles; give one type per particle")
    return types


def _type_label(t):
    """A particle type as part of a column name (a plain identifier): type3, typeminus3."""
    return f"type{t}" if t >= 0 else f"typeminus{-t}"


def _columns(pressure, types):
    """The reporter's columns as (name, units), in order: with the pressure tensor if ``pressure``, with the two
    columns of each type in ``types`` (ascending)."""
    columns = [("step", "1"), ("time", "ps"), ("bin", "1"), ("centre", "nm"), ("particles", "1"),
               ("density", "nm^-3"), ("theta_harmonic", "K"), ("kinetic_temperature", "K"), ("vx", "nm/ps"),
               ("vy", "nm/ps"), ("vz", "nm/ps")]
    if pressure:
        columns += [(f"P{a}", "kJ/mol/nm^3") for a in ("xx", "yy", "zz", "xy", "xz", "yz")]
    for t in types:
        columns += [(f"density_{_type_label(t)}", "nm^-3"), (f"theta_harmonic_{_type_label(t)}", "K")]
    return columns


class ProfileReporter:
    """Writes profiles along ``axis`` every ``reportInterval`` steps to ``file`` (a path or an open file), as CSV.
    Works with any integrator; theta_harmonic needs a GenDPDEIntegrator, the pressure columns a GenDPDEForce ``force``
    (periodic box). ``types``, one integer per particle or a dict {particle: type} (the form of
    GenDPDEForce.getParticleTypes, unnamed particles type 0), adds the columns of each type; by default the types
    set on ``force``, if any. Bad arguments raise OpenMMException when the reporter is made; types that do not fit the
    System (a length other than its particle count, a particle beyond it) at the first report, before it writes
    anything (the header goes with the first report)."""

    def __init__(self, file, reportInterval, axis=2, bins=20, force=None, types=None):
        name = "ProfileReporter"
        interval = checked_report_interval(name, reportInterval)
        file = checked_file(name, file)
        integral = lambda value: isinstance(value, numbers.Integral) and not isinstance(value, bool)   # noqa: E731
        checked_choice(name, "axis", axis, lambda a: integral(a) and 0 <= a <= 2, "0, 1 or 2 (x, y or z)")
        checked_choice(name, "bins", bins, lambda b: integral(b) and 1 <= b <= MAX_BINS,
                       f"an integer from 1 to {MAX_BINS} (each report computes and writes every bin: more would "
                       f"exhaust the memory, and no system has the particles to fill them)")
        if force is not None:
            if isinstance(force, openmm.Force) and not isinstance(force, GenDPDEForce) \
                    and GenDPDEForce.isinstance(force):
                force = GenDPDEForce.cast(force)   # (from System.getForce)
            checked_choice(name, "force", force, lambda f: isinstance(f, GenDPDEForce),
                           "None or a GenDPDEForce (the one in the System: its virials give the pressure columns)")
        if types is None and force is not None:
            types = force.getParticleTypes() or None
        self._types = _checked_types(types)
        self._out, self._own = open_file(name, file)
        self._interval, self._axis, self._bins = interval, int(axis), int(bins)
        self._masses = None
        self._force = force

    def describeNextReport(self, simulation):
        steps = self._interval - simulation.currentStep % self._interval
        return (steps, True, True, False, False)

    def report(self, simulation, state):
        system = simulation.system
        if self._masses is None:
            if self._types is not None:
                self._types = _per_particle_types(self._types, system.getNumParticles())
            self._masses = np.array([system.getParticleMass(i).value_in_unit(unit.amu)
                                     for i in range(system.getNumParticles())])
            columns = _columns(self._force is not None, [] if self._types is None else np.unique(self._types))
            self._out.write(",".join(name for name, _ in columns) + "\n")
            self._out.write("# units: " + ", ".join(f"{name}={units}" for name, units in columns) + "\n")
        integrator = simulation.integrator
        temperatures = None
        if isinstance(integrator, GenDPDEIntegrator) or GenDPDEIntegrator.isinstance(integrator):
            temperatures = GenDPDEIntegrator.cast(integrator).getParticleTemperatures().value_in_unit(unit.kelvin)
        values = profile(state.getPositions(asNumpy=True).value_in_unit(unit.nanometer),
                         state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond),
                         self._masses, state.getPeriodicBoxVectors(asNumpy=True).value_in_unit(unit.nanometer),
                         self._axis, self._bins, temperatures,
                         virial_tensor(self._force, simulation.context, per_particle=True) if self._force else None,
                         self._types)
        step, time = simulation.currentStep, state.getTime().value_in_unit(unit.picosecond)
        for b in range(self._bins):
            v = values["velocity"][b]
            self._out.write(f"{step},{time:.6g},{b},{values['centre'][b]:.6g},{values['count'][b]},"
                            f"{values['density'][b]:.6g},{values['theta_harmonic'][b]:.6g},"
                            f"{values['kinetic_temperature'][b]:.6g},{v[0]:.6g},{v[1]:.6g},{v[2]:.6g}")
            if self._force is not None:
                p = values["pressure"][b]
                self._out.write("," + ",".join(f"{x:.6g}" for x in (p[0, 0], p[1, 1], p[2, 2], p[0, 1], p[0, 2],
                                                                    p[1, 2])))
            if self._types is not None:
                for k in range(len(values["types"])):
                    self._out.write(f",{values['type_density'][b, k]:.6g},{values['type_theta'][b, k]:.6g}")
            self._out.write("\n")
        self._out.flush()

    def __del__(self):
        if getattr(self, "_own", False):
            self._out.close()
