/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The integrator's status words on the device (CommonGenDPDEStatus.h, whose layout arrives as the STATUS_* defines):
 * once a run of steps stops, every later kernel of the run does nothing or undoes its step. */

/** Stop the run at step stepIndex for this reason, unless it stopped already (the first stop is the one kept). */
inline DEVICE void haltRun(GLOBAL int* RESTRICT status, int reason, int stepIndex) {
    if (ATOMIC_CAS(&status[STATUS_HALTED], 0, reason) == 0)
        status[STATUS_HALT_STEP] = stepIndex;
}
