/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CpuGenDPDEForceKernel.h"
#include "CpuGenDPDEIntegratorKernel.h"
#include "GenDPDEKernels.h"
#include "openmm/KernelFactory.h"
#include "openmm/OpenMMException.h"
#include "openmm/Platform.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** Creates the CPU kernels: Reference's algorithms on the CPU platform's threads ("Threads" property). */
class CpuGenDPDEKernelFactory : public KernelFactory {
public:
    KernelImpl* createKernelImpl(std::string name, const Platform& platform, ContextImpl& context) const override {
        if (name == CalcGenDPDEForceKernel::Name())
            return new CpuCalcGenDPDEForceKernel(name, platform);
        if (name == IntegrateGenDPDEStepKernel::Name())
            return new CpuIntegrateGenDPDEStepKernel(name, platform);
        throw OpenMMException("GenDPDE plugin: the CPU kernel factory cannot create kernel '" + name + "'");
    }
};

} // namespace

// The entry points OpenMM calls when it loads this library from its plugin directory: the CPU platform only.
extern "C" OPENMM_EXPORT void registerPlatforms() {}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    for (int i = 0; i < Platform::getNumPlatforms(); i++) {
        Platform& platform = Platform::getPlatform(i);
        if (platform.getName() != "CPU")
            continue;
        KernelFactory* factory = new CpuGenDPDEKernelFactory();
        platform.registerKernelFactory(CalcGenDPDEForceKernel::Name(), factory);
        platform.registerKernelFactory(IntegrateGenDPDEStepKernel::Name(), factory);
    }
}
