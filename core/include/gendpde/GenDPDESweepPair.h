/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_SWEEP_PAIR_H_
#define GENDPDE_SWEEP_PAIR_H_

/* -------------------------------------------------------------------------- *
 * One pair of GenDPDEIntegrator's sweep (docs/theory.md sections 5-7), as   *
 * every engine performs it: the host platforms (GenDPDEPairSweep.h), the    *
 * device (kernels/gendpdeSweep.cc) and the LAMMPS fix (lammps/). An engine  *
 * brings the pair's geometry, the particles' state and the pair's random    *
 * stream; everything between (the unit vector, the relative velocity, the   *
 * order of the variates, the pair temperatures, the update of the internal  *
 * energies or of the bath, the impulse on the velocities) is written here   *
 * once.                                                                      *
 *                                                                            *
 * Written in the physics core's dialect (GenDPDEPhysicsCore.h, which comes  *
 * first): plain C, scalars, results through pointers. The includer also     *
 * defines the pair's random stream: GENDPDE_PAIR_STREAM, its type (a stream *
 * keyed on (seed, step, i, j) with i < j the particles' indices, so the     *
 * variates do not depend on the order of the pairs, the thread or the       *
 * engine), and GENDPDE_PAIR_NORMAL(stream), its next standard normal        *
 * variate. The host (GenDPDEPhysicsCoreDouble.h) uses CounterRandom's       *
 * PairStream; the device, the same generator in kernels/gendpdeRandom.cc.    *
 * -------------------------------------------------------------------------- */

#ifndef GENDPDE_PAIR_STREAM
#error "GenDPDESweepPair.h needs the pair's random stream: GENDPDE_PAIR_STREAM and GENDPDE_PAIR_NORMAL(stream)"
#endif

/** The amplitude alpha = sqrt(2 k_B kappa) of a pair's random heat (section 5), for heat conduction kappa. */
GENDPDE_CORE GENDPDE_REAL gendpdeHeatNoise(GENDPDE_REAL heatConduction, GENDPDE_REAL boltzmann) {
    return sqrt(2 * boltzmann * heatConduction);
}

/** The amplitude sigma = sqrt(2 gamma k_B T) of a pair's random impulse in the Isothermal mode (a bath at T). */
GENDPDE_CORE GENDPDE_REAL gendpdeBathNoise(GENDPDE_REAL friction, GENDPDE_REAL boltzmann, GENDPDE_REAL temperature) {
    return sqrt(2 * friction * boltzmann * temperature);
}

/**
 * One pair of the sweep at fixed positions, with the state the two particles have when the pair is reached:
 *  - internalEnergies != 0 (the Isoenergetic mode): gendpdePairUpdate at the pair temperatures of *energyI,
 *    *energyJ (gendpdePairTemperatures), its dissipative and random impulse where dissipation != 0 and its heat
 *    where conduction != 0; the variates come from the stream in that order (the impulse's, then the heat's), each
 *    drawn only where its term runs;
 *  - internalEnergies == 0 (the Isothermal mode): the DPD thermostat, gendpdePairImpulse with the friction gamma
 *    and the bath's noise sigma (gendpdeBathNoise), one variate; the energy goes to the bath.
 * dissipation and conduction are the step's terms (GenDPDEStepTerms: whether ANY pair of classes has friction,
 * heat conduction), not the pair's: a pair of zero friction in a run with friction still draws its variate, so that
 * every pair's stream is read the same way whatever its parameters.
 *
 * d = r_i - r_j = (dx, dy, dz) of length r (length), cutoff R of the pair terms; inverseMassI, inverseMassJ
 * (1/mass; a massless pair, both 0, and a pair at r = 0 are skipped); vi, vj the particles' velocities, three
 * components each (length/time), updated with the impulse P: v_i += P e/m_i, v_j -= P e/m_j, e = d/r;
 * energyI, energyJ their internal energies (energy; read and updated only with internalEnergies), heatCapacityI,
 * heatCapacityJ the C_V of their classes (energy/temperature); friction gamma (mass/time), heatConduction kappa
 * (energy temperature/time), heatNoise alpha = gendpdeHeatNoise(kappa) and bathNoise sigma of the pair's classes;
 * boltzmann k_B; stepSize dt and sqrtStepSize sqrt(dt) (time). Returns nonzero if an internal energy is now <= 0
 * (or not a number): the sweep stops at this pair.
 */
GENDPDE_CORE int gendpdeSweepPair(int dissipation, int conduction, int internalEnergies, GENDPDE_REAL dx,
                                  GENDPDE_REAL dy, GENDPDE_REAL dz, GENDPDE_REAL r, GENDPDE_REAL cutoff,
                                  GENDPDE_REAL inverseMassI, GENDPDE_REAL inverseMassJ, GENDPDE_REAL* vi,
                                  GENDPDE_REAL* vj, GENDPDE_ENERGY* energyI, GENDPDE_ENERGY* energyJ,
                                  GENDPDE_REAL heatCapacityI, GENDPDE_REAL heatCapacityJ, GENDPDE_REAL friction,
                                  GENDPDE_REAL heatConduction, GENDPDE_REAL heatNoise, GENDPDE_REAL bathNoise,
                                  GENDPDE_REAL boltzmann, GENDPDE_REAL stepSize, GENDPDE_REAL sqrtStepSize,
                                  GENDPDE_PAIR_STREAM* stream) {
    if (r == 0 || (inverseMassI == 0 && inverseMassJ == 0))
        return 0;
    const GENDPDE_REAL inverseDistance = 1 / r;
    const GENDPDE_REAL ex = dx * inverseDistance, ey = dy * inverseDistance, ez = dz * inverseDistance;
    const GENDPDE_REAL u0 = ex * (vi[0] - vj[0]) + ey * (vi[1] - vj[1]) + ez * (vi[2] - vj[2]);
    const GENDPDE_REAL omegaR = gendpdeRandomWeight(r, cutoff);
    GENDPDE_REAL impulse = 0;
    int failed = 0;
    if (!internalEnergies) {
        GENDPDE_REAL kineticChange;
        const GENDPDE_REAL xi = (GENDPDE_REAL) GENDPDE_PAIR_NORMAL(stream);
        impulse = gendpdePairImpulse(u0, omegaR, friction, bathNoise, stepSize, sqrtStepSize,
                                     inverseMassI + inverseMassJ, xi, &kineticChange);
    } else {
        GENDPDE_REAL pairThermalEnergy, inverseTemperatureDifference, frictionFactor;
        gendpdePairTemperatures(*energyI, *energyJ, heatCapacityI, heatCapacityJ, boltzmann, &pairThermalEnergy,
                                &inverseTemperatureDifference, &frictionFactor);
        const GENDPDE_REAL xi = (dissipation ? (GENDPDE_REAL) GENDPDE_PAIR_NORMAL(stream) : 0);
        const GENDPDE_REAL xiQ = (conduction ? (GENDPDE_REAL) GENDPDE_PAIR_NORMAL(stream) : 0);
        failed = gendpdePairUpdate(dissipation, conduction, pairThermalEnergy, inverseTemperatureDifference,
                                   frictionFactor, u0, omegaR, inverseMassI, inverseMassJ, friction, heatConduction,
                                   heatNoise, stepSize, sqrtStepSize, xi, xiQ, energyI, energyJ, &impulse);
    }
    if (!internalEnergies || dissipation) {
        const GENDPDE_REAL scaleI = impulse * inverseMassI, scaleJ = impulse * inverseMassJ;
        vi[0] += ex * scaleI;
        vi[1] += ey * scaleI;
        vi[2] += ez * scaleI;
        vj[0] -= ex * scaleJ;
        vj[1] -= ey * scaleJ;
        vj[2] -= ez * scaleJ;
    }
    return failed;
}

#endif /*GENDPDE_SWEEP_PAIR_H_*/
