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
 * whose PlatformData holds the ComputeContext (the first device's).
 */
template <class PlatformType>
class CommonGenDPDEKernelFactory : public OpenMM::KernelFactory {
public:
    OpenMM::KernelImpl* createKernelImpl(std::string name, const OpenMM::Platform& platform,
                                         OpenMM::ContextImpl& context) const override {
        OpenMM::ComputeContext& cc = *static_cast<typename PlatformType::PlatformData*>(context.getPlatformData())
                                             ->contexts[0];
        if (name == CalcGenDPDEForceKernel::Name())
            return new CommonCalcGenDPDEForceKernel(name, platform, cc);
        if (name == IntegrateGenDPDEStepKernel::Name())
            return new CommonIntegrateGenDPDEStepKernel(name, platform, cc);
        throw OpenMM::OpenMMException("GenDPDE plugin: the " + platform.getName() + " kernel factory cannot create "
                                      "kernel '" + name + "'");
    }
    /** Register on the platform of this name, if OpenMM has it. */
    static void registerOn(const std::string& platformName) {
        for (int i = 0; i < OpenMM::Platform::getNumPlatforms(); i++) {
            OpenMM::Platform& platform = OpenMM::Platform::getPlatform(i);
            if (platform.getName() != platformName)
                continue;
            OpenMM::KernelFactory* factory = new CommonGenDPDEKernelFactory<PlatformType>();
            platform.registerKernelFactory(CalcGenDPDEForceKernel::Name(), factory);
            platform.registerKernelFactory(IntegrateGenDPDEStepKernel::Name(), factory);
        }
    }
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_KERNEL_FACTORY_H_*/
