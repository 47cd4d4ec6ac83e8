"""Any fluid, not only argon: from physical properties and a coarse-graining level to every GenDPDE parameter
(docs/fluids.md; the `calibrate` subcommand measures the model's properties back).

>>> water = WATER                                          # 298.15 K, 0.1 MPa (a Fluid; see its definition)
>>> parameters = coarse_grain(water, molecules_per_particle=4, neighbors=20)
>>> model = parameters.liquid(500)                          # System, GenDPDEForce, GenDPDEIntegrator, positions

The mapping (k_B T0, n0 ... in OpenMM units; N_m molecules per particle; N_R neighbours within the cutoff):

    m = N_m M/N_A                 n0 = rho/m                    R = (3 N_R/(4 pi n0))^(1/3)   (or R given)
    B_T = 1/(gamma_T kappa_T)     pi0 = P - n0 k_B T            C_V = N_m c_v (per particle)
    gamma = 1575 eta/(2 pi n0^2 R^5)          kappa = 315 lambda T^2/(2 pi n0^2 R^5)

The Tait form makes the bulk modulus n dpi/dn equal 1/kappa_T at n0 (gamma_T B_T); pi0 leaves out the kinetic
pressure n0 k_B T, which the particles' motion adds. gamma and kappa are the kinetic-theory values for the weights
omega_D = omega_q = (1 - r/R)^2: the dissipative pair friction alone gives the viscosity
eta_D = (gamma n0^2/30) int d^3r r^2 omega_D = 2 pi gamma n0^2 R^5/1575, and the conduction term, linearised in the
temperature difference (1/theta_i - 1/theta_j = (theta_j - theta_i)/T^2), the conductivity
lambda_q = (kappa n0^2/(6 T^2)) int d^3r r^2 omega_q = 2 pi kappa n0^2 R^5/(315 T^2). What the model actually gives
(the kinetic and conservative parts add to both, the estimator shifts the density) is measured by `calibrate`.
"""

import dataclasses
import math
import numbers

import numpy as np
import openmm
from openmm import unit

from ..api import ESTIMATOR_NAMES, GenDPDEForce, GenDPDEIntegrator
from ..units import BOLTZMANN, ReducedUnits
from .argon import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS, estimator_value
from .lattice import build_liquid, fcc_box
from .model import Model

#: The OpenMM units of the parameters (plain floats in GenDPDEParameters).
FRICTION = unit.amu / unit.picosecond
HEAT_CONDUCTION = unit.kilojoule_per_mole * unit.kelvin / unit.picosecond
PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
VISCOSITY = unit.amu / (unit.nanometer * unit.picosecond)
CONDUCTIVITY = unit.kilojoule_per_mole / (unit.picosecond * unit.nanometer * unit.kelvin)
HEAT_CAPACITY = unit.kilojoule_per_mole / unit.kelvin


MASS_DENSITY = unit.amu / unit.nanometer**3
MOLAR_MASS = unit.gram / unit.mole
COMPRESSIBILITY = PRESSURE**-1


def amount_power(unit_):
    """The power of the amount of substance (mol) in an openmm.unit Unit: -1 for kJ/mol, 1 for a compressibility in
    OpenMM units (nm^3 mol/kJ), 0 for a temperature or an SI unit per molecule (Pa, J/K)."""
    return int(round(sum(power for dimension, power in unit_.iter_base_dimensions() if dimension.name == "amount")))


def _in_openmm(quantity, target, name):
    """A Quantity in ``target`` (an OpenMM unit): directly if compatible; else, where ``target`` is per mole (OpenMM's
    energies, pressures and masses are) and the quantity per molecule (SI: J, Pa, W, kg, 1/Pa ...: no mol in its
    unit), made per mole (times Avogadro's number, or divided by it for the inverse of an energy, such as a
    compressibility). Nothing else: a property with no mol in its unit (a temperature, a thermal expansion coefficient,
    a speed) takes only a compatible unit, and a quantity per mole is not made per molecule. Raises ValueError naming
    the property if neither works."""
    if not unit.is_quantity(quantity):
        raise ValueError(f"{name} = {quantity!r} needs a unit (an openmm.unit Quantity compatible with {target})")
    if quantity.unit.is_compatible(target):
        return quantity.value_in_unit(target)
    moles = amount_power(target)
    if moles and not amount_power(quantity.unit):
        per_mole = quantity * unit.AVOGADRO_CONSTANT_NA ** -moles
        if per_mole.unit.is_compatible(target):
            return per_mole.value_in_unit(target)
    raise ValueError(f"{name} = {quantity} is not compatible with {target}"
                     + (" (per mole, or per molecule in SI)" if moles else ""))


def _positive(name, value, given=None):
    """``value`` if it is a finite number > 0, else ValueError naming ``name`` and the value as ``given``."""
    if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value if given is None else given} is not allowed; it must be finite and > 0")
    return value


def heat_capacity_per_molecule(value):
    """c_v per molecule in kJ/mol/K from a Quantity per molecule (J/K), per mole of molecules (J/(mol K),
    kJ/mol/K), or a plain number in units of k_B; ValueError unless it is finite and > 0."""
    if unit.is_quantity(value):
        per_molecule = _in_openmm(value, HEAT_CAPACITY, "heat_capacity")
    else:
        per_molecule = value * BOLTZMANN.value_in_unit(HEAT_CAPACITY) if isinstance(value, numbers.Real) else None
    return _positive("heat_capacity", per_molecule, value)


#: The OpenMM units of a Fluid's properties (heat_capacity and tait_exponent aside).
_PROPERTY_UNITS = {"temperature": unit.kelvin, "pressure": PRESSURE, "mass_density": MASS_DENSITY,
                   "compressibility": COMPRESSIBILITY, "shear_viscosity": VISCOSITY,
                   "thermal_conductivity": CONDUCTIVITY, "molar_mass": MOLAR_MASS}
#: The OpenMM units of the optional properties.
_OPTIONAL_PROPERTY_UNITS = {"self_diffusion": unit.nanometer**2 / unit.picosecond,
                            "speed_of_sound": unit.nanometer / unit.picosecond,
                            "surface_tension": unit.kilojoule_per_mole / unit.nanometer**2,
                            "thermal_expansion": unit.kelvin**-1}
#: The OpenMM unit of every property with a unit (heat_capacity also takes a plain number in k_B).
PROPERTY_UNITS = {**_PROPERTY_UNITS, "heat_capacity": HEAT_CAPACITY, **_OPTIONAL_PROPERTY_UNITS}


@dataclasses.dataclass(frozen=True)
class Fluid:
    """A fluid at one state point; every property an openmm.unit Quantity in any compatible unit (SI per molecule,
    or per mole), except heat_capacity, which may also be a number in k_B per molecule. Every property must be
    finite and > 0 but the pressure (finite, of either sign), and tait_exponent > 1: a Fluid that is not raises
    ValueError naming the property, its value and what is allowed. The optional properties (self_diffusion,
    speed_of_sound, surface_tension) are not fitted, only measured back; None where not known."""
    name: str
    temperature: unit.Quantity            # T0
    pressure: unit.Quantity               # P0
    mass_density: unit.Quantity           # rho
    compressibility: unit.Quantity        # isothermal, kappa_T
    heat_capacity: object                 # isochoric, per molecule (c_v)
    shear_viscosity: unit.Quantity        # eta
    thermal_conductivity: unit.Quantity   # lambda
    molar_mass: unit.Quantity             # M
    tait_exponent: float = 7.0            # gamma_T of the Tait equation (a model choice: 7 for water, 6 for argon)
    self_diffusion: unit.Quantity = None  # the molecules' self-diffusion coefficient: not fitted, measured back
    speed_of_sound: unit.Quantity = None  # not fitted: compared with the model's (from its measured n dP/dn)
    surface_tension: unit.Quantity = None  # liquid-vapour; not fitted: compared with a slab's (`slab`)
    thermal_expansion: unit.Quantity = None  # alpha (1/K): if given, the model's law is TaitThermalExpansion

    def __post_init__(self):
        self.in_openmm()

    def in_openmm(self):
        """The properties as plain floats in OpenMM units (temperature K, pressure kJ/mol/nm^3, mass_density
        amu/nm^3, compressibility nm^3 mol/kJ, shear_viscosity amu/(nm ps), thermal_conductivity kJ/(mol ps nm K),
        molar_mass g/mol, heat_capacity kJ/mol/K per molecule, tait_exponent, and self_diffusion nm^2/ps if
        given, speed_of_sound nm/ps if given, surface_tension kJ/mol/nm^2 if given), checked as the class says."""
        values = {}
        for name, target in _PROPERTY_UNITS.items():
            given = getattr(self, name)
            values[name] = _in_openmm(given, target, name)
            if name != "pressure":
                _positive(name, values[name], given)
            elif not math.isfinite(values[name]):
                raise ValueError(f"pressure = {given} is not allowed; it must be finite")
        values["heat_capacity"] = heat_capacity_per_molecule(self.heat_capacity)
        if not (isinstance(self.tait_exponent, numbers.Real) and 1 < self.tait_exponent < math.inf):
            raise ValueError(f"tait_exponent = {self.tait_exponent} is not allowed; it must be finite and > 1")
        values["tait_exponent"] = self.tait_exponent
        for name, target in _OPTIONAL_PROPERTY_UNITS.items():
            if getattr(self, name) is not None:
                values[name] = _positive(name, _in_openmm(getattr(self, name), target, name), getattr(self, name))
        return values


@dataclasses.dataclass(frozen=True)
class GenDPDEParameters:
    """Every parameter of GenDPDEForce and GenDPDEIntegrator for one fluid, coarse-graining level and cutoff, as plain
    floats in OpenMM units (nm, amu, ps, kJ/mol, K), with the targets they came from."""
    fluid: Fluid
    molecules_per_particle: float
    mass: float                   # amu, one particle
    temperature: float            # K, T0
    density: float                # nm^-3, n0
    reference_pressure: float     # kJ/mol/nm^3, pi0
    bulk_modulus: float           # kJ/mol/nm^3, B_T
    tait_exponent: float          # gamma_T
    cutoff: float                 # nm, R
    neighbors: float              # particles within R at n0
    cutoff_scaling: float         # f_cut of V-B (a first estimate until `calibrate` tunes it)
    friction: float               # amu/ps, gamma
    heat_conduction: float        # kJ K/(mol ps), kappa
    heat_capacity: float          # kJ/mol/K, C_V per particle
    thermal_pressure: float = None              # kJ/mol/nm^3/K, beta of TaitThermalExpansion (None: the Tait law)
    thermal_reference_temperature: float = None  # K, theta0 of TaitThermalExpansion
    background_pressure: float = None   # kJ/mol/nm^3, p_b of GenDPDEForce (None: none); background_pressure_for()
    #: The density estimator ('VA', 'VB', 'VC') that cutoff_scaling was tuned for; None where none was (a mapping's
    #: first estimate, or a model file of format 1, which did not record it). liquid() refuses another estimator
    #: that reads f_cut: V-C with V-B's f_cut does not give n0.
    estimator: str = None

    @property
    def equation_of_state(self):
        """The local equation of state: 'TaitThermalExpansion' where thermal_pressure is set, else 'Tait'."""
        return "Tait" if self.thermal_pressure is None else "TaitThermalExpansion"

    @property
    def units(self):
        """The reduced units of the model: mass of a particle, length n0^(-1/3), energy L^3/kappa_T (k_B = 1)."""
        length = self.density ** (-1 / 3)
        return ReducedUnits(mass=self.mass * unit.amu, length=length * unit.nanometer,
                            energy=length**3 * self.tait_exponent * self.bulk_modulus * unit.kilojoule_per_mole)

    def reduced(self):
        """The parameters in the model's reduced units (the paper's Table II for argon)."""
        u = self.units
        kb = BOLTZMANN.value_in_unit(HEAT_CAPACITY)
        return {
            "T0*": u.from_openmm(self.temperature, "temperature"),
            "n0*": u.from_openmm(self.density, "number_density"),
            "pi0*": u.from_openmm(self.reference_pressure, "pressure"),
            "B_T*": u.from_openmm(self.bulk_modulus, "pressure"),
            "gamma_T": self.tait_exponent,
            "R*": u.from_openmm(self.cutoff, "length"),
            "f_cut": self.cutoff_scaling,
            "gamma*": u.from_openmm(self.friction, "friction"),
            "kappa*": u.from_openmm(self.heat_conduction, "heat_conduction"),
            "C_V*": self.heat_capacity / kb,
            "p_b*": u.from_openmm(self.background_pressure or 0.0, "pressure"),
        }

    def targets(self):
        """The fluid's properties that the model should reproduce, in OpenMM units: pressure, bulk modulus
        1/kappa_T, temperature, viscosity, conductivity, the density n0, and the isochoric heat capacity of the
        molecules of one particle (kJ/mol/K); and those it is not fitted to, None where the fluid has none:
        self_diffusion, speed_of_sound and surface_tension (kJ/mol/nm^2)."""
        f = self.fluid.in_openmm()
        return {"density": self.density, "pressure": f["pressure"], "bulk_modulus": 1 / f["compressibility"],
                "temperature": f["temperature"], "shear_viscosity": f["shear_viscosity"],
                "heat_capacity": self.molecules_per_particle * f["heat_capacity"],
                "thermal_conductivity": f["thermal_conductivity"], "self_diffusion": f.get("self_diffusion"),
                "speed_of_sound": f.get("speed_of_sound"), "surface_tension": f.get("surface_tension"),
                "thermal_expansion": f.get("thermal_expansion")}

    def with_cutoff_scaling(self, cutoff_scaling, estimator=None):
        """The parameters with f_cut = ``cutoff_scaling``, tuned for ``estimator`` (default: the one recorded)."""
        return dataclasses.replace(self, cutoff_scaling=cutoff_scaling, estimator=estimator or self.estimator)

    def for_estimator(self, estimator):
        """The parameters with ``estimator`` recorded as the one f_cut is for (calibrate and tune-fcut, which tune
        f_cut for it from this start)."""
        return dataclasses.replace(self, estimator=ESTIMATOR_NAMES[estimator_value(estimator)])

    def checked_estimator(self, estimator=None):
        """The estimator's name that liquid() builds with: ``estimator``, by default the recorded one (else 'VB'); a
        ValueError where f_cut was tuned for another estimator that reads f_cut (V-A does not)."""
        name = ESTIMATOR_NAMES[estimator_value(estimator or self.estimator or "VB")]
        if self.estimator is not None and name not in (self.estimator, "VA"):
            raise ValueError(f"estimator = {name!r} is not allowed for this model: its f_cut = "
                             f"{self.cutoff_scaling:.6g} was tuned for {self.estimator}, and with {name} it does not "
                             f"give the density n0; tune f_cut for {name} (calibrate --fluid FILE --estimator {name} "
                             f"--output NEW, or tune-fcut) and use with_cutoff_scaling(f_cut, {name!r})")
        return name

    def with_transport(self, friction, heat_conduction):
        return dataclasses.replace(self, friction=friction, heat_conduction=heat_conduction)

    def liquid(self, num_particles=None, estimator=None, mode=GenDPDEIntegrator.Isoenergetic, time_step=0.01,
               seed=0, density=None, cells=None):
        """The fluid at n0 (or ``density``, nm^-3) in a periodic box on an FCC lattice: a cube of num_particles = 4 m^3
        particles, or ``cells`` = (n_x, n_y, n_z) cubic FCC cells (any rectangular box: slabs, elongated boxes).
        Returns a FluidModel with its System (one GenDPDEForce), GenDPDEIntegrator (step ``time_step`` in reduced time
        units, bath temperature T0), topology and positions (nm). ``estimator``: by default the one f_cut was tuned
        for (else V-B); another that reads f_cut is refused (checked_estimator)."""
        estimator = self.checked_estimator(estimator)
        density = self.density if density is None else density
        if cells is None:
            if num_particles is None:
                raise ValueError("give num_particles (4 m^3, a cube) or cells = (n_x, n_y, n_z)")
            integral = isinstance(num_particles, numbers.Integral) and num_particles > 0
            m = round((num_particles / 4) ** (1 / 3)) if integral else 0
            if m < 1 or 4 * m**3 != num_particles:
                raise ValueError(f"num_particles = {num_particles} is not allowed; a cube holds 4 m^3 "
                                 f"(500, 864, 2048, 4000, ...); give cells for other boxes")
            cells = (m, m, m)
        positions, box = fcc_box(density, cells)
        num_particles = len(positions)
        widths = [box[k][k] for k in range(3)]
        if self.cutoff > min(widths) / 2:
            raise ValueError(f"the box {widths[0]:.3f} x {widths[1]:.3f} x {widths[2]:.3f} nm is less than twice the "
                             f"cutoff {self.cutoff:.3f} nm across; use more cells")
        step = self.units.to_openmm(time_step, "time").value_in_unit(unit.picosecond)
        system, force, integrator, topology = build_liquid(
            [openmm.Vec3(*row) for row in box], num_particles, self.mass, self.cutoff, estimator_value(estimator),
            self.cutoff_scaling, (self.density, self.reference_pressure, self.bulk_modulus, self.tait_exponent), step,
            self.friction, self.heat_conduction, self.heat_capacity, self.temperature, seed, mode)
        if self.background_pressure is not None:
            force.setBackgroundPressure(self.background_pressure)
        if self.thermal_pressure is not None:
            force.setEquationOfState(GenDPDEForce.TaitThermalExpansion,
                                     [self.thermal_pressure, self.thermal_reference_temperature])
        return FluidModel(system, force, integrator, topology, positions, self)


@dataclasses.dataclass
class FluidModel(Model):
    """A ready model of a fluid (model.Model) and the parameters it was built from."""
    parameters: GenDPDEParameters = None

    @property
    def bath_temperature(self):
        return self.parameters.temperature


def set_temperature_field(integrator, positions, temperature):
    """Set every particle's internal temperature theta_i = temperature(r_i) (K; r_i in nm, a row of ``positions``,
    e.g. State.getPositions(asNumpy=True) or a plain N x 3 array): a temperature field, such as two regions at two
    temperatures for a heat-conduction study. The integrator must be bound to its Context."""
    if unit.is_quantity(positions):
        positions = positions.value_in_unit(unit.nanometer)
    values = []
    for r in np.asarray(positions, dtype=float):
        t = temperature(r)
        t = t.value_in_unit(unit.kelvin) if unit.is_quantity(t) else float(t)
        values.append(t)
    integrator.setParticleTemperatures(values)


def cutoff_scaling_guess(neighbors):
    """A first f_cut for V-B: argon's tuned values (Table II) interpolated in the number of neighbours (f_cut sets the
    reduced range Rt = R/f_cut of the partition of unity and depends on the structure mostly through it), held
    constant outside the published range. `calibrate` tunes it for the fluid itself."""
    counts = [entry.neighbors for entry in ARGON_CUTOFFS]
    values = [entry.cutoff_scaling for entry in ARGON_CUTOFFS]
    return float(np.interp(neighbors, counts, values))


def coarse_grain(fluid, molecules_per_particle, neighbors=None, cutoff=None, cutoff_scaling=None):
    """Every GenDPDE parameter for ``fluid`` with ``molecules_per_particle`` molecules per particle and either
    ``neighbors`` particles within the cutoff at n0 or the ``cutoff`` itself (a length Quantity or nm); the formulas
    are the module's. Raises ValueError naming a bad argument."""
    _positive("molecules_per_particle", molecules_per_particle)
    try:
        return _coarse_grained(fluid, molecules_per_particle, neighbors, cutoff, cutoff_scaling)
    except (OverflowError, ZeroDivisionError):
        raise ValueError(f"{fluid.name}: the mapping overflows: the fluid's properties are out of the range of a "
                         f"model ({molecules_per_particle:g} molecules per particle)") from None


def _coarse_grained(fluid, molecules_per_particle, neighbors, cutoff, cutoff_scaling):
    if (neighbors is None) == (cutoff is None):
        raise ValueError("give exactly one of neighbors (particles within the cutoff) and cutoff")
    f = fluid.in_openmm()
    temperature = f["temperature"]
    mass = molecules_per_particle * f["molar_mass"]                               # amu (g/mol per particle)
    density = f["mass_density"] / mass
    kt = BOLTZMANN.value_in_unit(HEAT_CAPACITY) * temperature
    bulk_modulus = 1 / (f["compressibility"] * f["tait_exponent"])
    reference_pressure = f["pressure"] - density * kt
    if cutoff is None:
        cutoff = (3 * _positive("neighbors", neighbors) / (4 * math.pi * density)) ** (1 / 3)
    else:
        cutoff = _positive("cutoff", _in_openmm(cutoff, unit.nanometer, "cutoff") if unit.is_quantity(cutoff)
                           else cutoff, cutoff)
        neighbors = 4 * math.pi / 3 * density * cutoff**3
    thermal_pressure = thermal_reference_temperature = None
    if "thermal_expansion" in f:
        thermal_pressure, thermal_reference_temperature = thermal_expansion_law(
            f["thermal_expansion"], f["compressibility"], density, temperature,
            molecules_per_particle * f["heat_capacity"])
    r5 = density * density * cutoff**5
    friction = 1575 * f["shear_viscosity"] / (2 * math.pi * r5)
    heat_conduction = 315 * f["thermal_conductivity"] * temperature * temperature / (2 * math.pi * r5)
    parameters = GenDPDEParameters(
        fluid=fluid, molecules_per_particle=molecules_per_particle, mass=mass, temperature=temperature,
        density=density, reference_pressure=reference_pressure, bulk_modulus=bulk_modulus,
        tait_exponent=f["tait_exponent"], cutoff=cutoff, neighbors=neighbors,
        cutoff_scaling=cutoff_scaling_guess(neighbors) if cutoff_scaling is None else cutoff_scaling,
        friction=friction, heat_conduction=heat_conduction,
        heat_capacity=molecules_per_particle * f["heat_capacity"], thermal_pressure=thermal_pressure,
        thermal_reference_temperature=thermal_reference_temperature,
        background_pressure=background_pressure_for(reference_pressure, bulk_modulus))
    # Properties far outside what a fluid has (a temperature of 1e300 K) can take a parameter out of the floats: say
    # so here, naming it, rather than in a Context or as inf in a model file.
    for field in dataclasses.fields(GenDPDEParameters):
        value = getattr(parameters, field.name)
        signed = field.name in ("reference_pressure", "thermal_pressure")
        if field.name != "fluid" and value is not None and not (math.isfinite(value) and (signed or value > 0)):
            raise ValueError(f"{fluid.name}: the mapping gives {field.name} = {value}, not a finite number"
                             f"{'' if signed else ' > 0'}; the fluid's properties are out of the range of a model "
                             f"(temperature = {temperature:g} K, mass_density = {f['mass_density']:g} amu/nm^3, "
                             f"{molecules_per_particle:g} molecules per particle)")
    return parameters


def background_pressure_for(reference_pressure, bulk_modulus):
    """The background pressure p_b (kJ/mol/nm^3) of a model whose particles would be under tension, pi0 < 0: a liquid
    whose pressure is below n0 k_B T0, the pressure of its particles' motion (water at 0.1 MPa: pi0 = -34 MPa with 4
    molecules per particle). There a particle's free energy falls as its density rises, and the structure (close
    pairs, docs/theory.md section 12) lets the mean n_i stay where it is while the true density changes: the bulk
    modulus comes out ~0.1 of the fluid's. p_b = B_T - pi0 makes each particle's pressure B_T (n_i/n0)^gamma_T,
    positive at every density, and the energy's p_b (V_box - sum_i V_i) leaves the system's pressure as it was.
    None (no background pressure) where pi0 >= 0 (argon at 85 MPa: its Tait law keeps its particles in
    compression)."""
    return bulk_modulus - reference_pressure if reference_pressure < 0 else None


def thermal_expansion_law(alpha, compressibility, density, temperature, heat_capacity):
    """beta (kJ/mol/nm^3/K) and theta0 (K) of TaitThermalExpansion for a fluid's thermal expansion coefficient alpha
    (1/K) and compressibility kappa_T (nm^3 mol/kJ) at (n0, T0), for particles of heat capacity C (kJ/mol/K), in the
    Isoenergetic mode (docs/theory.md section 11): the particles' positions see the thermal pressure beta (1 + k_B/C)
    at the kinetic temperature T, and the motion adds n k_B, so (dP/dT)_V = alpha/kappa_T asks for
    beta = (alpha/kappa_T - n0 k_B)/(1 + k_B/C); theta0 = T0 (1 + k_B/C), the mean particle temperature at T0, keeps
    P(n0, T0) = P0. Raises ValueError if alpha/kappa_T is below the ideal gas's n0 k_B (beta would be negative)."""
    kb = BOLTZMANN.value_in_unit(HEAT_CAPACITY)
    dressing = 1 + kb / heat_capacity
    beta = (alpha / compressibility - density * kb) / dressing
    if not beta > 0:
        raise ValueError(f"thermal_expansion = {alpha} 1/K gives (dP/dT)_V = {alpha / compressibility} kJ/mol/nm^3/K, "
                         f"less than the kinetic n0 k_B = {density * kb}: this mapping needs a liquid")
    return beta, temperature * dressing


def _argon_fluid():
    """Liquid argon as the paper models it (5 atoms per particle), its properties written in physical units from
    the reduced state (ARGON_STATE, ARGON_UNITS: T0, P0, the density n0* = 1, kappa_T0* = 1, C_V* = 12.51 k_B per
    particle) and the molar mass of the paper's particle mass (40.00 g/mol per atom). The paper's Table I of
    transport properties was not available here: eta and lambda are the values that the mapping turns into its
    Table II, one value each for all three cutoffs (gamma* R*^5 = 99.848 and kappa* R*^5 = 0.0337 reproduce all three
    printed gamma* and kappa* to their last digit, python/tests/test_fluid.py): 2.40e-4 Pa s and 0.138 W/(m K),
    liquid argon's magnitudes at this state."""
    u = ARGON_UNITS
    s = ARGON_STATE
    atoms = 5
    t0 = s.temperature
    viscosity_unit = u.unit("mass") / (u.unit("length") * u.unit("time"))
    conductivity_unit = (u.unit("heat_capacity") / (u.unit("length") * u.unit("time")))
    return Fluid(
        name="liquid argon (Colella et al. 2025)",
        temperature=u.to_openmm(t0, "temperature"),
        pressure=u.to_openmm(s.pressure, "pressure"),
        mass_density=u.unit("mass") * s.density / u.unit("length") ** 3,
        compressibility=1 / u.unit("pressure") / (s.tait_exponent * s.bulk_modulus),
        heat_capacity=s.heat_capacity / atoms,
        shear_viscosity=(2 * math.pi * 99.848 / 1575) * viscosity_unit,
        thermal_conductivity=(2 * math.pi * 0.0337 / (315 * t0**2)) * conductivity_unit,
        molar_mass=u.unit("mass").value_in_unit(unit.amu) / atoms * unit.gram / unit.mole,
        tait_exponent=s.tait_exponent)


#: Liquid argon of the paper: coarse_grain(ARGON, 5, cutoff=1.6839 L) is its R* = 1.6839 model (Table II).
ARGON = _argon_fluid()

#: The same liquid argon with its thermal expansion coefficient at this state (125.7 K, 85.31 MPa),
#: alpha = 2.64e-3 1/K (the local thermodynamic model of Colella, Mackie, Larentzos, Bresme and Bonet Avalos,
#: arXiv 2603.11203): its particles have the TaitThermalExpansion law (docs/theory.md section 11).
ARGON_EXPANDING = dataclasses.replace(ARGON, name="liquid argon with thermal expansion (Colella et al.)",
                                      thermal_expansion=2.64e-3 / unit.kelvin)

#: Supercritical argon at 418.8 K and 85.31 MPa, the second state of the local thermodynamic model of Colella,
#: Mackie, Larentzos, Bresme and Bonet Avalos (arXiv 2603.11203: 695.99 kg/m^3, c_v = 356 J/(kg K),
#: kappa_T = 6.83e-9 1/Pa, alpha = 1.97e-3 1/K). The density, viscosity, conductivity and speed of sound are the
#: reference correlations' as CoolProp 8.0.0 evaluates them (the Tegeler-Span-Wagner equation of state, J. Phys. Chem.
#: Ref. Data 28, 779 (1999); the Lemmon-Jacobsen viscosity and conductivity, Int. J. Thermophys. 25, 21 (2004)):
#: 695.97 kg/m^3, 5.556e-5 Pa s, 0.05320 W/(m K), 641.6 m/s; the same evaluation gives c_v = 356.5 J/(kg K),
#: kappa_T = 6.828e-9 1/Pa and alpha = 1.966e-3 1/K, the paper's values. gamma_T = 6 as for the liquid (a model choice).
SUPERCRITICAL_ARGON = Fluid(
    name="supercritical argon, 418.8 K, 85.31 MPa",
    temperature=418.8 * unit.kelvin,
    pressure=85.31 * unit.megapascal,
    mass_density=695.99 * unit.kilogram / unit.meter**3,
    compressibility=6.83e-9 / unit.pascal,
    heat_capacity=356.0 * 39.948e-3 * unit.joule / (unit.mole * unit.kelvin),
    shear_viscosity=5.556e-5 * unit.pascal * unit.second,
    thermal_conductivity=0.05320 * unit.watt / (unit.meter * unit.kelvin),
    molar_mass=39.948 * unit.gram / unit.mole,
    tait_exponent=6.0,
    speed_of_sound=641.6 * unit.meter / unit.second,
    thermal_expansion=1.97e-3 / unit.kelvin)

#: Liquid water at 298.15 K and 0.1 MPa (IAPWS-95 values as tabulated by NIST: 997.05 kg/m^3, kappa_T = 0.4525/GPa,
#: c_v = 74.44 J/(mol K); viscosity 0.8900 mPa s, thermal conductivity 0.6065 W/(m K)); gamma_T = 7 (Tait); the
#: self-diffusion coefficient 2.299e-9 m^2/s (Mills, J. Phys. Chem. 77, 685 (1973)), the speed of sound
#: 1496.7 m/s (Del Grosso and Mader, J. Acoust. Soc. Am. 52, 1442 (1972)) and the liquid-vapour surface tension
#: 71.97 mN/m (the IAPWS release on the surface tension of ordinary water, from Vargaftik, Volkov and Voljak,
#: J. Phys. Chem. Ref. Data 12, 817 (1983)), reported, not fitted.
WATER = Fluid(
    name="liquid water, 298.15 K, 0.1 MPa",
    temperature=298.15 * unit.kelvin,
    pressure=0.1 * unit.megapascal,
    mass_density=997.05 * unit.kilogram / unit.meter**3,
    compressibility=0.4525e-9 / unit.pascal,
    heat_capacity=74.44 * unit.joule / (unit.mole * unit.kelvin),
    shear_viscosity=0.8900e-3 * unit.pascal * unit.second,
    thermal_conductivity=0.6065 * unit.watt / (unit.meter * unit.kelvin),
    molar_mass=18.015 * unit.gram / unit.mole,
    tait_exponent=7.0,
    self_diffusion=2.299e-9 * unit.meter**2 / unit.second,
    speed_of_sound=1496.7 * unit.meter / unit.second,
    surface_tension=0.07197 * unit.newton / unit.meter)


#: The coarse-graining of --fluid where its options are not given (add_fluid_arguments); the molecules per particle
#: by default_molecules_per_particle (None here).
COARSE_GRAINING = {"molecules_per_particle": None, "neighbors": 20.0}


#: The fewest molecules per particle by default.
MOLECULES_PER_PARTICLE = 4


#: The internal heat capacity C_V (k_B) that the default coarse-graining leaves a particle at least, once calibrate has
#: matched the fluid's c_v (match_heat_capacity: C_V = N_m c_v - k_B - 3 k_B/2 - c_U, c_U ~ 0.1-0.4 k_B). The relative
#: fluctuations of the internal energies go as sqrt(k_B/C_V), and with a smaller C_V a step of dt* = 0.01 takes one
#: below zero within a calibration (the integrator refuses the step): argon at 4 atoms per particle (C_V matched to
#: 7.4 k_B) stopped in the bulk-modulus stage of --quick, and ran at dt* = 0.005; at 5 atoms (9.3 k_B) it runs at
#: 0.01 (docs/fluids.md). Supercritical argon at 4 (4.3 k_B) stopped at dt* = 0.005 and 0.0025, at 5 (5.9 k_B) at
#: 0.01 and 0.005 (docs/thermal.md); at 7 (9.4 k_B) its --quick calibration runs at 0.01 (3 min, every result
#: within its tolerance).
MIN_DEFAULT_INTERNAL_HEAT_CAPACITY = 9.0


#: Boltzmann's constant in kJ/mol/K.
KB = BOLTZMANN.value_in_unit(unit.kilojoule_per_mole / unit.kelvin)


def default_molecules_per_particle(fluid):
    """The molecules per particle of --fluid where --molecules-per-particle is not given: MOLECULES_PER_PARTICLE, or
    the fewest (a whole number) that leave a particle MIN_DEFAULT_INTERNAL_HEAT_CAPACITY once c_v is matched, for a
    fluid whose molecules hold little heat (argon 5, supercritical argon 7; water 4)."""
    c_v = fluid.in_openmm()["heat_capacity"] / KB   # k_B per molecule
    return float(max(MOLECULES_PER_PARTICLE, math.ceil((MIN_DEFAULT_INTERNAL_HEAT_CAPACITY + 2.5) / c_v)))
