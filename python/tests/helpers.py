# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Small systems for the Python tests (liquid argon of docs/theory.md section 9 in OpenMM units, its numbers taken
from openmmgendpde.models.argon)."""

import importlib.util
import math
import pathlib

import numpy as np
import openmm
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.models.argon import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS

LENGTH = ARGON_UNITS.unit("length").value_in_unit(unit.nanometer)   # nm, the reduced length unit (n0* = 1)
MASS = ARGON_UNITS.unit("mass").value_in_unit(unit.amu)             # amu, one particle = 5 argon atoms
DENSITY = 1 / LENGTH**3                                             # nm^-3
#: T0 of the argon model, K.
TEMPERATURE = ARGON_UNITS.to_openmm(ARGON_STATE.temperature, "temperature").value_in_unit(unit.kelvin)
#: The parameters of the middle published cutoff (R_cut* = 1.6839): the default of the systems here.
MIDDLE_CUTOFF = ARGON_CUTOFFS[1]


def argon_integrator(step_size):
    """A GenDPDEIntegrator with the argon model's friction, heat conduction and heat capacity (MIDDLE_CUTOFF), all
    given as Quantities; ``step_size`` in ps or as a Quantity."""
    return GenDPDEIntegrator(step_size, ARGON_UNITS.to_openmm(MIDDLE_CUTOFF.friction, "friction"),
                             ARGON_UNITS.to_openmm(MIDDLE_CUTOFF.heat_conduction, "heat_conduction"),
                             ARGON_UNITS.to_openmm(ARGON_STATE.heat_capacity, "heat_capacity"))


def lattice_liquid(cells_per_side, density=DENSITY, jitter=0.15, seed=1, cutoff=MIDDLE_CUTOFF.cutoff * LENGTH,
                   estimator=GenDPDEForce.VB, cutoff_scaling=MIDDLE_CUTOFF.cutoff_scaling, periodic=True):
    """(system, force, positions) for a jittered simple-cubic lattice in a cubic box at ``density``."""
    n = cells_per_side**3
    edge = (n / density)**(1 / 3)
    spacing = edge / cells_per_side
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(openmm.Vec3(edge, 0, 0), openmm.Vec3(0, edge, 0), openmm.Vec3(0, 0, edge))
    for _ in range(n):
        system.addParticle(MASS)
    force = GenDPDEForce(cutoff)
    force.setDensityEstimator(estimator)
    force.setCutoffScaling(cutoff_scaling)
    force.setNonbondedMethod(GenDPDEForce.CutoffPeriodic if periodic else GenDPDEForce.CutoffNonPeriodic)
    system.addForce(force)
    grid = np.array([(x, y, z) for x in range(cells_per_side) for y in range(cells_per_side)
                     for z in range(cells_per_side)], dtype=float)
    rng = np.random.default_rng(seed)
    positions = (grid + 0.5) * spacing + rng.normal(0.0, jitter * spacing, grid.shape)
    return system, force, positions


def make_context(system, positions, platform, integrator=None):
    context = openmm.Context(system, integrator or openmm.VerletIntegrator(0.001), platform)
    context.setPositions(positions)
    return context


def energy_and_forces(context):
    state = context.getState(getEnergy=True, getForces=True)
    return (state.getPotentialEnergy().value_in_unit(openmm.unit.kilojoule_per_mole),
            state.getForces(asNumpy=True).value_in_unit(openmm.unit.kilojoule_per_mole / openmm.unit.nanometer))


def rms(array):
    return math.sqrt(float(np.mean(np.sum(np.asarray(array)**2, axis=-1))))


def assert_rejected_without_change(obj, call, fragments):
    """call(obj) raises openmm.OpenMMException whose message contains every fragment, and obj is unchanged
    (compared through its serialization, which covers every parameter)."""
    before = openmm.XmlSerializer.serialize(obj)
    with pytest.raises(openmm.OpenMMException) as error:
        call(obj)
    for fragment in fragments:
        assert fragment in str(error.value)
    assert openmm.XmlSerializer.serialize(obj) == before


def made_up_thermal_pressure(self, seed=None):
    """Calibration.thermal_pressure made up: (dP/dT)_n = 3 n0 k_B (argon's, kinetic and structural, docs/fluids.md),
    standard error 1%."""
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.models.fluid import KB
    return Measured(3 * self.parameters.density * KB, 0.03 * self.parameters.density * KB)


def fake_calibration(monkeypatch, mapped, pressure_offset=0.0):
    """Replace calibrate's simulations (Calibration's measurements) by made-up ones, for tests of the command
    around them: the pressure reads P0 + ``pressure_offset``/kappa_T while pi0 is ``mapped``'s and P0 once it moved;
    f_cut is 'tuned' to 1.3; c_U reads 0.5 k_B; the bulk modulus and the transport coefficients read their targets,
    (dP/dT)_n 3 n0 k_B (made_up_thermal_pressure); the thermal expansion of a fluid that has one is not measured."""
    import openmmgendpde.calibration.calibrate as calibrate
    from openmmgendpde.calibration.calibration import Calibration, Measured
    from openmmgendpde.models.fluid import KB
    monkeypatch.setattr(calibrate, "thermal_expansion_rows", lambda *arguments: [])   # (runs of its own)

    def thermodynamics(self, density=None, pressure_error=None):
        t = self.parameters.targets()
        measured = t["pressure"] + pressure_offset * t["bulk_modulus"]
        if self.parameters.reference_pressure != mapped.reference_pressure:
            measured = t["pressure"]
        self.configurational_heat_capacity = Measured(0.5 * KB, 0.01 * KB, 50)
        return {"density": Measured(t["density"], 1e-3), "kinetic_temperature": Measured(t["temperature"], 0.1),
                "harmonic_temperature": Measured(t["temperature"], 0.1), "self_diffusion": Measured(1e-3, 1e-5),
                "pressure": Measured(measured, 1e-4), "heat_capacity": self.heat_capacity(),
                "configurational_heat_capacity": self.configurational_heat_capacity}

    def tune(self, iterations=None):
        self.parameters = self.parameters.with_cutoff_scaling(1.3)
        return 1.3

    monkeypatch.setattr(Calibration, "tune_cutoff_scaling", tune)
    monkeypatch.setattr(Calibration, "thermodynamics", thermodynamics)
    monkeypatch.setattr(Calibration, "bulk_modulus",
                        lambda self: (Measured(self.parameters.targets()["bulk_modulus"], 1.0), Measured(1.0, 0.01)))
    monkeypatch.setattr(Calibration, "thermal_pressure", made_up_thermal_pressure)
    for name, target in (("shear_viscosity", "shear_viscosity"), ("steady_viscosity", "shear_viscosity"),
                         ("thermal_conductivity", "thermal_conductivity"),
                         ("steady_conductivity", "thermal_conductivity")):
        monkeypatch.setattr(Calibration, name, lambda self, target=target: Measured(
            self.parameters.targets()[target], 1e-6, 3))


def load_file(path):
    """The module in the file ``path`` (a tool of devtools/ or lammps/unittest/, which are no package), loaded
    afresh under its file's name."""
    path = pathlib.Path(path)
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
