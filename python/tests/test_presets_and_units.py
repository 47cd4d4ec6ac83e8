# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Reduced units and the liquid-argon preset (docs/theory.md section 9)."""

import math
import os
import subprocess
import sys

import numpy as np
import openmm
import pytest
from openmm import app, unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.models.argon import (
    ARGON_CUTOFFS,
    ARGON_STATE,
    ARGON_UNITS,
    fcc_lattice,
    liquid_argon,
    pressure_unit_mpa,
)
from openmmgendpde.units import OPENMM_UNITS, ReducedUnits

AVOGADRO = 6.02214076e23
BOLTZMANN_SI = 1.380649e-23


def test_round_trips_for_every_kind():
    for kind in OPENMM_UNITS:
        for value in (0.011054, 1.0, 23.42):
            assert ARGON_UNITS.from_openmm(ARGON_UNITS.to_openmm(value, kind), kind) == pytest.approx(value, rel=1e-15)


def test_derived_units_match_model_md_from_si():
    """docs/theory.md section 9: mass 3.3211e-25 kg (200 amu, 5 argon atoms), L = 0.61616 nm, u = 1.5700e-19 J
    (94.55 kJ/mol), time L sqrt(m/u) = 0.8962 ps, pressure unit 671.1 MPa; all from the SI definitions here."""
    assert ARGON_UNITS.unit("mass").value_in_unit(unit.amu) == pytest.approx(3.3211e-25 * AVOGADRO * 1000, rel=1e-12)
    assert ARGON_UNITS.unit("energy").value_in_unit(unit.kilojoule_per_mole) == pytest.approx(94.55, abs=0.005)
    seconds = 0.61616e-9 * math.sqrt(3.3211e-25 / 1.5700e-19)
    assert ARGON_UNITS.unit("time").value_in_unit(unit.picosecond) == pytest.approx(seconds * 1e12, rel=1e-12)
    assert ARGON_UNITS.unit("time").value_in_unit(unit.picosecond) == pytest.approx(0.8962, abs=5e-5)
    assert pressure_unit_mpa() == pytest.approx(1.5700e-19 / 0.61616e-9**3 / 1e6, rel=1e-12)
    assert pressure_unit_mpa() == pytest.approx(671.1, abs=0.05)
    assert ARGON_UNITS.unit("temperature").value_in_unit(unit.kelvin) == pytest.approx(1.5700e-19 / BOLTZMANN_SI,
                                                                                       rel=1e-12)


def test_reduced_state_recovered_from_si_values():
    """The SI state of the argon model (T0 = 125.70 K, P0 = 85.30 MPa, n0 = 4.2748 nm^-3, kappa_T0 = L^3/u) maps back
    to T0* = 0.011054, P0* = 0.12711, n0* = 1, B_T* = 1/6 with gamma_T = 6."""
    units = ARGON_UNITS
    t0 = 0.011054 * 1.5700e-19 / BOLTZMANN_SI
    assert units.from_openmm(t0 * unit.kelvin, "temperature") == pytest.approx(0.011054, rel=1e-12)
    p0_mpa = 0.12711 * 1.5700e-19 / 0.61616e-9**3 / 1e6
    p0 = (p0_mpa * unit.megapascal * unit.AVOGADRO_CONSTANT_NA).in_units_of(OPENMM_UNITS["pressure"])
    assert units.from_openmm(p0, "pressure") == pytest.approx(0.12711, rel=1e-12)
    assert units.from_openmm(1 / 0.61616**3, "number_density") == pytest.approx(1.0, rel=1e-14)
    bulk_si = 1 / (6 * 0.61616e-9**3 / 1.5700e-19)           # B_T = 1/(gamma_T kappa_T0), Pa
    bulk = (bulk_si * unit.pascal * unit.AVOGADRO_CONSTANT_NA).in_units_of(OPENMM_UNITS["pressure"])
    assert units.from_openmm(bulk, "pressure") == pytest.approx(1 / 6, rel=1e-12)
    assert ARGON_STATE.reference_pressure == pytest.approx(0.1161, abs=5e-5)
    assert ARGON_STATE.free_energy_minimum_density == pytest.approx(0.820, abs=5e-4)


def test_units_accept_per_particle_or_per_mole_mass_and_energy():
    a = ReducedUnits(200.0013 * unit.amu, 0.61616 * unit.nanometer, 94.5476 * unit.kilojoule_per_mole)
    assert a.unit("time").value_in_unit(unit.picosecond) == pytest.approx(
        ARGON_UNITS.unit("time").value_in_unit(unit.picosecond), rel=1e-5)
    with pytest.raises(ValueError, match="unknown kind"):
        a.unit("luminosity")


@pytest.mark.parametrize("entry", ARGON_CUTOFFS, ids=lambda e: str(e.cutoff))
def test_liquid_argon_preset(entry):
    argon = liquid_argon(500, entry.cutoff, "VA")
    length = 0.61616
    assert argon.num_particles == 500
    edge = argon.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    assert edge == pytest.approx(500 ** (1 / 3) * length, rel=1e-14)
    force = argon.force
    assert force.getCutoffDistance().value_in_unit(unit.nanometer) == pytest.approx(entry.cutoff * length, rel=1e-14)
    assert force.getDensityEstimator() == GenDPDEForce.VA and force.getCutoffScaling() == entry.cutoff_scaling
    assert ARGON_UNITS.from_openmm(force.getBulkModulus(), "pressure") == pytest.approx(1 / 6, rel=1e-14)
    integrator = argon.integrator
    assert ARGON_UNITS.from_openmm(integrator.getFriction(), "friction") == pytest.approx(entry.friction, rel=1e-14)
    assert ARGON_UNITS.from_openmm(integrator.getHeatConduction(), "heat_conduction") == pytest.approx(
        entry.heat_conduction, rel=1e-14)
    assert ARGON_UNITS.from_openmm(integrator.getHeatCapacity(), "heat_capacity") == pytest.approx(12.51, rel=1e-14)
    assert ARGON_UNITS.from_openmm(integrator.getTemperature(), "temperature") == pytest.approx(0.011054, rel=1e-14)
    # The FCC lattice: nearest neighbors at a/sqrt(2), 12 of them.
    positions = argon.positions
    spacing = edge / round((500 / 4) ** (1 / 3))
    d = positions[1:] - positions[0]
    d -= edge * np.round(d / edge)
    distances = np.linalg.norm(d, axis=1)
    assert distances.min() == pytest.approx(spacing / math.sqrt(2), rel=1e-12)
    assert np.sum(np.isclose(distances, spacing / math.sqrt(2))) == 12


def test_preset_rejects_what_it_cannot_build():
    with pytest.raises(ValueError, match="4 m\\^3"):
        fcc_lattice(1000, 1.0)
    with pytest.raises(ValueError, match="twice"):
        liquid_argon(32, 2.1564)
    with pytest.raises(ValueError, match="not one of the published cutoffs"):
        liquid_argon(500, 1.5)
    for bad in (-4, 500.0, True, 0):
        with pytest.raises(ValueError, match=f"num_particles = {bad!r} is not allowed"):
            liquid_argon(bad)
    with pytest.raises(ValueError, match="time_step = 3 K is not a time"):
        liquid_argon(500, time_step=3 * unit.kelvin)


def test_preset_takes_a_time_step_quantity_and_writes_pdb_files(tmp_path):
    argon = liquid_argon(500, time_step=4.5 * unit.femtosecond)
    assert argon.integrator.getStepSize().value_in_unit(unit.picosecond) == pytest.approx(0.0045, rel=1e-15)
    app.PDBFile.writeFile(argon.topology, argon.positions * unit.nanometer, open(tmp_path / "argon.pdb", "w"))
    written = app.PDBFile(str(tmp_path / "argon.pdb"))
    assert written.topology.getNumAtoms() == 500
    edge = argon.system.getDefaultPeriodicBoxVectors()[0][0].value_in_unit(unit.nanometer)
    assert written.topology.getUnitCellDimensions()[0].value_in_unit(unit.nanometer) == pytest.approx(edge, abs=1e-3)


def test_a_second_simulation_of_one_preset_is_refused():
    """An integrator serves one Context: calling simulation() twice (a re-run notebook cell) raises, and the first
    Simulation keeps working."""
    argon = liquid_argon(500)
    first = argon.simulation()
    with pytest.raises(openmm.OpenMMException, match="already bound to a context"):
        argon.simulation()
    first.step(2)
    assert first.currentStep == 2


def test_a_presets_force_keeps_its_system_alive():
    """The force of a preset that is gone (`liquid_argon(500).force`) stays usable: the System, which owns the C++
    force, lives as long as the force (in plain OpenMM it would be freed with the System). In a subprocess, since
    a use after free can crash the interpreter, with glibc's MALLOC_PERTURB_ filling freed memory so that such a use
    fails reliably; the force, read after garbage collection and other allocations by a ProfileReporter and by
    XmlSerializer, against a fresh preset's."""
    script = ("import gc, io, openmm\n"
              "from openmmgendpde.models.argon import liquid_argon\n"
              "from openmmgendpde.analysis.profiles import ProfileReporter\n"
              "force = liquid_argon(500, estimator='VC').force\n"
              "gc.collect()\n"
              "others = [liquid_argon(500) for _ in range(3)]\n"
              "reporter = ProfileReporter(io.StringIO(), 1, force=force)\n"
              "print(openmm.XmlSerializer.serialize(force))\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env={**os.environ, "MALLOC_PERTURB_": "165"})
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout == openmm.XmlSerializer.serialize(liquid_argon(500, estimator="VC").force) + "\n"
