# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Liquid argon as modelled by Colella, Larentzos, Bresme and Bonet Avalos (J. Chem. Theory Comput. 2025):
the reference case of docs/theory.md section 9.

One particle is 5 argon atoms. Reduced units: mass 3.3211e-25 kg, length 0.61616 nm (so n0* = 1), energy
1.5700e-19 J; k_B = 1. The model's numbers have one home, the C++ header internal/LiquidArgon.h (GenDPDEForce's
defaults come from it too); this module reads them through the bindings and adds the published results.
"""

import dataclasses
import numbers

import numpy as np
from openmm import app, unit

from ..api import GenDPDEForce, GenDPDEIntegrator, estimator_value  # noqa: F401  (estimator_value: this module's API)
from ..gendpde import LiquidArgon as _Model
from ..units import ARGON_UNITS, OPENMM_UNITS, ReducedUnits  # noqa: F401  (ARGON_UNITS: part of this module's API)
from .lattice import fcc_positions
from .model import Model, ModelParameters

#: The names of an argon model's particles in its Topology (atom, element, residue): 5 argon atoms each.
ARGON_NAMES = ("AR", app.element.argon, "AR5")


@dataclasses.dataclass(frozen=True)
class ArgonState:
    """The thermodynamic state and equation of state of the model (reduced units)."""
    temperature: float = _Model.temperature       # T0* (printed 0.0111)
    pressure: float = _Model.pressure             # P0* (printed 0.127)
    density: float = _Model.density               # n0*
    tait_exponent: float = _Model.taitExponent    # gamma_T
    bulk_modulus: float = _Model.bulkModulus      # B_T* = 1/(gamma_T kappa_T0*), kappa_T0* = 1
    heat_capacity: float = _Model.heatCapacity    # C_V* per particle (units of k_B)

    @property
    def free_energy_minimum_density(self):
        """n_min* = n0* (1 - pi0*/B_T*)^(1/gamma_T): where f(n) is minimal with VA (0.820), the density towards
        which VA particles clump (the pairing instability)."""
        return self.density * (1 - self.reference_pressure / self.bulk_modulus) ** (1 / self.tait_exponent)

    @property
    def reference_pressure(self):
        """pi0* = P0* - n0* T0* (the Tait pressure excludes the kinetic term)."""
        return self.pressure - self.density * self.temperature


ARGON_STATE = ArgonState()


@dataclasses.dataclass(frozen=True)
class ArgonCutoff:
    """Parameters that depend on the cutoff (reduced units)."""
    cutoff: float            # R_cut*
    neighbors: int           # particles within range at n0* = 1
    friction: float          # gamma*
    heat_conduction: float   # kappa*
    cutoff_scaling: float    # f_cut of the VB estimator


ARGON_CUTOFFS = tuple(ArgonCutoff(c.cutoff, c.neighbors, c.friction, c.heatConduction, c.cutoffScaling)
                      for c in (_Model.getCutoff(index) for index in range(_Model.numCutoffs)))

#: R_cut* of the studies of one cutoff (tune-fcut, speed-vs-error, the benchmarks): the middle one of the three
#: published.
DEFAULT_CUTOFF = ARGON_CUTOFFS[1].cutoff

#: Published averages (Table III): T*, n-bar*, P* for each cutoff and estimator; +-0.0001 (T*), +-0.001 (others).
PUBLISHED_TABLE3 = {
    1.3365: {"VA": {"T": 0.0115, "n": 0.799, "P": 0.008}, "VB": {"T": 0.0112, "n": 0.997, "P": 0.136}},
    1.6839: {"VA": {"T": 0.0112, "n": 0.811, "P": 0.011}, "VB": {"T": 0.0112, "n": 1.000, "P": 0.128}},
    2.1564: {"VA": {"T": 0.0111, "n": 0.870, "P": 0.041}, "VB": {"T": 0.0111, "n": 1.000, "P": 0.127}},
}

#: The estimators the paper compares (Tables III and IV, Fig. 1), in its order: those the argon studies run.
PUBLISHED_ESTIMATORS = tuple(PUBLISHED_TABLE3[1.6839])

#: Published total simulation time ratios V-B/V-A (Table IV, the authors' Fortran code).
PUBLISHED_TABLE4_RATIO = {1.3365: 1.07, 1.6839: 1.22, 2.1564: 1.03}


def argon_cutoff(cutoff):
    """The ArgonCutoff whose R_cut* equals ``cutoff`` (to 1e-6)."""
    for entry in ARGON_CUTOFFS:
        if abs(entry.cutoff - cutoff) < 1e-6:
            return entry
    raise ValueError(f"R_cut* = {cutoff} is not one of the published cutoffs "
                     f"{', '.join(str(entry.cutoff) for entry in ARGON_CUTOFFS)}")


#: f_cut of the VC estimator (docs/interfaces.md) where it has been tuned (`tune-fcut --estimator VC`, n-bar* = 1
#: at the state point; internal/LiquidArgon.h); elsewhere the published f_cut of VB, from which it differs little
#: (VC is VB in bulk).
VC_CUTOFF_SCALING = {c.cutoff: c.cutoffScalingVC for c in (_Model.getCutoff(i) for i in range(_Model.numCutoffs))
                     if c.cutoffScalingVC > 0}


def default_cutoff_scaling(cutoff, estimator):
    """The f_cut of ``estimator`` at R_cut* = ``cutoff``: the published one (of VB), or VC_CUTOFF_SCALING for VC
    where it has been tuned."""
    if estimator_value(estimator) == GenDPDEForce.VC:
        for tuned, value in VC_CUTOFF_SCALING.items():
            if abs(tuned - cutoff) < 1e-6:
                return value
    return argon_cutoff(cutoff).cutoff_scaling


def fcc_lattice(num_particles, edge):
    """Positions (num_particles x 3, in the units of ``edge``) of a face-centred cubic lattice filling a cubic box;
    num_particles must be 4 m^3."""
    cells = round((num_particles / 4) ** (1 / 3))
    if 4 * cells**3 != num_particles:
        raise ValueError(f"an FCC lattice in a cubic box holds 4 m^3 particles (500, 864, 2048, 4000, 32000, ...), "
                         f"not {num_particles}")
    return fcc_positions((cells, cells, cells), edge / cells)


@dataclasses.dataclass
class LiquidArgon(Model):
    """The published liquid-argon model (model.Model) with its cutoff's parameters, state and reduced units."""
    cutoff: ArgonCutoff = None
    state: ArgonState = ARGON_STATE
    units: ReducedUnits = ARGON_UNITS

    @property
    def temperature(self):
        """T0 (a Quantity in K)."""
        return self.units.to_openmm(self.state.temperature, "temperature")

    @property
    def box_volume(self):
        """nm^3 (Model.volume)."""
        return self.volume


def argon_parameters(cutoff=1.6839, estimator="VB", cutoff_scaling=None):
    """The ModelParameters of the published model at R_cut* = ``cutoff`` (one of the published 1.3365, 1.6839,
    2.1564), in OpenMM units: the state of ARGON_STATE, the cutoff's gamma* and kappa* (ARGON_CUTOFFS), and f_cut
    ``cutoff_scaling`` (default: default_cutoff_scaling of the cutoff and ``estimator``)."""
    published, units, state = argon_cutoff(cutoff), ARGON_UNITS, ARGON_STATE

    def openmm_value(value, kind):
        return units.to_openmm(value, kind).value_in_unit(OPENMM_UNITS[kind])

    return ModelParameters(
        mass=units.unit("mass").value_in_unit(unit.amu), temperature=openmm_value(state.temperature, "temperature"),
        density=openmm_value(state.density, "number_density"),
        reference_pressure=openmm_value(state.reference_pressure, "pressure"),
        bulk_modulus=openmm_value(state.bulk_modulus, "pressure"), tait_exponent=state.tait_exponent,
        cutoff=openmm_value(published.cutoff, "length"),
        cutoff_scaling=default_cutoff_scaling(cutoff, estimator) if cutoff_scaling is None else cutoff_scaling,
        friction=openmm_value(published.friction, "friction"),
        heat_conduction=openmm_value(published.heat_conduction, "heat_conduction"),
        heat_capacity=openmm_value(state.heat_capacity, "heat_capacity"))


def liquid_argon(num_particles=4000, cutoff=1.6839, estimator="VB", cutoff_scaling=None, time_step=0.01, seed=0,
                 mode=GenDPDEIntegrator.Isoenergetic):
    """Liquid argon at n0* = 1 in a cubic periodic box, particles on an FCC lattice.

    ``num_particles`` is 4 m^3 (an FCC lattice of m^3 cells); ``cutoff`` is R_cut* (one of the published 1.3365,
    1.6839, 2.1564); ``cutoff_scaling`` defaults to the published f_cut for that cutoff (VC:
    ``default_cutoff_scaling``); ``estimator`` is a name of the table of estimators (api.ESTIMATOR_NAMES) or its
    GenDPDEForce value. The GenDPDEIntegrator has the published gamma*, kappa* and C_V*, step ``time_step`` (reduced,
    or a time Quantity), the bath temperature T0 at which every particle starts, and random seed ``seed`` (0: chosen
    when the Context is created). Returns a LiquidArgon (built by argon_parameters(...).build) whose System holds one
    GenDPDEForce. Bad arguments raise ValueError naming the argument, the value and what is allowed.
    """
    if isinstance(num_particles, bool) or not isinstance(num_particles, numbers.Integral) or num_particles < 4:
        raise ValueError(f"liquid_argon: num_particles = {num_particles!r} is not allowed; it must be an integer "
                         f"4 m^3 with m >= 1 (500, 864, 2048, 4000, 32000, ...)")
    if unit.is_quantity(time_step):
        if not time_step.unit.is_compatible(unit.picosecond):
            raise ValueError(f"liquid_argon: time_step = {time_step} is not a time")
        step_size = time_step.in_units_of(unit.picosecond)
    else:
        step_size = ARGON_UNITS.to_openmm(time_step, "time")
    published = argon_cutoff(cutoff)
    length = ARGON_UNITS.unit("length").value_in_unit(unit.nanometer)
    edge = (num_particles / ARGON_STATE.density) ** (1 / 3) * length
    if published.cutoff * length > edge / 2:
        raise ValueError(f"{num_particles} particles make a box of edge {edge / length:.3f} L, less than twice "
                         f"R_cut* = {published.cutoff}; use more particles")
    positions = fcc_lattice(num_particles, edge)   # (checks that num_particles is 4 m^3)
    return argon_parameters(cutoff, estimator, cutoff_scaling).build(
        np.diag([edge] * 3), positions, estimator_value(estimator), step_size, seed, mode, ARGON_NAMES,
        model_type=LiquidArgon, cutoff=published)


def pressure_unit_mpa():
    """The reduced pressure unit u/L^3 in MPa."""
    per_mole = ARGON_UNITS.unit("pressure")
    return (per_mole / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.megapascal)


__all__ = ["ARGON_CUTOFFS", "ARGON_STATE", "ARGON_UNITS", "DEFAULT_CUTOFF", "ArgonCutoff", "ArgonState", "LiquidArgon",
           "PUBLISHED_ESTIMATORS", "PUBLISHED_TABLE3", "PUBLISHED_TABLE4_RATIO", "VC_CUTOFF_SCALING", "argon_cutoff",
           "argon_parameters", "default_cutoff_scaling", "fcc_lattice", "liquid_argon", "pressure_unit_mpa"]
