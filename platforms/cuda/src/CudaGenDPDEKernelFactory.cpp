#include "CommonGenDPDEKernelFactory.h"
#include "CudaContext.h"
#include "CudaPlatform.h"

// The entry points OpenMM calls when it loads this library from its plugin directory: the CUDA platform only.
extern "C" OPENMM_EXPORT void registerPlatforms() {
}

extern "C" OPENMM_EXPORT void registerKernelFactories() {
    GenDPDEPlugin::CommonGenDPDEKernelFactory<OpenMM::CudaPlatform>::registerOn("CUDA");
}
