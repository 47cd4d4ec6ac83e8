/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_KERNEL_FACTORY_H_
#define COMMON_GENDPDE_KERNEL_FACTORY_H_

#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEIntegratorKernel.h"
#include "openmm/KernelFactory.h"
#include "openmm/OpenMMException.h"
#include "openmm/Platform.h"
#include "openmm/internal/ContextImpl.h"
#include <string>

namespace GenDPDEPlugin {

/**
 * Creates the Common kernels on one of OpenMM's Common platforms: PlatformType is OpenCLPlatform or CudaPlatform,
 * whose PlatformData holds one ComputeContext per device. The kernels run on one device: a Context spread over
 * several (DeviceIndex "0,1") is refused, naming the devices, rather than run on the first alone. localMemory gives
 * the local (shared) memory one work group may use on a device of the platform, in bytes.
 */
template <class PlatformType>
class CommonGenDPDEKernelFactory : public OpenMM::KernelFactory {
public:
    typedef int (*LocalMemory)(OpenMM::ComputeContext& cc);
    explicit CommonGenDPDEKernelFactory(LocalMemory localMemory) : localMemory(localMemory) {}
    OpenMM::KernelImpl* createKernelImpl(std::string name, const OpenMM::Platform& platform,
                                         OpenMM::ContextImpl& context) const override {
        auto& data = *static_cast<typename PlatformType::PlatformData*>(context.getPlatformData());
        const auto& contexts = data.contexts;
        if (contexts.size() != 1)
            throw OpenMM::OpenMMException("GenDPDE plugin: the " + platform.getName()
                                          + " kernels run on one device, "
                                            "and this Context uses "
                                          + std::to_string(contexts.size()) + " (DeviceIndex '"
                                          + data.propertyValues["DeviceIndex"]
                                          + "'); create the Context with one DeviceIndex");
        OpenMM::ComputeContext& cc = *contexts[0];
        if (name == CalcGenDPDEForceKernel::Name())
            return new CommonCalcGenDPDEForceKernel(name, platform, cc);
        if (name == IntegrateGenDPDEStepKernel::Name())
            return new CommonIntegrateGenDPDEStepKernel(name, platform, cc, localMemory(cc));
        throw OpenMM::OpenMMException("GenDPDE plugin: the " + platform.getName()
                                      + " kernel factory cannot create "
                                        "kernel '"
                                      + name + "'");
    }
    /** Register on the platform of this name, if OpenMM has it. */
    static void registerOn(const std::string& platformName, LocalMemory localMemory) {
        for (int i = 0; i < OpenMM::Platform::getNumPlatforms(); i++) {
            OpenMM::Platform& platform = OpenMM::Platform::getPlatform(i);
            if (platform.getName() != platformName)
                continue;
            OpenMM::KernelFactory* factory = new CommonGenDPDEKernelFactory<PlatformType>(localMemory);
            platform.registerKernelFactory(CalcGenDPDEForceKernel::Name(), factory);
            platform.registerKernelFactory(IntegrateGenDPDEStepKernel::Name(), factory);
        }
    }

private:
    LocalMemory localMemory;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_KERNEL_FACTORY_H_*/
