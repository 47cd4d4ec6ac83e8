/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator on the device (docs/theory.md sections 5-7): one step is startStep (the checks, a copy of the
 * state, the first kick), the Shardlow sweep of gendpdeSweep.cc (when the step has pair terms), and finishStep (the
 * second kick and the drift, or the roll back of a failed step). Velocities in `mixed` precision (velm, w = 1/m),
 * internal energies in `mixed` precision indexed by original particle index (atom reordering never moves them).
 *
 * Nothing here waits for the host: the status words (CommonGenDPDEStatus.h) say whether the run of steps has stopped,
 * and once it has, every kernel of every later step does nothing, so the state stays that of before the failing
 * step; the host reads the words after the run and names the particle and the step. The argument order of each
 * kernel is the enum of the same name in CommonGenDPDEIntegratorKernel.cpp. */

inline DEVICE mixed3 loadForce(GLOBAL const mm_long* RESTRICT forceBuffers, int slot) {
    const mixed scale = 1/(mixed) 0x100000000;
    return make_mixed3(scale*forceBuffers[slot], scale*forceBuffers[slot + PADDED_NUM_ATOMS],
                       scale*forceBuffers[slot + 2*PADDED_NUM_ATOMS]);
}

/**
 * The start of step stepIndex of a run. Each particle's velocity (and, with saveEnergies, every internal energy) is
 * kept for a roll back. The run stops (HALT_FORCE) if the GenDPDEForce whose checks this step makes (checkForce)
 * found a particle in an invalid state in its evaluation of this step (forceErrors, copied into the status words);
 * else each particle's step is checked (forces finite, no move farther than maxDisplacement; else the run stops,
 * HALT_UNSTABLE, with the smallest original index of such a particle) and it is kicked by kickStep F/m. Whether the
 * run stopped is never read here (it may be changing): finishStep undoes a stopped run's steps.
 */
KERNEL void startStep(GLOBAL mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers,
        GLOBAL const int* RESTRICT atomIndex, mixed stepSize, mixed maxDisplacement, mixed kickStep, int stepIndex,
        GLOBAL int* RESTRICT status, int checkForce, GLOBAL const int* RESTRICT forceErrors,
        GLOBAL mixed4* RESTRICT savedVelm, int saveEnergies, GLOBAL const mixed* RESTRICT energies,
        GLOBAL mixed* RESTRICT savedEnergies) {
    if (saveEnergies)
        for (int i = GLOBAL_ID; i < NUM_ATOMS; i += GLOBAL_SIZE)
            savedEnergies[i] = energies[i];
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE)
        savedVelm[slot] = velm[slot];
    if (checkForce && (forceErrors[0] != NO_VALUE || forceErrors[1] != NO_VALUE)) {
        if (GLOBAL_ID == 0) {
            status[STATUS_FORCE_NON_FINITE] = forceErrors[0];
            status[STATUS_FORCE_INVALID] = forceErrors[1];
            haltRun(status, HALT_FORCE, stepIndex);
        }
        return;
    }
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        mixed4 v = velm[slot];
        if (v.w == 0)
            continue;
        const mixed3 f = loadForce(forceBuffers, slot);
        const mixed3 displacement = (make_mixed3(v.x, v.y, v.z) + f*(stepSize*v.w))*stepSize;
        if (!(dot(displacement, displacement) <= maxDisplacement*maxDisplacement)) {
            ATOMIC_MIN(&status[STATUS_UNSTABLE], atomIndex[slot]);
            haltRun(status, HALT_UNSTABLE, stepIndex);
        }
        const mixed3 kick = f*(kickStep*v.w);
        v.x += kick.x;
        v.y += kick.y;
        v.z += kick.z;
        velm[slot] = v;
    }
}

/**
 * The end of a step: if the run has stopped (in this step or before), the velocities (and, with restoreEnergies, the
 * internal energies) of the step's start are restored, so a stopped run changes nothing; else each particle is
 * kicked by kickStep F/m (unless kickStep is 0) and moves r += driftStep v (posq plus its correction in mixed
 * precision).
 */
KERNEL void finishStep(GLOBAL mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers,
        GLOBAL real4* RESTRICT posq, GLOBAL real4* RESTRICT posqCorrection, mixed kickStep, mixed driftStep,
        GLOBAL const int* RESTRICT status, GLOBAL const mixed4* RESTRICT savedVelm, int restoreEnergies,
        GLOBAL mixed* RESTRICT energies, GLOBAL const mixed* RESTRICT savedEnergies) {
    if (status[STATUS_HALTED] != 0) {
        for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE)
            velm[slot] = savedVelm[slot];
        if (restoreEnergies)
            for (int i = GLOBAL_ID; i < NUM_ATOMS; i += GLOBAL_SIZE)
                energies[i] = savedEnergies[i];
        return;
    }
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        mixed4 v = velm[slot];
        if (v.w == 0)
            continue;
        if (kickStep != 0) {
            const mixed3 kick = loadForce(forceBuffers, slot)*(kickStep*v.w);
            v.x += kick.x;
            v.y += kick.y;
            v.z += kick.z;
            velm[slot] = v;
        }
        mixed3 r = loadMixedPosition(posq, posqCorrection, slot);
        r.x += v.x*driftStep;
        r.y += v.y*driftStep;
        r.z += v.z*driftStep;
        const real4 old = posq[slot];
#ifdef USE_MIXED_PRECISION
        const real4 rounded = make_real4((real) r.x, (real) r.y, (real) r.z, old.w);
        posq[slot] = rounded;
        posqCorrection[slot] = make_real4(r.x - (mixed) rounded.x, r.y - (mixed) rounded.y, r.z - (mixed) rounded.z, 0);
#else
        posq[slot] = make_real4(r.x, r.y, r.z, old.w);
#endif
    }
}

/**
 * The thermal state a GenDPDEForce's evaluation found (C_V theta_i and sigma(n_i), by original index, docs/theory.md
 * section 11), kept as the particles' state, unless the run has stopped or the evaluation found an invalid particle
 * (forceErrors, when this run makes the force's checks): a failed evaluation leaves the state as it was, as on the
 * host platforms, whose force stops before the state is kept.
 */
KERNEL void keepThermalState(GLOBAL const mixed* RESTRICT thermalEnergy, GLOBAL const mixed* RESTRICT densityEntropy,
        GLOBAL mixed* RESTRICT energies, GLOBAL mixed* RESTRICT entropies, GLOBAL const int* RESTRICT status,
        int checkForce, GLOBAL const int* RESTRICT forceErrors) {
    if (status[STATUS_HALTED] != 0 || (checkForce && (forceErrors[0] != NO_VALUE || forceErrors[1] != NO_VALUE)))
        return;
    for (int i = GLOBAL_ID; i < NUM_ATOMS; i += GLOBAL_SIZE) {
        energies[i] = thermalEnergy[i];
        entropies[i] = densityEntropy[i];
    }
}

/** Each particle's kinetic energy with the on-step velocity v + (dt/2) F/m. */
KERNEL void kineticEnergies(GLOBAL const mixed4* RESTRICT velm, GLOBAL const mm_long* RESTRICT forceBuffers,
                            mixed halfStep, GLOBAL mixed* RESTRICT energy) {
    for (int slot = GLOBAL_ID; slot < NUM_ATOMS; slot += GLOBAL_SIZE) {
        const mixed4 v = velm[slot];
        if (v.w == 0)
            energy[slot] = 0;
        else {
            const mixed3 u = make_mixed3(v.x, v.y, v.z) + loadForce(forceBuffers, slot)*(halfStep*v.w);
            energy[slot] = dot(u, u)/(2*v.w);
        }
    }
}
