/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDEKernelFactory.h"
#include "OpenCLContext.h"
#include "OpenCLPlatform.h"

namespace {

/** The local memory of the Context's device (CL_DEVICE_LOCAL_MEM_SIZE; at least 32 kB on every OpenCL GPU). */
int localMemory(OpenMM::ComputeContext& cc) {
    const cl_ulong size = dynamic_cast<OpenMM::OpenCLContext&>(cc).getDevice().getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
    return (int) std::min<cl_ulong>(size, 1 << 20);
}

} // namespace

// The entry points OpenMM calls when it loads this library from its plugin directory: the OpenCL platform only.
extern "C" OPENMM_EXPORT void registerPlatforms() {}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    GenDPDEPlugin::CommonGenDPDEKernelFactory<OpenMM::OpenCLPlatform>::registerOn("OpenCL", localMemory);
}
