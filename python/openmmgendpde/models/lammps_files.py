"""A GenDPDE model as LAMMPS input for the project's LAMMPS plugin (pair style ``gendpde`` and fix ``gendpde``), so
that a calibrated fluid runs in either engine (`lammps-input`; docs/lammps.md).

The LAMMPS system is the OpenMM one: ``model_input`` builds the model as every study does
(GenDPDEParameters.liquid: the FCC lattice, the box, the System's GenDPDEForce and its GenDPDEIntegrator), draws the
velocities as Model.context does (Maxwell-Boltzmann at T0, OpenMM's setVelocitiesToTemperature with the seed), and
``lammps_input`` reads everything it writes from those OpenMM objects (positions, box, masses, particle types,
cutoff, estimator, f_cut, each type's law and parameters, background pressure, heat capacities, friction,
conduction, bath temperature, step, mode, seed), never from a second copy of the parameters. Particle i of OpenMM
is atom i + 1 of LAMMPS (the plugin uses tag - 1 as the index of a particle's random streams, as OpenMM uses i);
OpenMM's particle types, sorted, are LAMMPS's atom types 1, 2, ...

Units: OpenMM's (nm, kJ/mol, ps, amu, K) to LAMMPS's ``units metal`` (Å, eV, ps, g/mol, K), METAL_UNITS, with the
energy factor 1 kJ/mol = 1000/(e N_A) eV = 1/96.48533212331002 eV (CODATA 2018, exact: e = 1.602176634e-19 C,
N_A = 6.02214076e23/mol):

    kind                 OpenMM            LAMMPS metal     factor (metal value = factor x OpenMM value)
    length               nm                Å                10
    velocity             nm/ps             Å/ps             10
    time                 ps                ps               1
    mass                 amu               g/mol            1
    temperature          K                 K                1
    energy               kJ/mol            eV               E = 1000/(e N_A) = 0.010364269656262174
    pressure             kJ/mol/nm^3       eV/Å^3           E/1000 (n0, pi0, B_T, p_b)
    number density       nm^-3             Å^-3             1/1000
    volume               nm^3              Å^3              1000
    friction             amu/ps            g/mol/ps         1
    heat capacity        kJ/mol/K          eV/K             E (C_V; entropy scales)
    heat conduction      kJ/mol K/ps       eV K/ps          E
    thermal pressure     kJ/mol/nm^3/K     eV/Å^3/K         E/1000 (beta of TaitThermalExpansion)
    energy x volume      kJ/mol nm^3       eV Å^3           1000 E (attractions)

The constants are not the same in the two engines, and no factor can make them so. OpenMM's k_B is CODATA 2018's,
0.00831446261815324 kJ/mol/K = 8.617333262e-5 eV/K; LAMMPS's metal units have their own, force->boltz =
8.617343e-5 eV/K (older CODATA), which the plugin uses: 1.13e-6 relatively larger (the sixth significant digit).
A model whose parameters were fitted with OpenMM's k_B sees in LAMMPS a k_B 1.13e-6 larger wherever k_B enters
(the thermostat's noise, sigma^2 = 2 gamma k_B T; the fluctuation-dissipation balance of the internal energies;
the temperature LAMMPS reports from the kinetic energy). Likewise LAMMPS's mvv2e = 1.0364269e-4 eV per g/mol
Å^2/ps^2 is 6.3e-8 relatively below the exact 10/(e N_A) = 1.0364269656e-4, and its nktv2p (eV/Å^3 to bar)
8.4e-8 below. All three are far below any statistical error of a run, but trajectories of the two engines are not
the same to the last bit even from the same state and seed.

The neighbour skin (``neighbor SKIN bin``) is by default 0.1 R, rounded up to 4 significant digits: the skin of
the plugin's OpenMM platforms (their lists hold candidates within 1.1 R, rebuilt once a particle has moved 0.05 R),
which scales with the model's length, unlike LAMMPS's metal default of 2 Å (0.2 R for argon's R = 10.4 Å, 0.24 R
for water's 8.3 Å: more pairs in the list for nothing). ``comm_modify cutoff GHOST``: the fix's sweep over pairs
needs ghosts 1.5 sweep-cell widths plus the skin around each subdomain: per box direction of width L (Å) it has
n = 4 floor(m/4) cells, m = floor(L/((1 + 1e-9) R)), of width w = L/n (m >= 4 is required: the box must be at
least 4 R wide), and GHOST = max(1.5 max(w), R) + SKIN (R + SKIN: the pair style's own need), rounded up to
4 significant digits (ghost_cutoff).
"""

import dataclasses
import decimal
import math
import os

import numpy as np
import openmm
from openmm import unit

from ..api import ESTIMATOR_NAMES, GenDPDEForce, GenDPDEIntegrator, law_description
from ..internal.files import atomic_write

#: 1 kJ/mol in eV: 1000/(e N_A), CODATA 2018 (exact e and N_A).
ELEMENTARY_CHARGE = 1.602176634e-19   # C
AVOGADRO = 6.02214076e23              # 1/mol
ENERGY = 1e3 / (ELEMENTARY_CHARGE * AVOGADRO)
#: LAMMPS's k_B in metal units (update.cpp: force->boltz), which the plugin uses, in eV/K.
LAMMPS_METAL_BOLTZMANN = 8.617343e-5

#: kind -> (OpenMM unit, LAMMPS metal unit, factor): a value in metal units is factor x the value in OpenMM units.
METAL_UNITS = {
    "length": ("nm", "Å", 10.0),
    "velocity": ("nm/ps", "Å/ps", 10.0),
    "time": ("ps", "ps", 1.0),
    "mass": ("amu", "g/mol", 1.0),
    "temperature": ("K", "K", 1.0),
    "energy": ("kJ/mol", "eV", ENERGY),
    "pressure": ("kJ/mol/nm^3", "eV/Å^3", ENERGY * 1e-3),
    "number_density": ("nm^-3", "Å^-3", 1e-3),
    "volume": ("nm^3", "Å^3", 1e3),
    "friction": ("amu/ps", "g/mol/ps", 1.0),
    "heat_capacity": ("kJ/mol/K", "eV/K", ENERGY),
    "heat_conduction": ("kJ/mol K/ps", "eV K/ps", ENERGY),
    "thermal_pressure": ("kJ/mol/nm^3/K", "eV/Å^3/K", ENERGY * 1e-3),
    "energy_volume": ("kJ/mol nm^3", "eV Å^3", ENERGY * 1e3),
}

#: The Tait parameters n0, pi0, B_T, gamma_T (a law that extends Tait takes them first).
TAIT_KINDS = ("number_density", "pressure", "pressure", None)   # gamma_T: a plain number
#: The integrator's modes as the fix names them.
MODES = {"isoenergetic": GenDPDEIntegrator.Isoenergetic, "isothermal": GenDPDEIntegrator.Isothermal,
         "conservative": GenDPDEIntegrator.Conservative}
#: The files lammps_input writes, as the input script reads them.
DATA_FILE = "gendpde.data"
SCRIPT_FILE = "in.gendpde"
#: The default neighbour skin as a fraction of R: that of the plugin's OpenMM platforms.
SKIN_FRACTION = 0.1
#: The fewest sweep cells per box direction that the fix takes.
MIN_SWEEP_CELLS = 4
#: The largest seed the fix takes.
MAX_SEED = 2**31 - 1


def in_metal(value, kind):
    """``value`` (a float in OpenMM units, or a Quantity) of ``kind`` (a key of METAL_UNITS, or None for a plain
    number) in LAMMPS's metal units."""
    if kind is None:
        return float(value)
    if unit.is_quantity(value):
        value = value.value_in_unit(_OPENMM_UNITS[kind])
    return float(value) * METAL_UNITS[kind][2]


_OPENMM_UNITS = {
    "length": unit.nanometer, "velocity": unit.nanometer / unit.picosecond, "time": unit.picosecond,
    "mass": unit.amu, "temperature": unit.kelvin, "energy": unit.kilojoule_per_mole,
    "pressure": unit.kilojoule_per_mole / unit.nanometer**3, "number_density": unit.nanometer**-3,
    "volume": unit.nanometer**3, "friction": unit.amu / unit.picosecond,
    "heat_capacity": unit.kilojoule_per_mole / unit.kelvin,
    "heat_conduction": unit.kilojoule_per_mole * unit.kelvin / unit.picosecond,
    "thermal_pressure": unit.kilojoule_per_mole / unit.nanometer**3 / unit.kelvin,
    "energy_volume": unit.kilojoule_per_mole * unit.nanometer**3,
}


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
    """The neighbour skin (Å) for the cutoff R (Å): SKIN_FRACTION R, rounded up to 4 significant digits."""
    return round_up(SKIN_FRACTION * cutoff)


def sweep_cells(width, cutoff):
    """The fix's sweep cells across a box ``width`` (Å) for the cutoff R (Å): 4 floor(m/4), m = floor(L/((1 + 1e-9)
    R)); ValueError where m < 4."""
    m = math.floor(width / ((1 + 1e-9) * cutoff))
    if m < MIN_SWEEP_CELLS:
        raise ValueError(f"the box is {width:.6g} Å wide, {width / cutoff:.3f} R for the cutoff R = {cutoff:.6g} Å; "
                         f"LAMMPS's fix gendpde needs at least {MIN_SWEEP_CELLS} R ({MIN_SWEEP_CELLS * cutoff:.6g} "
                         f"Å): use more particles")
    return MIN_SWEEP_CELLS * (m // MIN_SWEEP_CELLS)


def ghost_cutoff(widths, cutoff, skin):
    """comm_modify cutoff (Å) for box ``widths`` (Å), the cutoff R and the skin (Å): max(1.5 w, R) + skin, w the
    widest sweep cell (sweep_cells), rounded up to 4 significant digits."""
    cell = max(width / sweep_cells(width, cutoff) for width in widths)
    return round_up(max(1.5 * cell, cutoff) + skin)


@dataclasses.dataclass(frozen=True)
class LammpsInput:
    """The texts of a LAMMPS data file (DATA_FILE) and input script (SCRIPT_FILE), and the numbers chosen for them."""
    data: str
    script: str
    cutoff: float   # Å
    skin: float     # Å
    ghost: float    # Å, comm_modify cutoff


def _number(value):
    """A float as the shortest text that reads back to it."""
    return repr(float(value))


def _types(force, integrator, num_particles):
    """The OpenMM type of each particle (the force's; the integrator's, where it has any, must agree)."""
    types = [0] * num_particles
    for particle, type_ in dict(force.getParticleTypes()).items():
        types[particle] = int(type_)
    given = dict(integrator.getParticleTypes())
    if given and any(given.get(i, 0) != types[i] for i in range(num_particles)):
        raise ValueError("the particle types of the GenDPDEIntegrator differ from the GenDPDEForce's")
    return types


def _laws(force, kinds):
    """{OpenMM type: (law, Tait parameters, law parameters)} for the types ``kinds``, each as the force has it."""
    tait = {}
    for k in range(force.getNumTypeParameters()):
        type_, *parameters = force.getTypeParameters(k)
        tait[int(type_)] = parameters
    laws = {}
    for k in range(force.getNumTypeEquationsOfState()):
        type_, law, parameters = force.getTypeEquationOfState(k)
        laws[int(type_)] = (law, parameters)
    default_tait, default_law = force.getTaitParameters(), force.getEquationOfState()
    return {kind: (*laws.get(kind, default_law), tait.get(kind, default_tait)) for kind in kinds}


def _kind_of(openmm_unit):
    """The kind (a key of METAL_UNITS, or None for a plain number) of a parameter in ``openmm_unit``."""
    if openmm_unit is None or openmm_unit == unit.dimensionless:
        return None
    for kind, known in _OPENMM_UNITS.items():
        if openmm_unit.is_compatible(known) and math.isclose(openmm_unit.conversion_factor_to(known), 1.0):
            return kind
    raise ValueError(f"a law's parameter is in {openmm_unit}, which lammps_files cannot convert to metal units")


def _pair_coeff(index, law, parameters, tait):
    """One pair_coeff line (metal units) of the LAMMPS type ``index``: the law as GenDPDEForce names it and its
    parameters, all as the table of the laws describes them (api.law_description), so that no law is spelt here."""
    name, extends_tait, described = law_description(law)
    if len(parameters) != len(described):
        raise ValueError(f"the law {name} has {len(parameters)} parameters, not {len(described)}")
    values = [in_metal(v, k) for v, k in zip(tait, TAIT_KINDS)] if extends_tait else []
    values += [in_metal(v, _kind_of(u)) for v, (_, u) in zip(parameters, described)]
    return f"pair_coeff {index} {index} {name} " + " ".join(map(_number, values))


def _transport(integrator, kinds):
    """({OpenMM type: C_V}, {(type a, type b): (gamma, kappa)} for a <= b) as the integrator has them (Quantities)."""
    capacities = {kind: integrator.getHeatCapacity() for kind in kinds}
    for k in range(integrator.getNumTypeHeatCapacities()):
        type_, capacity = integrator.getTypeHeatCapacity(k)
        if int(type_) in capacities:
            capacities[int(type_)] = capacity
    pairs = {(a, b): (integrator.getFriction(), integrator.getHeatConduction())
             for a in kinds for b in kinds if a <= b}
    for k in range(integrator.getNumTypePairs()):
        a, b, friction, conduction = integrator.getTypePairParameters(k)
        key = (min(int(a), int(b)), max(int(a), int(b)))
        if key in pairs:
            pairs[key] = (friction, conduction)
    return capacities, pairs


def _initial_temperature(integrator):
    """The temperature the particles start at in OpenMM (K): those set before a Context (all one value: the fix's
    ``initial`` takes one), else the bath's."""
    try:
        temperatures = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    except openmm.OpenMMException:   # none set: the particles start at the bath temperature
        return integrator.getTemperature().value_in_unit(unit.kelvin)
    values = set(np.asarray(temperatures, dtype=float).tolist())
    if len(values) != 1:
        raise ValueError("the particles' initial temperatures differ; the fix's 'initial' keyword takes one")
    return values.pop()


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


def lammps_input(system, integrator, positions, velocities=None, steps=1000, thermo=100, skin=None, title="",
                 plugin=None):
    """LammpsInput for the OpenMM ``system`` (one GenDPDEForce, CutoffPeriodic, an orthogonal box), its
    GenDPDEIntegrator, ``positions`` (N x 3, nm) and ``velocities`` (N x 3, nm/ps; None: no Velocities section):
    a run of ``steps`` steps, thermo output every ``thermo`` steps, neighbour ``skin`` (Å; default default_skin),
    ``title`` in the files' first comment, ``plugin``: the default of the script's variable ``plugin`` (None: given
    on the command line, lmp -var plugin PATH). ValueError for what the plugin cannot express."""
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
    num_particles = system.getNumParticles()
    positions = np.asarray(positions.value_in_unit(unit.nanometer) if unit.is_quantity(positions) else positions,
                           dtype=float)
    if positions.shape != (num_particles, 3):
        raise ValueError(f"{positions.shape[0]} positions for {num_particles} particles")
    types = _types(force, integrator, num_particles)
    kinds = sorted(set(types))
    index = {kind: k + 1 for k, kind in enumerate(kinds)}   # OpenMM type -> LAMMPS type
    masses = {}
    for i in range(num_particles):
        mass = system.getParticleMass(i).value_in_unit(unit.amu)
        if mass <= 0:
            raise ValueError(f"particle {i} has mass {mass}: a fixed particle has no counterpart in this input")
        if masses.setdefault(types[i], mass) != mass:
            raise ValueError(f"particles of type {types[i]} have different masses; LAMMPS's masses are per type")
    widths = [in_metal(width, "length") for width in _box_widths(system)]
    cutoff = in_metal(cutoff_nm, "length")
    skin = default_skin(cutoff) if skin is None else float(skin)
    ghost = ghost_cutoff(widths, cutoff, skin)
    title = " ".join(title.split())
    header = "GenDPDE model for the LAMMPS plugin (python -m openmmgendpde lammps-input)"

    data = [f"{header}{': ' + title if title else ''}", "", f"{num_particles} atoms", f"{len(kinds)} atom types", ""]
    data += [f"0.0 {_number(width)} {axis}lo {axis}hi" for width, axis in zip(widths, "xyz")]
    data += ["", "Masses", ""] + [f"{index[kind]} {_number(in_metal(masses[kind], 'mass'))}" for kind in kinds]
    data += ["", "Atoms # atomic", ""]
    for i, (r, kind) in enumerate(zip(positions, types)):
        x, y, z = (_wrapped(in_metal(c, "length"), width) for c, width in zip(r, widths))
        data.append(f"{i + 1} {index[kind]} {_number(x)} {_number(y)} {_number(z)}")
    if velocities is not None:
        velocities = np.asarray(velocities.value_in_unit(unit.nanometer / unit.picosecond)
                                if unit.is_quantity(velocities) else velocities, dtype=float)
        if velocities.shape != (num_particles, 3):
            raise ValueError(f"{velocities.shape[0]} velocities for {num_particles} particles")
        data += ["", "Velocities", ""]
        data += [f"{i + 1} " + " ".join(_number(in_metal(c, "velocity")) for c in v) for i, v in enumerate(velocities)]

    laws = _laws(force, kinds)
    background = in_metal(force.getBackgroundPressure(), "pressure")
    capacities, pairs = _transport(integrator, kinds)
    mode = {value: name for name, value in MODES.items()}[integrator.getMode()]
    temperature = integrator.getTemperature().value_in_unit(unit.kelvin)
    fix = ["fix integrate all gendpde ${mode} ${seed}"]
    fix += [f"heat_capacity {index[kind]} {_number(in_metal(capacities[kind], 'heat_capacity'))}" for kind in kinds]
    fix += [f"friction {index[a]} {index[b]} {_number(in_metal(gamma, 'friction'))}"
            for (a, b), (gamma, _) in pairs.items()]
    fix += [f"conduction {index[a]} {index[b]} {_number(in_metal(kappa, 'heat_conduction'))}"
            for (a, b), (_, kappa) in pairs.items()]
    fix += ["temperature ${temperature}", "initial ${initial}"]
    estimator = ESTIMATOR_NAMES[force.getDensityEstimator()].lower()
    step = integrator.getStepSize().value_in_unit(unit.picosecond)
    script = [
        f"# {header}" + (f":\n# {title}." if title else "."),
        "# Units: metal (Å, eV, ps, g/mol, K), converted from OpenMM's (nm, kJ/mol, ps, amu, K) with",
        "# 1 kJ/mol = 1000/(e N_A) eV (CODATA 2018); LAMMPS's metal k_B (8.617343e-5 eV/K) is 1.13e-6 relatively",
        "# larger than OpenMM's (openmmgendpde.models.lammps_files).",
        f"# Run where {DATA_FILE} is: lmp -var plugin /path/to/gendpdeplugin.so -in {SCRIPT_FILE}",
        "# Each variable below can also be set on the command line (lmp -var steps 5000 ...).",
        "",
        *([f"variable plugin index {plugin}"] if plugin else []),
        f"variable steps index {int(steps)}",
        f"variable dt index {_number(step)}   # ps",
        f"variable mode index {mode}   # isoenergetic, isothermal or conservative",
        f"variable seed index {seed}",
        f"variable temperature index {_number(temperature)}   # K, the bath of the isothermal mode",
        f"variable initial index {_number(_initial_temperature(integrator))}   # K, the start: eps_i = C_V T",
        f"variable thermo index {int(thermo)}",
        "",
        "units metal",
        "atom_style atomic",
        "atom_modify map yes   # (atom-style variables of per-atom files need it: initial v_name)",
        "boundary p p p",
        "plugin load ${plugin}",
        f"read_data {DATA_FILE}",
        "",
        "# R (Å), the density estimator, f_cut (the reduced range is R/f_cut), background pressure p_b (eV/Å^3)",
        f"pair_style gendpde {_number(cutoff)} {estimator} {_number(force.getCutoffScaling())}"
        + (f" background {_number(background)}" if background != 0 else ""),
        "# per type: the law as GenDPDEForce names it and its parameters in metal units (a law that extends Tait",
        "# takes n0 (1/Å^3), pi0 and B_T (eV/Å^3) and gamma_T first; docs/lammps.md)",
        *[_pair_coeff(index[kind], *laws[kind]) for kind in kinds],
        "",
        f"# skin {_number(skin)} Å; ghosts: 1.5 sweep cells + skin, the fix's sweep needs them (lammps_files)",
        f"neighbor {_number(skin)} bin",
        "neigh_modify every 1 delay 0 check yes",
        f"comm_modify cutoff {_number(ghost)}",
        "",
        "# heat capacity C_V (eV/K), friction gamma (g/mol/ps), conduction kappa (eV K/ps)",
        " &\n    ".join(fix),
        "variable conserved equal etotal+f_integrate   # f_integrate: the sum of the internal energies (eV)",
        "timestep ${dt}",
        "thermo_style custom step temp pe ke etotal f_integrate v_conserved press",
        "thermo_modify format float %.15g",
        "thermo ${thermo}",
        "run ${steps}",
    ]
    return LammpsInput("\n".join(data) + "\n", "\n".join(script) + "\n", cutoff, skin, ghost)


def model_input(parameters, num_particles, mode="isoenergetic", seed=1, step_size=None, steps=1000, thermo=100,
                skin=None, plugin=None, title=None):
    """LammpsInput of a model (GenDPDEParameters, e.g. fluid_files.load_parameters of a model file) as its liquid()
    builds it with ``num_particles`` (4 m^3), the integrator in ``mode`` (a key of MODES) with random ``seed``,
    step ``step_size`` (ps; default liquid()'s, dt* = 0.01), and the velocities that Model.context draws with
    ``seed`` (Reference platform); the other arguments as lammps_input's. ValueError (or OpenMMException from the
    integrator's checks) for a bad argument."""
    if mode not in MODES:
        raise ValueError(f"mode = {mode!r} is not allowed; it must be one of {', '.join(MODES)}")
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
                        f"{title}, {num_particles} particles", plugin)


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
    """Write DATA_FILE and SCRIPT_FILE of ``texts`` (a LammpsInput) into ``directory`` (made if absent), each
    atomically; their paths."""
    os.makedirs(directory, exist_ok=True)
    paths = os.path.join(directory, DATA_FILE), os.path.join(directory, SCRIPT_FILE)
    for path, text in zip(paths, (texts.data, texts.script)):
        with atomic_write(path) as stream:
            stream.write(text)
    return paths
