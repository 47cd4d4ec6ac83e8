# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The background pressure p_b of GenDPDEForce and the compression study (docs/theory.md section 12)."""

import math

import numpy as np
import openmm
import pytest
from helpers import assert_rejected_without_change, lattice_liquid, make_context
from openmm import unit

from openmmgendpde import GenDPDEForce
from openmmgendpde.analysis.rdf import radial_distribution
from openmmgendpde.models import fluid, fluid_files
from openmmgendpde.models.lattice import fcc_positions
from openmmgendpde.studies.compression import bond_order, responses, structure_factor

PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3


def test_units_range_and_serialization():
    force = GenDPDEForce(1.0 * unit.nanometer)
    assert force.getBackgroundPressure() == 0 * PRESSURE
    force.setBackgroundPressure(100 * unit.megapascal)
    # 100 MPa = 1e8 J/m^3 = 1e8 * 6.02214076e23 / 1e3 kJ/mol / 1e27 nm^3 (written out)
    assert force.getBackgroundPressure().value_in_unit(PRESSURE) == pytest.approx(1e8 * 6.02214076e23 / 1e30,
                                                                                  rel=1e-12)
    copy = GenDPDEForce.cast(openmm.XmlSerializer.deserialize(openmm.XmlSerializer.serialize(force)))
    assert copy.getBackgroundPressure() == force.getBackgroundPressure()
    for bad in (-1.0, math.nan, math.inf):
        assert_rejected_without_change(force, lambda f: f.setBackgroundPressure(bad), ["background pressure p_b"])
    # A file of version 3 (before p_b) reads as p_b = 0; one that says p_b at version 3 is refused.
    xml = openmm.XmlSerializer.serialize(GenDPDEForce(1.0)).replace('version="4"', 'version="3"')
    assert 'backgroundPressure="0"' in xml
    with pytest.raises(openmm.OpenMMException, match="backgroundPressure"):
        openmm.XmlSerializer.deserialize(xml)
    old = GenDPDEForce.cast(openmm.XmlSerializer.deserialize(xml.replace(' backgroundPressure="0"', "")))
    assert old.getBackgroundPressure() == 0 * PRESSURE


def test_energy_is_the_partition_of_unity_defect(platform):
    """U(p_b) - U(0) = p_b (V_box - sum_i V_i), with the V_i the force reports (the definition of p_b), to 1e-9 of
    p_b V_box (double precision; the GPU platforms' float energies carry ~1e-7 of U); each particle's pressure
    rises by p_b."""
    system, force, positions = lattice_liquid(6, seed=3)
    force.setTaitParameters(force.getReferenceDensity(), -20 * PRESSURE, force.getBulkModulus(), 7.0)
    context = make_context(system, positions, platform)
    energy0 = context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    volumes = force.getParticleVolumes(context).value_in_unit(unit.nanometer**3)
    box = context.getState().getPeriodicBoxVolume().value_in_unit(unit.nanometer**3)
    force.setBackgroundPressure(80 * PRESSURE)
    force.updateParametersInContext(context)
    energy = context.getState(getEnergy=True).getPotentialEnergy().value_in_unit(unit.kilojoule_per_mole)
    assert energy - energy0 == pytest.approx(80 * (box - np.sum(volumes)), rel=1e-9, abs=1e-9 * 80 * box)
    pressures = force.getParticlePressures(context).value_in_unit(PRESSURE)
    force.setBackgroundPressure(0.0)
    force.updateParametersInContext(context)
    assert pressures - force.getParticlePressures(context).value_in_unit(PRESSURE) == pytest.approx(80, rel=1e-9)


def test_needs_periodic_boundaries():
    system, force, positions = lattice_liquid(4, periodic=False)
    force.setBackgroundPressure(10.0)
    with pytest.raises(openmm.OpenMMException, match="CutoffPeriodic"):
        make_context(system, positions, openmm.Platform.getPlatformByName("Reference"))


def test_mapping_adds_a_background_pressure_where_the_particles_would_be_under_tension(tmp_path):
    """Water at 0.1 MPa: pi0 = P0 - n0 k_B T0 < 0, so p_b = B_T - pi0 (each particle's pressure B_T (n/n0)^gamma);
    argon at 85 MPa (pi0 > 0) gets none. The model file keeps p_b."""
    water = fluid.coarse_grain(fluid.WATER, 4, neighbors=20)
    assert water.reference_pressure < 0
    assert water.background_pressure == pytest.approx(water.bulk_modulus - water.reference_pressure, rel=1e-15)
    argon = fluid.coarse_grain(fluid.ARGON, 5, neighbors=20)
    assert argon.reference_pressure > 0 and argon.background_pressure is None
    path = str(tmp_path / "water.toml")
    fluid_files.save_parameters(water, path)
    again = fluid_files.load_parameters(path)
    assert again.background_pressure == water.background_pressure
    model = again.liquid(500, "VB")
    assert model.force.getBackgroundPressure().value_in_unit(PRESSURE) == water.background_pressure


def test_structure_measures_against_known_values():
    """An FCC crystal: Q6 = <q6> = 0.5745 (Steinhardt et al. 1983, 12 nearest neighbours), S(k) = 0 at the box's
    smallest wave vectors (none is a reciprocal lattice vector of the crystal); an ideal gas: g(r) = 1 and S(k) = 1
    (expected values; tolerances 5 standard errors of the sampled means)."""
    cells, edge = 4, 1.0
    crystal = np.asarray(fcc_positions((cells, cells, cells), edge))
    box = np.array([cells * edge] * 3)
    q6, local = bond_order(crystal, box, 0.85 * edge)   # nearest neighbours at 0.707 edge, next at 1.0
    assert q6 == pytest.approx(0.57452, abs=1e-4) and local == pytest.approx(0.57452, abs=1e-4)
    for _, s, _ in structure_factor([crystal], box):
        assert s == pytest.approx(0.0, abs=1e-20)
    rng = np.random.default_rng(5)
    gas = [rng.uniform(0, box[0], (2000, 3)) for _ in range(40)]
    r, g = radial_distribution(gas, box[0], r_max=1.5, bin_width=0.15, length=1.0)
    # each bin holds >~ 2000 * 40 * 4 pi r^2 dr n / 2 pairs: the outer bins ~1e5, the first ~400 (error 5%)
    assert np.all(np.abs(g[3:] - 1) < 0.03) and abs(g[0] - 1) < 0.25
    for k, s, error in structure_factor(gas, box):
        assert abs(s - 1) < 5 * max(error, 1 / math.sqrt(40 * 3)), (k, s, error)


def test_responses_of_two_boxes():
    """A fluid whose n-bar follows n exactly and whose P = K ln n: response 1, n dP/dn = K."""
    from openmmgendpde.calibration.calibration import Measured
    from openmmgendpde.studies.compression import CompressionPoint

    def point(c):
        n = 8.0 * (1 + c)
        return CompressionPoint(c, n, Measured(1.02 * n, 0.001), 0.1, 0.9, 0.0, 0.0, 0.3, Measured(1, 0),
                                Measured(300.0 * math.log(n), 0.5), 300.0, [])
    response, primitive, modulus = responses([point(-0.05), point(0.0), point(0.05)])
    assert response.value == pytest.approx(1.0, rel=1e-12) and primitive == pytest.approx(1.0, rel=1e-12)
    assert modulus.value == pytest.approx(300.0, rel=1e-12)
