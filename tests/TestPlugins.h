#ifndef GENDPDE_TEST_PLUGINS_H_
#define GENDPDE_TEST_PLUGINS_H_

/* Plugin loading for the C++ test programs. An installed plugin is loaded by `import openmm` (or by
 * Platform::loadPluginsFromDirectory in a C++ program) from OpenMM's plugin directory; a test runs this build's
 * kernel libraries instead, so it loads OpenMM's CPU platform and then this build's libraries by path (paths
 * compiled in by tests/CMakeLists.txt). Loading OpenMM's whole plugin directory could also load an installed copy
 * of this plugin. */

#include "openmm/Platform.h"
#include <string>

/** Load OpenMM's CPU platform and its kernels (libOpenMMCPU). */
inline void loadOpenMMCpuPlatform() {
    OpenMM::Platform::loadPluginLibrary(OPENMM_PLUGIN_DIR "/libOpenMMCPU.so");
}

/** Load one of OpenMM's GPU platforms ("OpenCL" or "CUDA") and this build's kernels for it. */
inline void loadComputePlugins(const std::string& platformName) {
    OpenMM::Platform::loadPluginLibrary(OPENMM_PLUGIN_DIR "/libOpenMM" + platformName + ".so");
    OpenMM::Platform::loadPluginLibrary(GENDPDE_PLUGIN_DIR "/libOpenMMGenDPDEReference.so");
    OpenMM::Platform::loadPluginLibrary(GENDPDE_PLUGIN_DIR "/libOpenMMGenDPDE" + platformName + ".so");
}

/** Load this build's kernel library for one platform ("Reference" or "CPU"). */
inline void loadGenDPDEKernels(const std::string& platformName) {
    OpenMM::Platform::loadPluginLibrary(GENDPDE_PLUGIN_DIR "/libOpenMMGenDPDE" + platformName + ".so");
}

/** The CPU platform and every kernel library of this build. */
inline void loadPlugins() {
    loadOpenMMCpuPlatform();
    loadGenDPDEKernels("Reference");
    loadGenDPDEKernels("CPU");
}

#endif /*GENDPDE_TEST_PLUGINS_H_*/
