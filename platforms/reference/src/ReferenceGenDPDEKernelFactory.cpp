#include "GenDPDEKernels.h"
#include "ReferenceGenDPDEForceKernel.h"
#include "ReferenceGenDPDEIntegratorKernel.h"
#include "openmm/KernelFactory.h"
#include "openmm/OpenMMException.h"
#include "openmm/reference/ReferencePlatform.h"
#include <mutex>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** Creates the Reference kernels; also serves the CPU platform, which derives from ReferencePlatform. */
class ReferenceGenDPDEKernelFactory : public KernelFactory {
public:
    KernelImpl* createKernelImpl(std::string name, const Platform& platform, ContextImpl& context) const override {
        if (name == CalcGenDPDEForceKernel::Name())
            return new ReferenceCalcGenDPDEForceKernel(name, platform);
        if (name == IntegrateGenDPDEStepKernel::Name())
            return new ReferenceIntegrateGenDPDEStepKernel(name, platform);
        throw OpenMMException("GenDPDE plugin: the Reference kernel factory cannot create kernel '" + name + "'");
    }
};

std::vector<std::string> kernelNames() {
    return {CalcGenDPDEForceKernel::Name(), IntegrateGenDPDEStepKernel::Name()};
}

} // namespace

void GenDPDEPlugin::registerGenDPDEKernelFactories() {
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    for (int i = 0; i < Platform::getNumPlatforms(); i++) {
        Platform& platform = Platform::getPlatform(i);
        if (dynamic_cast<ReferencePlatform*>(&platform) == nullptr || platform.supportsKernels(kernelNames()))
            continue;
        KernelFactory* factory = new ReferenceGenDPDEKernelFactory();   // owned by the platform
        for (const std::string& name : kernelNames())
            platform.registerKernelFactory(name, factory);
    }
}

// The entry points OpenMM calls when the library is loaded with Platform.loadPluginsFromDirectory().
extern "C" OPENMM_EXPORT void registerPlatforms() {
}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    registerGenDPDEKernelFactories();
}
