/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "ReferenceGenDPDEKernelFactory.h"
#include "GenDPDEKernels.h"
#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceGenDPDEIntegratorKernel.h"
#include "openmm/OpenMMException.h"
#include "openmm/Platform.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

KernelImpl* ReferenceGenDPDEKernelFactory::createKernelImpl(std::string name, const Platform& platform,
                                                            ContextImpl& context) const {
    if (name == CalcGenDPDEForceKernel::Name())
        return new ReferenceCalcGenDPDEForceKernel(name, platform);
    if (name == IntegrateGenDPDEStepKernel::Name())
        return new ReferenceIntegrateGenDPDEStepKernel(name, platform);
    throw OpenMMException("GenDPDE plugin: the Reference kernel factory cannot create kernel '" + name + "'");
}

std::vector<std::string> ReferenceGenDPDEKernelFactory::kernelNames() {
    return {CalcGenDPDEForceKernel::Name(), IntegrateGenDPDEStepKernel::Name()};
}

void ReferenceGenDPDEKernelFactory::registerOn(const std::string& platformName) {
    for (int i = 0; i < Platform::getNumPlatforms(); i++) {
        Platform& platform = Platform::getPlatform(i);
        if (platform.getName() != platformName)
            continue;
        KernelFactory* factory = new ReferenceGenDPDEKernelFactory();
        for (const std::string& name : kernelNames())
            platform.registerKernelFactory(name, factory);
    }
}

// The entry points OpenMM calls when it loads this library from its plugin directory: the Reference platform only
// (registering on every ReferencePlatform subclass would also claim the CPU platform, which has its own library).
extern "C" OPENMM_EXPORT void registerPlatforms() {}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    ReferenceGenDPDEKernelFactory::registerOn("Reference");
}
