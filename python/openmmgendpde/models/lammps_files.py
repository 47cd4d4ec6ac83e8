# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A GenDPDE model as LAMMPS input for the project's LAMMPS package (pair style ``gendpde`` and fix ``gendpde``), so
that a calibrated fluid runs in either engine: the one writer of LAMMPS input of the project, used by the
`lammps-input` command, the tests of the package and the tools that compare the engines (docs/lammps.md).

The LAMMPS system is the OpenMM one: ``model_input`` builds the model as every study does
(GenDPDEParameters.liquid: the FCC lattice, the box, the System's GenDPDEForce and its GenDPDEIntegrator), draws the
velocities as Model.context does (Maxwell-Boltzmann at T0, OpenMM's setVelocitiesToTemperature with the seed), and
``lammps_input`` reads everything it writes from those OpenMM objects (positions, box, masses, particle types,
cutoff, estimator, f_cut, each type's law and parameters, background pressure, heat capacities, friction,
conduction, bath temperature, step, mode, seed), never from a second copy of the parameters. Particle i of OpenMM
is atom i + 1 of LAMMPS (the package uses ID - 1 as the index of a particle's random streams, as OpenMM uses i);
OpenMM's particle types, sorted, are LAMMPS's atom types 1, 2, ...

Units (``units``: metal, real or lj) are converted by models/lammps_units.py, whose docstring gives every factor and
why pressures are energy/volume in every units.

The neighbour skin (``neighbor SKIN bin``) is by default 0.1 R, rounded up to 4 significant digits: the skin of
the plugin's OpenMM platforms (their lists hold candidates within 1.1 R, rebuilt once a particle has moved 0.05 R),
which scales with the model's length, unlike LAMMPS's metal default of 2 Å (0.2 R for argon's R = 10.4 Å, 0.24 R
for water's 8.3 Å: more pairs in the list for nothing). ``comm_modify cutoff GHOST``: the fix's sweep over pairs
needs ghosts 1.5 sweep-cell widths plus the skin around each subdomain; the sweep's cells and that cutoff come from
the physics core (GenDPDESweepDefinition.h, through the bindings: sweepCandidateRange, sweepCellCount,
sweepGhostCutoff, sweepMinCellsAcrossSubdomains), the functions fix gendpde calls, so the two cannot differ; GHOST is
the core's value rounded up to 4 significant digits (ghost_cutoff). The sweep's cells are at least the candidates'
reach, 1.1 R, wide, and the box must be at least sweepMinCellsAcrossSubdomains() = 4 cells, so about 4.4 R, wide.
The fix requires a skin of at least 0.1 R (its order is built again once an atom has moved 0.05 R).
"""

import dataclasses
import decimal
import os

import numpy as np
from openmm import unit

from ..api import GenDPDEForce
from ..gendpde import sweepCandidateRange, sweepCellCount, sweepGhostCutoff, sweepMinCellsAcrossSubdomains
from ..internal.files import atomic_write
from .lammps_script import (
    DATA_FILE,
    HEADER,
    MODES,
    SCRIPT_FILE,
    TEMPERATURES_FILE,
    Script,
    closing_sections,
    model_sections,
    number_text,
    opening_sections,
)
from .lammps_units import UNITS, in_units

#: The default neighbour skin as a fraction of R: that of the plugin's OpenMM platforms.
SKIN_FRACTION = 0.1
#: The largest seed the fix takes.
MAX_SEED = 2**31 - 1
#: The script's sections, in order (LammpsInput.sections).
SECTIONS = ("header", "variables", "setup", "pair", "neighbors", "fix", "output", "run")


def round_up(value, digits=4):
    """The smallest decimal of ``digits`` significant digits whose float is >= ``value`` > 0, as that float (its
    repr is the decimal): ``value`` itself where it is such a decimal's float already (29.35), else the decimal
    above its exact binary expansion (29.3501 -> 29.36), whose float is >= value (rounding to a float is monotonic)."""
    exact = decimal.Decimal(value)
    step = decimal.Decimal(1).scaleb(exact.adjusted() - digits + 1)
    if float(exact.quantize(step, rounding=decimal.ROUND_FLOOR)) == value:
        return float(value)
    return float(exact.quantize(step, rounding=decimal.ROUND_CEILING))


def default_skin(cutoff):
    """The neighbour skin for the cutoff R (both in the script's length unit): SKIN_FRACTION R, rounded up to 4
    significant digits."""
    return round_up(SKIN_FRACTION * cutoff)


def sweep_cells(width, cutoff, length="Å"):
    """The fix's sweep cells across a periodic box ``width`` for the cutoff R (the core's sweepCellCount for the
    candidates' reach sweepCandidateRange(R) = 1.1 R, as fix gendpde counts them); ValueError where fewer than
    sweepMinCellsAcrossSubdomains() fit (``length``: the unit the message names)."""
    reach = sweepCandidateRange(cutoff)
    cells = sweepCellCount(width, reach, True)
    least = sweepMinCellsAcrossSubdomains()
    if cells < least:
        raise ValueError(f"the box is {width:.6g} {length} wide, {width / cutoff:.3f} R for the cutoff R = "
                         f"{cutoff:.6g} {length}; LAMMPS's fix gendpde needs at least {least} cells of 1.1 R "
                         f"({least * reach:.6g} {length}): use more particles")
    return cells


def ghost_cutoff(widths, cutoff, skin, length="Å"):
    """comm_modify cutoff for box ``widths``, the cutoff R and the skin (one length unit): the core's
    sweepGhostCutoff (1.5 widths of the widest sweep cell + the skin, which fix gendpde requires), rounded up to 4
    significant digits; ValueError for a box too small for the sweep (sweep_cells)."""
    for width in widths:
        sweep_cells(width, cutoff, length)
    return round_up(sweepGhostCutoff(*widths, cutoff, skin))


@dataclasses.dataclass(frozen=True)
class LammpsInput:
    """The texts of a LAMMPS data file (DATA_FILE) and input script (SCRIPT_FILE, ``script``: its ``sections`` in
    the order of SECTIONS), any other file the script reads (``files``: name -> text, e.g. TEMPERATURES_FILE), and
    the numbers chosen for them, in the script's ``units``."""
    data: str
    sections: dict
    units: str
    cutoff: float
    skin: float
    ghost: float    # comm_modify cutoff
    files: dict = dataclasses.field(default_factory=dict)

    @property
    def script(self):
        """The whole input script: every section, in the order of SECTIONS."""
        return self.commands(*SECTIONS)

    def commands(self, *names):
        """The text of the script's sections ``names`` (of SECTIONS, in the order given)."""
        return "".join(self.sections[name] for name in names)


def _types(force, integrator, num_particles):
    """The OpenMM type of each particle (the force's; the integrator's, where it has any, must agree)."""
    types = [0] * num_particles
    for particle, type_ in dict(force.getParticleTypes()).items():
        types[particle] = int(type_)
    given = dict(integrator.getParticleTypes())
    if given and any(given.get(i, 0) != types[i] for i in range(num_particles)):
        raise ValueError("the particle types of the GenDPDEIntegrator differ from the GenDPDEForce's")
    return types


def _box_widths(system):
    """The widths (nm) of the System's orthogonal periodic box; ValueError for a triclinic one."""
    vectors = [[v.value_in_unit(unit.nanometer) for v in row] for row in system.getDefaultPeriodicBoxVectors()]
    if any(vectors[i][j] != 0 for i in range(3) for j in range(3) if i != j):
        raise ValueError("the periodic box is triclinic; the LAMMPS data file is written for an orthogonal box")
    return [vectors[k][k] for k in range(3)]


def _wrapped(x, width):
    """x wrapped into [0, width)."""
    x = x % width
    return 0.0 if x >= width else x


def _array(values, quantity_unit, num_particles, what, columns=3):
    """``values`` (a Quantity or numbers in OpenMM units) as a float array of num_particles rows."""
    array = np.asarray(values.value_in_unit(quantity_unit) if unit.is_quantity(values) else values, dtype=float)
    if array.shape != ((num_particles, columns) if columns else (num_particles,)):
        raise ValueError(f"{array.shape[0] if array.ndim else 1} {what} for {num_particles} particles")
    return array


def lammps_input(system, integrator, positions, velocities=None, steps=1000, thermo=100, skin=None, title="",
                 plugin=None, units="metal", temperatures=None, restart=None):
    """LammpsInput for the OpenMM ``system`` (one GenDPDEForce, CutoffPeriodic, an orthogonal box), its
    GenDPDEIntegrator, ``positions`` (N x 3, nm) and ``velocities`` (N x 3, nm/ps; None: no Velocities section),
    in LAMMPS's ``units`` (metal, real or lj: UNITS and the module docstring): a run of ``steps`` steps, thermo
    output every ``thermo`` steps, neighbour ``skin`` (in the units' length; default default_skin), ``title`` in the
    files' first comment, ``plugin``: the default of the script's variable ``plugin`` (None: given on the command
    line, lmp -var plugin PATH); ``temperatures``: each particle's initial temperature (N, K), written as the
    atomfile TEMPERATURES_FILE that the fix reads (initial v_theta; default: the one temperature the integrator
    starts from); ``restart``: the name of a restart file the script reads (read_restart) instead of the data file.
    ValueError for what the package cannot express."""
    if units not in UNITS:
        raise ValueError(f"units = {units!r} is not allowed; it must be one of {', '.join(UNITS)}")
    force, seed, cutoff_nm = _checked_model(system, integrator)
    num_particles = system.getNumParticles()
    positions = _array(positions, unit.nanometer, num_particles, "positions")
    types = _types(force, integrator, num_particles)
    kinds = sorted(set(types))
    index = {kind: k + 1 for k, kind in enumerate(kinds)}   # OpenMM type -> LAMMPS type
    masses = _masses(system, types)
    length = UNITS[units]["length"][0]
    widths = [in_units(width, "length", units) for width in _box_widths(system)]
    cutoff = in_units(cutoff_nm, "length", units)
    skin = default_skin(cutoff) if skin is None else float(skin)
    ghost = ghost_cutoff(widths, cutoff, skin, length)
    title = " ".join(title.split())
    data = _data_text(f"{HEADER}{': ' + title if title else ''}", units, widths, index, masses, positions, types,
                      velocities)
    files = {}
    if temperatures is not None:
        files[TEMPERATURES_FILE] = _temperatures_text(temperatures, num_particles, units)
    script = Script(units, title, plugin, steps, thermo, seed, cutoff, skin, ghost, temperatures is not None,
                     restart)
    sections = {**opening_sections(script, integrator), **model_sections(script, force, integrator, kinds, index),
                **closing_sections(script)}
    return LammpsInput(data, sections, units, cutoff, skin, ghost, files)


def _checked_model(system, integrator):
    """(the GenDPDEForce, the integrator's seed, the cutoff in nm) of a System and integrator the package can run;
    ValueError naming what it cannot express."""
    if system.getNumForces() != 1 or not GenDPDEForce.isinstance(system.getForce(0)):
        raise ValueError("the System must hold one force, a GenDPDEForce (the pair style computes nothing else)")
    force = GenDPDEForce.cast(system.getForce(0))
    if force.getNonbondedMethod() != GenDPDEForce.CutoffPeriodic:
        raise ValueError("the GenDPDEForce must be CutoffPeriodic (the data file is a periodic box)")
    if integrator.getAdiabaticPositionChanges():
        raise ValueError("the integrator's adiabatic position changes have no keyword in the LAMMPS fix")
    seed = integrator.getRandomNumberSeed()
    if not 1 <= seed <= MAX_SEED:
        raise ValueError(f"the integrator's random seed is {seed}; the fix takes 1 to {MAX_SEED} (0 means OpenMM picks "
                         f"one when a Context is created, and LAMMPS could not draw the same random numbers)")
    cutoff_nm = force.getCutoffDistance().value_in_unit(unit.nanometer)
    own_cutoff = integrator.getCutoffDistance().value_in_unit(unit.nanometer)
    if own_cutoff not in (0, cutoff_nm):
        raise ValueError(f"the integrator's cutoff {own_cutoff} nm differs from the force's {cutoff_nm} nm; the "
                         f"pair style and the fix have one")
    return force, seed, cutoff_nm


def _masses(system, types):
    """{OpenMM type: mass (amu)}; ValueError for a fixed particle or a type whose particles differ in mass."""
    masses = {}
    for i, type_ in enumerate(types):
        mass = system.getParticleMass(i).value_in_unit(unit.amu)
        if mass <= 0:
            raise ValueError(f"particle {i} has mass {mass}: a fixed particle has no counterpart in this input")
        if masses.setdefault(type_, mass) != mass:
            raise ValueError(f"particles of type {type_} have different masses; LAMMPS's masses are per type")
    return masses


def _data_text(first_line, units, widths, index, masses, positions, types, velocities):
    """The data file: the box (``widths`` in ``units``), the masses and atoms of each LAMMPS type (``index``: OpenMM
    type -> LAMMPS type), the positions (nm, wrapped into the box) and, if given, the velocities (nm/ps)."""
    def convert(value, kind):
        return in_units(value, kind, units)
    data = [first_line, "", f"{len(positions)} atoms", f"{len(index)} atom types", ""]
    data += [f"0.0 {number_text(width)} {axis}lo {axis}hi" for width, axis in zip(widths, "xyz")]
    data += ["", "Masses", ""] + [f"{index[kind]} {number_text(convert(masses[kind], 'mass'))}" for kind in index]
    data += ["", "Atoms # atomic", ""]
    for i, (r, kind) in enumerate(zip(positions, types)):
        x, y, z = (_wrapped(convert(c, "length"), width) for c, width in zip(r, widths))
        data.append(f"{i + 1} {index[kind]} {number_text(x)} {number_text(y)} {number_text(z)}")
    if velocities is not None:
        velocities = _array(velocities, unit.nanometer / unit.picosecond, len(positions), "velocities")
        data += ["", "Velocities", ""]
        data += [f"{i + 1} " + " ".join(number_text(convert(c, "velocity")) for c in v)
                 for i, v in enumerate(velocities)]
    return "\n".join(data) + "\n"


def _temperatures_text(temperatures, num_particles, units):
    """TEMPERATURES_FILE: an atomfile of each particle's initial temperature (K; the count, then "ID value" per atom,
    LAMMPS's variable atomfile)."""
    temperatures = _array(temperatures, unit.kelvin, num_particles, "temperatures", columns=None)
    if not np.all(temperatures > 0):
        raise ValueError("every initial temperature must be > 0")
    return "\n".join(
        [f"# each particle's initial temperature ({UNITS[units]['temperature'][0]})", str(num_particles)]
        + [f"{i + 1} {number_text(in_units(t, 'temperature', units))}" for i, t in enumerate(temperatures)]) + "\n"


def model_input(parameters, num_particles, mode="isoenergetic", seed=1, step_size=None, steps=1000, thermo=100,
                skin=None, plugin=None, title=None, units="metal"):
    """LammpsInput of a model (GenDPDEParameters, e.g. fluid_files.load_parameters of a model file) as its liquid()
    builds it with ``num_particles`` (4 m^3), the integrator in ``mode`` (a key of MODES) with random ``seed``,
    step ``step_size`` (ps; default liquid()'s, dt* = 0.01), and the velocities that Model.context draws with
    ``seed`` (Reference platform); the other arguments as lammps_input's. ValueError (or OpenMMException from the
    integrator's checks) for a bad argument."""
    if mode not in MODES:
        raise ValueError(f"mode = {mode!r} is not allowed; it must be one of {', '.join(MODES)}")
    if units not in UNITS:
        raise ValueError(f"units = {units!r} is not allowed; it must be one of {', '.join(UNITS)}")
    model = parameters.liquid(num_particles, mode=MODES[mode], seed=seed)
    if step_size is not None:
        model.integrator.setStepSize(step_size)
    context = model.context("Reference", seed=seed)
    state = context.getState(getPositions=True, getVelocities=True)
    positions = state.getPositions(asNumpy=True)
    velocities = state.getVelocities(asNumpy=True)
    del context
    title = parameters.fluid.name if title is None else title
    return lammps_input(model.system, model.integrator, positions, velocities, steps, thermo, skin,
                        f"{title}, {num_particles} particles", plugin, units)


def thermo_table(log):
    """{step: {column: value}} of every thermo line of a LAMMPS log or screen output (the first line of a step where
    runs repeat it): what a run of these files prints, for the tools and tests that read it back."""
    rows, columns = {}, None
    for line in log.splitlines():
        fields = line.split()
        if fields[:1] == ["Step"]:
            columns = fields
        elif line.startswith("Loop time"):
            columns = None
        elif columns and len(fields) == len(columns):
            try:
                values = [float(x) for x in fields]
            except ValueError:
                continue
            rows.setdefault(int(values[0]), dict(zip(columns, values)))
    return rows


def write_lammps_input(directory, texts):
    """Write DATA_FILE, SCRIPT_FILE and the other files of ``texts`` (a LammpsInput) into ``directory`` (made if
    absent), each atomically; the paths of the data file and the script."""
    os.makedirs(directory, exist_ok=True)
    paths = os.path.join(directory, DATA_FILE), os.path.join(directory, SCRIPT_FILE)
    for path, text in [*zip(paths, (texts.data, texts.script)),
                       *((os.path.join(directory, name), text) for name, text in texts.files.items())]:
        with atomic_write(path) as stream:
            stream.write(text)
    return paths
