# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
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

The local equation of state is any law of the table (``coarse_grain(..., law=...)``; by default Tait, or the thermal
Tait law for a fluid with a thermal expansion, beta and theta0 of thermal_expansion_law), its parameters fitted to the
Tait law's pi0 and n dpi/dn at n0 and to that beta (models.laws; docs/thermal.md).
"""

import dataclasses
import math

import numpy as np
from openmm import unit

from ..api import LAWS, GenDPDEForce, law_value
from ..units import BOLTZMANN
from . import laws
from .argon import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS
from .model import set_temperature_field  # noqa: F401  (part of this module's API, version 0.2)
from .parameters import FluidModel, GenDPDEParameters  # noqa: F401  (part of this module's API)
from .properties import (  # noqa: F401  (part of this module's API)
    COMPRESSIBILITY,
    CONDUCTIVITY,
    FRICTION,
    HEAT_CAPACITY,
    HEAT_CONDUCTION,
    MASS_DENSITY,
    MOLAR_MASS,
    PRESSURE,
    PROPERTY_UNITS,
    VISCOSITY,
    Fluid,
    _in_openmm,
    _positive,
    amount_power,
    heat_capacity_per_molecule,
)


def cutoff_scaling_guess(neighbors):
    """A first f_cut for V-B: argon's tuned values (Table II) interpolated in the number of neighbours (f_cut sets the
    reduced range Rt = R/f_cut of the partition of unity and depends on the structure mostly through it), held
    constant outside the published range. `calibrate` tunes it for the fluid itself."""
    counts = [entry.neighbors for entry in ARGON_CUTOFFS]
    values = [entry.cutoff_scaling for entry in ARGON_CUTOFFS]
    return float(np.interp(neighbors, counts, values))


def coarse_grain(fluid, molecules_per_particle, neighbors=None, cutoff=None, cutoff_scaling=None, law=None):
    """Every GenDPDE parameter for ``fluid`` with ``molecules_per_particle`` molecules per particle and either
    ``neighbors`` particles within the cutoff at n0 or the ``cutoff`` itself (a length Quantity or nm); the formulas
    are the module's. ``law``: the local equation of state (a name of the table of laws, api.LAW_NAMES, or its
    GenDPDEForce.EquationOfState value); by default Tait, or TaitThermalExpansion for a fluid with a thermal_expansion.
    A law with parameters of its own is fitted (models.laws) to the Tait law's pi0 and n dpi/dn = gamma_T B_T at n0 and
    to the thermal pressure beta (thermal_expansion_law) at the particles' mean temperature, so it needs the fluid's
    thermal_expansion. Raises ValueError naming a bad argument."""
    _positive("molecules_per_particle", molecules_per_particle)
    try:
        parameters = _coarse_grained(fluid, molecules_per_particle, neighbors, cutoff, cutoff_scaling)
        thermal = _thermal_law(fluid, parameters)
    except (OverflowError, ZeroDivisionError):
        raise ValueError(f"{fluid.name}: the mapping overflows: the fluid's properties are out of the range of a "
                         f"model ({molecules_per_particle:g} molecules per particle)") from None
    if law is None:
        law = GenDPDEForce.Tait if thermal is None else GenDPDEForce.TaitThermalExpansion
    chosen = LAWS[law_value(law)]
    if not chosen.parameters:
        return parameters.with_law(chosen.value, ())
    if thermal is None:
        raise ValueError(f"law = {chosen.name!r} is not allowed for {fluid.name}: its parameters are fitted to the "
                         f"fluid's thermal expansion, and the fluid has no thermal_expansion")
    beta, theta = thermal
    return parameters.with_law(chosen.value, laws.fit(chosen.value, parameters.tait,
                                                      parameters.reference_state(beta, theta)))


def _thermal_law(fluid, parameters):
    """(beta, theta_r) of the fluid's thermal expansion at the mapped parameters (thermal_expansion_law), or None
    for a fluid without one; ValueError naming beta if it is not a finite number."""
    if fluid.thermal_expansion is None:
        return None
    f = fluid.in_openmm()
    beta, theta = thermal_expansion_law(f["thermal_expansion"], f["compressibility"], parameters.density,
                                        parameters.temperature, parameters.heat_capacity)
    if not (math.isfinite(beta) and math.isfinite(theta)):
        raise ValueError(f"{fluid.name}: the mapping gives thermal_pressure = {beta}, not a finite number; the "
                         f"fluid's properties are out of the range of a model")
    return beta, theta


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
    r5 = density * density * cutoff**5
    friction = 1575 * f["shear_viscosity"] / (2 * math.pi * r5)
    heat_conduction = 315 * f["thermal_conductivity"] * temperature * temperature / (2 * math.pi * r5)
    parameters = GenDPDEParameters(
        fluid=fluid, molecules_per_particle=molecules_per_particle, mass=mass, temperature=temperature,
        density=density, reference_pressure=reference_pressure, bulk_modulus=bulk_modulus,
        tait_exponent=f["tait_exponent"], cutoff=cutoff, neighbors=neighbors,
        cutoff_scaling=cutoff_scaling_guess(neighbors) if cutoff_scaling is None else cutoff_scaling,
        friction=friction, heat_conduction=heat_conduction,
        heat_capacity=molecules_per_particle * f["heat_capacity"],
        background_pressure=background_pressure_for(reference_pressure, bulk_modulus))
    # Properties far outside what a fluid has (a temperature of 1e300 K) can take a parameter out of the floats: say
    # so here, naming it, rather than in a Context or as inf in a model file.
    for field in dataclasses.fields(GenDPDEParameters):
        value = getattr(parameters, field.name)
        signed = field.name == "reference_pressure"
        if isinstance(value, float) and not (math.isfinite(value) and (signed or value > 0)):
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
