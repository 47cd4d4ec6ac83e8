/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_FORCE_CHECKS_H_
#define COMMON_GENDPDE_FORCE_CHECKS_H_

#include "openmm/common/ArrayInterface.h"
#include "openmm/internal/ContextImpl.h"

namespace GenDPDEPlugin {

/**
 * The checks of a GenDPDEForce's evaluation on OpenMM's Common platforms: after its density pass, two flags on the
 * device name the first particle whose position is not finite and the first whose state is invalid (no neighbour
 * under V-A, an overflowing equation of state). Normally the force waits for them after each evaluation and throws.
 * A GenDPDEIntegrator running a series of steps defers them instead: its own kernels read the flags on the device
 * (stopping the run before anything changes), clear them for the next evaluation, and the integrator reports the
 * error after the run through throwErrors(), so that a step never waits for the device.
 */
class CommonGenDPDEForceChecks {
public:
    virtual ~CommonGenDPDEForceChecks() {}
    /** While deferred, evaluations neither clear nor read the flags (the integrator's kernels do). */
    virtual void setDeferred(bool deferred) = 0;
    /** The two flags (ints, 0x7FFFFFFF when clear): nonFinite, the smallest original index of a particle whose
     *  position is not finite; invalid, the smallest 4 i + status over particles whose state is invalid. */
    virtual OpenMM::ArrayInterface& getErrorFlags() = 0;
    /** Throw the force's error for these flags, found at this step (the state is that of the step). */
    virtual void throwErrors(OpenMM::ContextImpl& context, int nonFinite, int invalid, long long step) = 0;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_FORCE_CHECKS_H_*/
