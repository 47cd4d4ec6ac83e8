"""The mapping from a fluid's physical properties to GenDPDE parameters (openmmgendpde.fluid) and `calibrate`."""

import json
import math

import numpy as np
import pytest
from openmm import unit

from openmmgendpde.__main__ import main
from openmmgendpde.fluid import (ARGON, WATER, Fluid, coarse_grain, heat_capacity_per_molecule,
                                 set_temperature_field)
from openmmgendpde.model import fcc_box
from openmmgendpde.presets import ARGON_CUTOFFS, ARGON_STATE, ARGON_UNITS

N_A = 6.02214076e23
K_B = 1.380649e-23


@pytest.mark.parametrize("published", ARGON_CUTOFFS, ids=lambda c: f"R*={c.cutoff}")
def test_argon_mapping_recovers_table_ii(published):
    """The paper's Table II (internal/LiquidArgon.h) from argon's physical state: T0, P0, n0, kappa_T0, C_V exactly
    (they define the reduced units), and for each published cutoff the printed gamma*, kappa* and f_cut to their
    last digit. eta and lambda are one value each for the three cutoffs (the paper's Table I of transport properties
    was not available: fluid.ARGON says how they were chosen), so this checks that the mapping's R^-5 law is the
    paper's: gamma* R*^5 varies by 0.05% across the printed values, and an R^-4 or R^-6 law misses them by 25%."""
    parameters = coarse_grain(ARGON, 5, cutoff=ARGON_UNITS.to_openmm(published.cutoff, "length"))
    reduced = parameters.reduced()
    assert reduced["n0*"] == pytest.approx(ARGON_STATE.density, rel=1e-9)
    assert reduced["T0*"] == pytest.approx(ARGON_STATE.temperature, rel=1e-9)
    assert reduced["pi0*"] == pytest.approx(ARGON_STATE.reference_pressure, rel=1e-9)
    assert reduced["B_T*"] == pytest.approx(ARGON_STATE.bulk_modulus, rel=1e-9)
    assert reduced["C_V*"] == pytest.approx(ARGON_STATE.heat_capacity, rel=1e-9)
    assert round(parameters.neighbors) == published.neighbors
    assert round(reduced["gamma*"], 2) == published.friction
    assert round(reduced["kappa*"], 4) == published.heat_conduction
    assert round(reduced["f_cut"], 2) == published.cutoff_scaling


def test_water_mapping_by_hand():
    """Water, 4 molecules per particle, 20 neighbours, against the formulas evaluated here in SI units."""
    p = coarse_grain(WATER, 4, neighbors=20)
    mass = 4 * 18.015e-3 / N_A                          # kg
    n0 = 997.05 / mass                                  # m^-3
    assert p.mass == pytest.approx(4 * 18.015, rel=1e-12)
    assert p.density == pytest.approx(n0 * 1e-27, rel=1e-12)
    per_mole_nm3 = N_A * 1e-27 / 1e3                    # Pa -> kJ/mol/nm^3
    assert p.bulk_modulus == pytest.approx(1 / (7 * 0.4525e-9) * per_mole_nm3, rel=1e-12)
    assert p.reference_pressure == pytest.approx((0.1e6 - n0 * K_B * 298.15) * per_mole_nm3, rel=1e-9)
    cutoff = (3 * 20 / (4 * math.pi * n0)) ** (1 / 3)  # m
    assert p.cutoff == pytest.approx(cutoff * 1e9, rel=1e-12)
    friction = 1575 * 0.89e-3 / (2 * math.pi * n0**2 * cutoff**5)                     # kg/s
    assert p.friction == pytest.approx(friction / 1.66053906660e-27 * 1e-12, rel=1e-8)   # amu/ps
    kappa = 315 * 0.6065 * 298.15**2 / (2 * math.pi * n0**2 * cutoff**5)               # J K/s
    assert p.heat_conduction == pytest.approx(kappa * N_A / 1e3 * 1e-12, rel=1e-9)      # kJ K/(mol ps)
    assert p.heat_capacity == pytest.approx(4 * 74.44e-3, rel=1e-12)


def test_units_of_the_properties_are_interchangeable():
    """The same water in other units, and c_v per molecule in J/K, per mole, or in k_B, gives the same model."""
    cv = 74.44 / (K_B * N_A)
    variants = [
        WATER,
        Fluid("water", 25.0 * unit.kelvin + 273.15 * unit.kelvin, 1.0 * unit.bar, 0.99705 * unit.gram / unit.centimeter**3,
              0.4525 / (1e9 * unit.pascal), cv, 0.89 * unit.pascal * unit.second / 1000,
              0.6065e-3 * unit.kilojoule / (unit.second * unit.meter * unit.kelvin), 18.015 * unit.dalton, 7.0),
        Fluid("water", 298.15 * unit.kelvin, 0.1 * unit.megapascal, 997.05 * unit.kilogram / unit.meter**3,
              0.4525e-9 / unit.pascal, cv * K_B * unit.joule / unit.kelvin, 0.89e-3 * unit.pascal * unit.second,
              0.6065 * unit.watt / (unit.meter * unit.kelvin), 18.015 * unit.gram / unit.mole, 7.0),
    ]
    reference = coarse_grain(variants[0], 4, neighbors=20)
    for fluid in variants[1:]:
        p = coarse_grain(fluid, 4, neighbors=20)
        for field in ("mass", "density", "reference_pressure", "bulk_modulus", "cutoff", "friction",
                      "heat_conduction", "heat_capacity", "temperature"):
            assert getattr(p, field) == pytest.approx(getattr(reference, field), rel=1e-9), field
    assert heat_capacity_per_molecule(1.0) == pytest.approx(K_B * N_A / 1000, rel=1e-12)


@pytest.mark.parametrize("call, message", [
    (lambda: coarse_grain(WATER, 0, neighbors=20), "molecules_per_particle = 0"),
    (lambda: coarse_grain(WATER, 4), "exactly one of neighbors"),
    (lambda: coarse_grain(WATER, 4, neighbors=20, cutoff=1.0), "exactly one of neighbors"),
    (lambda: coarse_grain(WATER, 4, neighbors=-1), "neighbors = -1"),
    (lambda: coarse_grain(Fluid("x", 300 * unit.kelvin, 1.0, WATER.mass_density, WATER.compressibility, 3.0,
                                WATER.shear_viscosity, WATER.thermal_conductivity, WATER.molar_mass), 4, neighbors=20),
     "pressure = 1.0 needs a unit"),
])
def test_bad_input_names_the_argument(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_calibrate_quick_on_water(tmp_path):
    """`calibrate --quick` sets water up and measures it back (a functional check: 500 particles, short runs).
    What is asserted is what the run controls: f_cut tuned so that n-bar is within 2% of n0 (two secant steps on
    ~1% statistical errors), the isoenergetic runs start at T0 and conserve energy (harmonic mean of theta_i within
    1%), every measured property finite with a finite error."""
    path = tmp_path / "water.json"
    results = main(["calibrate", "--quick", "--fluid", "water", "--platform", "CPU", "--json", str(path)])
    saved = json.loads(path.read_text())["results"]
    assert saved.keys() == results.keys()
    for name, entry in results.items():
        assert saved[name] == pytest.approx(entry), name
    density = results["density n-bar (nm^-3)"]
    assert density["model"] == pytest.approx(density["target"], rel=0.02)
    temperature = results["harmonic mean of theta_i (K)"]
    assert temperature["model"] == pytest.approx(temperature["target"], rel=0.01)
    for entry in results.values():
        assert math.isfinite(entry["model"]) and math.isfinite(entry["error"]) and entry["error"] >= 0


def test_fcc_box_fills_any_rectangular_box_at_the_density():
    """n_x x n_y x n_z cubic FCC cells: N = 4 n_x n_y n_z at exactly the density, every nearest-neighbour distance
    a/sqrt(2) (periodic images included), so a slab or an elongated box starts as a perfect crystal."""
    density = 8.0
    positions, box = fcc_box(density, (2, 3, 7))
    widths = np.array([box[0][0], box[1][1], box[2][2]])
    assert len(positions) == 4 * 2 * 3 * 7
    assert len(positions) / np.prod(widths) == pytest.approx(density, rel=1e-12)
    a = (4 / density) ** (1 / 3)
    delta = positions[:, None, :] - positions[None, :, :]
    delta -= widths * np.round(delta / widths)
    distance = np.sqrt((delta**2).sum(axis=-1)) + np.eye(len(positions)) * 1e9
    assert distance.min(axis=1) == pytest.approx(np.full(len(positions), a / math.sqrt(2)), rel=1e-12)


def test_slab_box_model_and_a_temperature_field():
    """A model in an elongated box (2 x 2 x 8 cells) with two halves at two temperatures set by a field."""
    import openmm
    parameters = coarse_grain(WATER, 4, neighbors=10)
    model = parameters.liquid(cells=(3, 3, 8))
    context = openmm.Context(model.system, model.integrator, openmm.Platform.getPlatformByName("Reference"))
    context.setPositions(model.positions)
    length = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer)
    set_temperature_field(model.integrator, model.positions, lambda r: 280.0 if r[2] < length / 2 else 320.0)
    theta = model.integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    expected = np.where(model.positions[:, 2] < length / 2, 280.0, 320.0)
    assert theta == pytest.approx(expected, rel=1e-12)
    with pytest.raises(ValueError, match="less than twice the cutoff"):
        parameters.liquid(cells=(1, 3, 8))


def test_stability_criterion_separates_a_good_step_from_a_blow_up():
    """The step-size test of openmmgendpde.stability on argon (V-B, Isoenergetic, 500 particles): dt* = 0.01 (the
    step of every argon study here, 10^5-step runs without a failure, docs/argon.md) passes; dt* = 1 (a particle
    crosses a neighbour's range in a few steps) fails."""
    from openmmgendpde.stability import _passes
    parameters = coarse_grain(ARGON, 5, neighbors=20)
    assert _passes(parameters, "VB", "Isoenergetic", 0.01, 1000, 500, "CPU", 1)
    assert not _passes(parameters, "VB", "Isoenergetic", 1.0, 1000, 500, "CPU", 1)


def test_conduction_wave_decays_at_the_rate_of_the_lattice_sum():
    """A case with a known answer for the wave-decay measurement that calibrate uses for the conductivity: particles
    on an FCC lattice too heavy to move (1e9 amu: they drift 1e-5 of a spacing), no conservative force, no friction,
    only heat conduction (a GenDPDEForce is in the System only to make it periodic: OpenMM's System is periodic when
    a force is; its forces move nothing here). A wave theta_i = T0 (1 + e sin(k z_i)) (e = 0.1) then obeys, to first order in e,
    d theta_i/dt = kappa/(C_V T0^2) sum_j omega_q(r_ij) (theta_j - theta_i), so its amplitude decays at exactly
        Gamma = kappa/(C_V T0^2) sum_j omega_q(r_0j) (1 - cos(k z_0j))
    (every lattice site alike; the sum over one site's neighbours, computed here with numpy). Measured: the mean of
    4 replicas (the conductive noise averages out) fitted by calibrate's decay fit, dt small against 1/Gamma (50
    steps per decay time, Shardlow error ~1%); tolerance 5% (second order in e ~1%, the noise left ~2%)."""
    import openmm
    from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
    from openmmgendpde.calibrate import _decay_rate
    density, temperature, heat_capacity, kappa = 8.0, 300.0, 0.3, 2.0e4
    positions, box = fcc_box(density, (4, 4, 8))
    cutoff = 0.9
    edges = np.diag(box)
    k = 2 * np.pi / edges[2]
    delta = positions - positions[0]
    delta -= edges * np.round(delta / edges)
    r = np.sqrt((delta**2).sum(axis=1))
    near = (r > 0) & (r < cutoff)
    omega = (1 - r[near] / cutoff) ** 2
    expected = kappa / (heat_capacity * temperature**2) * np.sum(omega * (1 - np.cos(k * delta[near, 2])))
    curves = []
    dt = 1 / (50 * expected)
    for seed in range(1, 5):
        system = openmm.System()
        system.setDefaultPeriodicBoxVectors(*[openmm.Vec3(*row) for row in box])
        for _ in positions:
            system.addParticle(1e9)
        periodic = GenDPDEForce(cutoff)
        periodic.setNonbondedMethod(GenDPDEForce.CutoffPeriodic)
        system.addForce(periodic)
        integrator = GenDPDEIntegrator(dt, 0.0, kappa, heat_capacity)
        integrator.setCutoffDistance(cutoff)
        integrator.setRandomNumberSeed(seed)
        context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("CPU"))
        context.setPositions(positions)
        set_temperature_field(integrator, positions, lambda p: temperature * (1 + 0.1 * np.sin(k * p[2])))
        amplitudes = []
        for n in range(41):
            if n:
                integrator.step(5)
            theta = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
            amplitudes.append(2 * np.mean(theta * np.sin(k * positions[:, 2])))
        curves.append(amplitudes)
    times = dt * 5 * np.arange(41)
    measured = _decay_rate(times, np.mean(curves, axis=0))
    print(f"lattice-sum decay rate {expected:.5f}/ps, measured {measured:.5f}/ps")
    assert measured == pytest.approx(expected, rel=0.05)
