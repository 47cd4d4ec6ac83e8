# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The particles' thermal state with a law that depends on temperature, as a user meets it from Python: liquid argon
with its thermal expansion (expansion.mapped(): TaitThermalExpansion, 5 atoms per particle). What each call keeps is
one rule (docs/integrator.md, "The particles' thermal state: one rule"); its every case is tested on every platform
against the brute-force oracle in C++ (tests/TestGenDPDEThermalState.h). Here: the calls that broke it before, and a
run that goes bad stopping at once."""

import copy

import numpy as np
import openmm
import pytest
from openmm import unit

from openmmgendpde import GenDPDEForce, GenDPDEIntegrator
from openmmgendpde.calibration.expansion import mapped
from openmmgendpde.studies.slab import argon_model, slab_positions

KELVIN = unit.kelvin
KJ = unit.kilojoule_per_mole
PER_NM3 = unit.nanometer**-3


def melted_liquid(platform="CPU", num_particles=256, barostat=None, massless=False):
    """The mapped liquid (256 particles), melted (Isothermal), then Isoenergetic with energies drawn at T0."""
    parameters = mapped()
    model = parameters.liquid(num_particles, mode=GenDPDEIntegrator.Isothermal, seed=3)
    if barostat is not None:
        model.system.addForce(barostat)
    if massless:
        for i in range(model.system.getNumParticles()):
            model.system.setParticleMass(i, 0.0)
        model.integrator.setTemperature(parameters.temperature)
        context = openmm.Context(model.system, model.integrator, openmm.Platform.getPlatformByName(platform))
        context.setPositions(model.positions * unit.nanometer)
        model.integrator.setMode(GenDPDEIntegrator.Conservative)
        model.integrator.setInternalEnergiesToTemperature(parameters.temperature, 3)
        return parameters, model, context
    return parameters, model, model.melted(platform, GenDPDEIntegrator.Isoenergetic, 100, 50, seed=3)


def temperatures(integrator):
    return integrator.getParticleTemperatures().value_in_unit(KELVIN)


@pytest.mark.parametrize("change", ["beta x2.1", "beta -1", "law VanDerWaals", "f_cut 1.0", "estimator VA"])
def test_a_parameter_update_keeps_every_temperature(change):
    # Before: beta 0.955 -> 2.0 took <theta> from 132.9 K to 12.0 K, beta -> -1 to 11,887 K, f_cut -> 1 to 84 K.
    parameters, model, context = melted_liquid()
    force, integrator = model.force, model.integrator
    before = temperatures(integrator)
    conserved = integrator.getConservedEnergy().value_in_unit(KJ)
    law, (beta, theta0) = force.getEquationOfState()
    if change.startswith("beta"):   # (kJ/mol/nm^3/K: 0.955 mapped)
        beta = beta.value_in_unit(KJ / unit.nanometer**3 / KELVIN)
        force.setEquationOfState(law, [2.1 * beta if change == "beta x2.1" else -1.0, theta0])
    elif change == "law VanDerWaals":
        # (k = C_V/20, b a tenth of the volume per particle, a = 0: the law holds at these densities)
        force.setEquationOfState(GenDPDEForce.VanDerWaals, [0.0, 0.1 / 4.27, parameters.heat_capacity / 20])
    elif change == "f_cut 1.0":
        force.setCutoffScaling(1.0)
    else:
        force.setDensityEstimator(GenDPDEForce.VA)
    force.updateParametersInContext(context)
    assert np.array_equal(temperatures(integrator), before)
    # The law changed, not the particles: K + U + sum eps changes by the change of U only, and the run goes on.
    assert integrator.getConservedEnergy().value_in_unit(KJ) != conserved
    integrator.step(5)


@pytest.mark.parametrize("how", ["a fresh Context", "loadCheckpoint", "setInternalEnergies"])
def test_reading_before_an_adiabatic_compression_changes_nothing(how):
    # Before: after loadCheckpoint, setInternalEnergies or in a fresh Context a 3% compression by setPositions kept
    # <theta> at 132.7 K, and heated it to 162.1 K if getInternalEnergies() was called first.
    def compressed(read_first):
        parameters, model, context = melted_liquid()
        integrator = model.integrator
        if how == "a fresh Context":
            positions = context.getState(getPositions=True).getPositions()
            energies = integrator.getInternalEnergies()
            integrator = copy.deepcopy(integrator)   # (its parameters; one Context per integrator)
            context = openmm.Context(model.system, integrator, openmm.Platform.getPlatformByName("CPU"))
            integrator.setInternalEnergies(energies)
            context.setPositions(positions)
        elif how == "loadCheckpoint":
            context.loadCheckpoint(context.createCheckpoint())
        else:
            integrator.setInternalEnergies(integrator.getInternalEnergies())
        integrator.setAdiabaticPositionChanges(True)
        if read_first:
            integrator.getInternalEnergies()
            integrator.getParticleTemperatures()
            context.getState(getEnergy=True, getForces=True, getIntegratorParameters=True)
            model.force.getParticlePressures(context)
        theta = temperatures(integrator)
        state = context.getState(getPositions=True)
        n = model.force.getParticleDensities(context).value_in_unit(PER_NM3)
        scale = 0.97 ** (1 / 3)
        a, b, c = state.getPeriodicBoxVectors()
        context.setPeriodicBoxVectors(a * scale, b * scale, c * scale)
        context.setPositions(state.getPositions(asNumpy=True) * scale)
        n1 = model.force.getParticleDensities(context).value_in_unit(PER_NM3)
        # the isentropic law of TaitThermalExpansion, sigma = beta/n: theta'/theta = exp(-beta (1/n' - 1/n)/C)
        expected = theta * np.exp(-parameters.thermal_pressure * (1 / n1 - 1 / n) / parameters.heat_capacity)
        return theta, temperatures(integrator), expected
    before, plain, expected = compressed(False)
    assert np.array_equal(plain, compressed(True)[1])
    np.testing.assert_allclose(plain, expected, rtol=1e-9)
    assert np.mean(plain) > np.mean(before) + 5   # (a 3% compression heats this liquid by 9.9 K)


@pytest.mark.parametrize("adiabatic", [False, True])
def test_a_barostat_move_follows_the_setting(adiabatic):
    # Before: 20 moves compressing V by 6.2% heated <theta> from 132.3 to 152.6 K whatever the setting. The particles
    # have no mass here, so that the barostat's moves are the only change (Conservative mode).
    barostat = openmm.MonteCarloBarostat(3000 * unit.bar, 135.7 * KELVIN, 1)
    barostat.setRandomNumberSeed(5)
    parameters, model, context = melted_liquid(barostat=barostat, massless=True)
    integrator = model.integrator
    integrator.setAdiabaticPositionChanges(adiabatic)
    before = temperatures(integrator)
    n = model.force.getParticleDensities(context).value_in_unit(PER_NM3)
    volume = context.getState().getPeriodicBoxVolume()
    integrator.step(20)
    assert context.getState().getPeriodicBoxVolume() / volume < 0.99   # (compressed by the moves)
    after = temperatures(integrator)
    if adiabatic:
        n1 = model.force.getParticleDensities(context).value_in_unit(PER_NM3)
        expected = before * np.exp(-parameters.thermal_pressure * (1 / n1 - 1 / n) / parameters.heat_capacity)
        np.testing.assert_allclose(after, expected, rtol=1e-9)
        assert np.mean(after) > np.mean(before) + 1
    else:
        assert np.array_equal(after, before)


@pytest.mark.parametrize("damage", ["truncated", "a flipped byte in the energies", "a flipped byte in the positions",
                                    "1000 zero bytes appended"])
def test_a_refused_checkpoint_changes_nothing(damage):
    # Before: a truncated checkpoint was refused yet the temperatures changed by up to 39%; a flipped byte in the
    # energies and appended bytes were accepted.
    parameters, model, context = melted_liquid()
    integrator = model.integrator
    checkpoint = context.createCheckpoint()
    integrator.step(30)
    before, energies = temperatures(integrator), integrator.getInternalEnergies()
    n = context.getSystem().getNumParticles()
    damaged = bytearray(checkpoint)
    if damage == "truncated":
        damaged = damaged[:-10]
    elif damage == "a flipped byte in the energies":
        damaged[-16 - 8 * (n - 89)] ^= 0x40   # particle 89's internal energy
    elif damage == "a flipped byte in the positions":
        damaged[len(damaged) // 3] ^= 0x01
    else:
        damaged += bytes(1000)
    with pytest.raises(openmm.OpenMMException, match="GenDPDEIntegrator: the checkpoint"):
        context.loadCheckpoint(bytes(damaged))
    assert np.array_equal(temperatures(integrator), before)
    assert np.array_equal(integrator.getInternalEnergies().value_in_unit(KJ), energies.value_in_unit(KJ))


def test_a_slab_whose_surface_particle_is_not_integrated_stops_at_once():
    # Before: a V-C slab in vacuum of the expanding argon at dt* = 0.01 (the bulk liquid's step, ~3x the one
    # stability.suggest_time_step gives a slab) ran on silently while a surface particle's temperature swung by
    # factors of 2-20 per step, until the conserved energy jumped by +365 kJ/mol in one go (at step 2250 with the
    # sweep order of 0.2-0.4; the particle at 0.2 K), and the run stopped much later naming another particle, or never
    # (OpenCL). Now the first step that changes a particle's temperature by more than a factor 2 by its motion alone
    # stops the run, naming it, before any jump: the conserved energy at the stop is within 5 kJ/mol of its value
    # 100-200 steps earlier (the slab's steady drift at this step is at most ~2 kJ/mol per 100 steps, measured; the
    # jump was 365). When the run goes bad depends on the trajectory (the current order stops at step 4548).
    positions, box, thickness = slab_positions(cells=(4, 4, 4))
    slab, context = argon_model(positions, box, "VC", platform="CPU")
    slab.force.setEquationOfState(GenDPDEForce.TaitThermalExpansion, [0.955, 125.7])
    context.reinitialize(preserveState=True)
    integrator = slab.integrator
    energies = [integrator.getConservedEnergy().value_in_unit(KJ)]
    with pytest.raises(openmm.OpenMMException, match=r"the temperature of particle (\d+) went from .* more than a "
                                                     r"factor 2, at step (\d+)") as error:
        for _ in range(80):
            integrator.step(100)
            energies.append(integrator.getConservedEnergy().value_in_unit(KJ))
    assert len(energies) >= 2
    assert abs(integrator.getConservedEnergy().value_in_unit(KJ) - energies[-2]) < 5
    # The particle named is at a free surface: its density well below the liquid's (4.27 nm^-3).
    particle = int(str(error.value).split("particle ")[1].split()[0])
    assert slab.force.getParticleDensities(context)[particle].value_in_unit(PER_NM3) < 2.0
