/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TEST_PLUGINS_H_
#define GENDPDE_TEST_PLUGINS_H_

/* Plugin loading for the C++ test programs. An installed plugin is loaded by `import openmm` (or by
 * Platform::loadPluginsFromDirectory in a C++ program) from OpenMM's plugin directory; a test runs this build's
 * kernel libraries instead, so it loads OpenMM's CPU platform and then this build's libraries by path (paths
 * compiled in by tests/CMakeLists.txt). Loading OpenMM's whole plugin directory could also load an installed copy
 * of this plugin. */

#include "TestUtilities.h"
#include "openmm/Platform.h"
#include <functional>
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

/**
 * The whole main() of a GPU platform's test driver (platforms/common/tests): load the platform platformName
 * ("OpenCL" or "CUDA") and this build's kernels for it, point platform at it, give it the precision named on the
 * command line (argv[1], double by default; the shared tests' tolerances follow it, precisionTolerance in
 * TestUtilities.h), and run tests.
 */
inline int runComputeTestProgram(int argc, char** argv, const std::string& platformName, OpenMM::Platform*& platform,
                                 const std::function<void()>& tests) {
    const std::string precision = (argc > 1 ? argv[1] : "double");
    return runTestProgram([&]() {
        loadComputePlugins(platformName);
        platform = &OpenMM::Platform::getPlatformByName(platformName);
        platform->setPropertyDefaultValue("Precision", precision);
        testPrecision() = precision;
        tests();
    });
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
