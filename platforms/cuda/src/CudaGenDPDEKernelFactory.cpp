/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDEKernelFactory.h"
#include "CudaContext.h"
#include "CudaPlatform.h"

namespace {

/** The static shared memory one CUDA thread block may use: 48 kB on every GPU OpenMM supports. */
int localMemory(OpenMM::ComputeContext& cc) {
    return 48 * 1024;
}

} // namespace

// The entry points OpenMM calls when it loads this library from its plugin directory: the CUDA platform only.
extern "C" OPENMM_EXPORT void registerPlatforms() {}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    GenDPDEPlugin::CommonGenDPDEKernelFactory<OpenMM::CudaPlatform>::registerOn("CUDA", localMemory);
}
