#include "CommonGenDPDEKernelFactory.h"
#include "OpenCLContext.h"
#include "OpenCLPlatform.h"

// The entry points OpenMM calls when it loads this library from its plugin directory: the OpenCL platform only.
extern "C" OPENMM_EXPORT void registerPlatforms() {
}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    GenDPDEPlugin::CommonGenDPDEKernelFactory<OpenMM::OpenCLPlatform>::registerOn("OpenCL");
}
