"""GenDPDE (generalised energy-conserving dissipative particle dynamics) for OpenMM.

``GenDPDEForce`` is the many-body conservative force U = sum_i f(n_i) with the traditional (VA) and the
partition-of-unity (VB) density estimators and the Tait equation of state. It is an ``openmm.Force``: add it to a
``System``, run it in a ``Context`` or an ``openmm.app.Simulation``, serialize it with ``openmm.XmlSerializer``.

Arguments accept ``openmm.unit`` quantities or plain numbers in OpenMM units (nm, ps, amu, kJ/mol, K);
parameter getters return quantities. Per-particle observables are numpy arrays in OpenMM units:
densities in nm^-3, volumes in nm^3, pressures in kJ/mol/nm^3, the virial in kJ/mol.
"""

import openmm as _openmm  # noqa: F401  (first: OpenMM's platforms and SWIG types must be loaded before ours)
from openmm import unit as _unit

from . import gendpde as _swig
from ._wrapping import (DIMENSIONLESS, NUMBER_DENSITY, PRESSURE, accept_units, add_cast_copy_and_pickle,
                        return_units)

__version__ = "0.1.0"
__all__ = ["GenDPDEForce"]

GenDPDEForce = _swig.GenDPDEForce

accept_units(GenDPDEForce, "__init__", [("cutoff", _unit.nanometer)])
accept_units(GenDPDEForce, "setCutoffDistance", [("distance", _unit.nanometer)])
return_units(GenDPDEForce, "getCutoffDistance", _unit.nanometer)
accept_units(GenDPDEForce, "setCutoffScaling", [("scaling", DIMENSIONLESS)])
accept_units(GenDPDEForce, "setTaitParameters", [("referenceDensity", NUMBER_DENSITY), ("referencePressure", PRESSURE),
                                                 ("bulkModulus", PRESSURE), ("exponent", DIMENSIONLESS)])
return_units(GenDPDEForce, "getTaitParameters", [NUMBER_DENSITY, PRESSURE, PRESSURE, DIMENSIONLESS])
return_units(GenDPDEForce, "getReferenceDensity", NUMBER_DENSITY)
return_units(GenDPDEForce, "getReferencePressure", PRESSURE)
return_units(GenDPDEForce, "getBulkModulus", PRESSURE)
add_cast_copy_and_pickle(GenDPDEForce)


def _force_repr(self):
    estimator = "VA" if self.getDensityEstimator() == GenDPDEForce.VA else "VB"
    method = "CutoffPeriodic" if self.usesPeriodicBoundaryConditions() else "CutoffNonPeriodic"
    n0, pi0, bulk, gamma = (value._value if _unit.is_quantity(value) else value for value in self.getTaitParameters())
    return (f"<GenDPDEForce cutoff={self.getCutoffDistance()._value:g} nm, {method}, estimator={estimator}, "
            f"cutoffScaling={self.getCutoffScaling():g}, Tait(n0={n0:g} nm^-3, pi0={pi0:g}, B_T={bulk:g} "
            f"kJ/mol/nm^3, gamma_T={gamma:g})>")


GenDPDEForce.__repr__ = _force_repr
