#include "ReferenceGenDPDEKernelFactory.h"
#include "openmm/Platform.h"

using namespace GenDPDEPlugin;

// The entry points OpenMM calls when it loads this library from its plugin directory. The CPU platform runs the
// Reference kernels for now: a CPU Context keeps its state in the Reference platform's data (CpuPlatform derives
// from ReferencePlatform), so they work there unchanged, on one thread.
extern "C" OPENMM_EXPORT void registerPlatforms() {
}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    ReferenceGenDPDEKernelFactory::registerOn("CPU");
}
