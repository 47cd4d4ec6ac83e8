/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_REFERENCE_KERNEL_ACCESS_H_
#define GENDPDE_REFERENCE_KERNEL_ACCESS_H_

/* Access to the state a Reference (or CPU) Context keeps in ReferencePlatform::PlatformData. */

#include "openmm/Vec3.h"
#include "openmm/internal/ContextImpl.h"
#include "openmm/reference/ReferencePlatform.h"
#include <vector>

namespace GenDPDEPlugin {

inline OpenMM::ReferencePlatform::PlatformData& platformData(OpenMM::ContextImpl& context) {
    return *reinterpret_cast<OpenMM::ReferencePlatform::PlatformData*>(context.getPlatformData());
}

/** Positions (nm). */
inline std::vector<OpenMM::Vec3>& extractPositions(OpenMM::ContextImpl& context) {
    return *platformData(context).positions;
}

/** Velocities (nm/ps). */
inline std::vector<OpenMM::Vec3>& extractVelocities(OpenMM::ContextImpl& context) {
    return *platformData(context).velocities;
}

/** Forces (kJ/mol/nm); kernels add to them. */
inline std::vector<OpenMM::Vec3>& extractForces(OpenMM::ContextImpl& context) {
    return *platformData(context).forces;
}

/** The three periodic box vectors (nm). */
inline OpenMM::Vec3* extractBoxVectors(OpenMM::ContextImpl& context) {
    return platformData(context).periodicBoxVectors;
}

/** The number of threads the platform was given (the CPU platform's "Threads" property). */
inline int extractNumThreads(OpenMM::ContextImpl& context) {
    return platformData(context).threads.getNumThreads();
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_REFERENCE_KERNEL_ACCESS_H_*/
