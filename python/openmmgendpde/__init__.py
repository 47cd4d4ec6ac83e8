# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""GenDPDE (generalised energy-conserving dissipative particle dynamics) for OpenMM.

``GenDPDEForce`` is the many-body conservative force U = sum_i f(n_i) with the traditional (VA), the
partition-of-unity (VB) and the surface-corrected (VC, for free surfaces) density estimators, the Tait equation of
state and the local laws that depend on a particle's temperature (GenDPDEForce.EquationOfState), particle types
and a background pressure. It is an ``openmm.Force``: add it to a ``System``, run it in a ``Context`` or an
``openmm.app.Simulation``, serialize it with ``openmm.XmlSerializer``.

``GenDPDEIntegrator`` is the energy-conserving integrator that carries each particle's internal energy, with
dissipative and random pair forces and heat conduction (Shardlow-like splitting; Isoenergetic, Isothermal and
Conservative modes). It is an ``openmm.Integrator``. ``GenDPDEReporter`` reports the thermodynamic state as OpenMM's
reporters do; ``StateDataReporter`` is OpenMM's with the conserved energy and the harmonic-mean temperature.

Arguments accept ``openmm.unit`` quantities or plain numbers in OpenMM units (nm, ps, amu, kJ/mol, K). Getters
and results return quantities, as OpenMM's do; a per-particle result is one Quantity holding a numpy array (like
``State.getPositions(asNumpy=True)``): densities in nm^-3, volumes in nm^3, pressures in kJ/mol/nm^3, temperatures
in K, internal energies in kJ/mol. ``.value_in_unit(unit)`` gives the plain array.

The subpackages (README, "The package"): ``models`` builds models (the published argon, any fluid), ``analysis``
measures them, ``calibration`` fits a model to a fluid, ``studies`` and ``benchmarks`` are the command line's
(``python -m openmmgendpde``).
"""

import openmm as _openmm  # first: loads OpenMM's platforms and this plugin's kernel libraries, and the SWIG types

from ._version import openmm_build_version as _openmm_build_version
from ._version import version as __version__


def _major_minor(version):
    return tuple(version.split(".")[:2])


if _major_minor(_openmm.__version__) != _major_minor(_openmm_build_version):
    raise ImportError(f"openmmgendpde {__version__} was built against OpenMM {_openmm_build_version} and cannot run "
                      f"with OpenMM {_openmm.__version__} (OpenMM's platform internals change between minor "
                      f"versions); reinstall it in this environment (pip install .)")

from .api import ESTIMATOR_NAMES, KERNEL_NAMES, GenDPDEForce, GenDPDEIntegrator  # noqa: E402, F401
from .reporter import GenDPDEReporter, StateDataReporter  # noqa: E402

__all__ = ["GenDPDEForce", "GenDPDEIntegrator", "GenDPDEReporter", "StateDataReporter"]

from .internal import moved as _moved  # noqa: E402

_moved.install()   # the flat package's module names (openmmgendpde.fluid, .presets, ...), deprecated
