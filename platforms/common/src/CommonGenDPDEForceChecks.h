/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_FORCE_CHECKS_H_
#define COMMON_GENDPDE_FORCE_CHECKS_H_

#include "openmm/common/ArrayInterface.h"
#include "openmm/common/ComputeVectorTypes.h"
#include "openmm/internal/ContextImpl.h"

namespace GenDPDEPlugin {

/**
 * The cells of the integrator's sweep order at its last build (CommonGenDPDEBlockSweep), which a GenDPDEForce with
 * the same pair range makes its neighbour list from while it shares the build: (n_x, n_y, n_z, n_x n_y n_z); the first
 * entry of each cell (int); the particles cell by cell, by original index inside a cell (int); by original index: each
 * particle's cell (int), build position (mixed4) and slot (int, of this step).
 */
struct CommonGenDPDESharedGrid {
    OpenMM::mm_int4 cells;
    OpenMM::ArrayInterface *cellStart, *sortedAtom, *atomCell, *buildPosition, *slotOfAtom;
};

/**
 * What the integrator kernel lends a GenDPDEForce's kernel during a run of steps in which they share one build
 * (docs/performance.md, the GPU platforms): one check decides, by the sweep order's rule (GenDPDESweepDefinition.h),
 * when the order and the force's neighbour list are built, and one grid, the order's, serves both.
 */
class CommonGenDPDEBuildSource {
public:
    virtual ~CommonGenDPDEBuildSource() {}
    /**
     * Before the force's evaluation of a step (at the step's positions): launch the sweep's build check for this step
     * and, where a build is due, its cells. On the device the check also clears forceErrors[0..1] and sets
     * listRebuild[0] where the order is built, or if listForced. Returns the cells the list is to be made from.
     */
    virtual CommonGenDPDESharedGrid prepareBuild(OpenMM::ArrayInterface& listRebuild,
                                                 OpenMM::ArrayInterface& forceErrors, bool listForced) = 0;
};

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
    /**
     * For the run of steps now beginning: share the integrator's build if this force can (periodic, the same pair
     * range, laws that do not depend on temperature, which may evaluate a step twice); returns the list's rebuild
     * mark (one int on the device, which the sweep sets at builds it makes on its own), or null if it does not share.
     * null as source: the run is over.
     */
    virtual OpenMM::ArrayInterface* shareBuild(CommonGenDPDEBuildSource* source, double range) { return nullptr; }
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_FORCE_CHECKS_H_*/
