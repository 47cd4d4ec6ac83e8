/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* Each kernel library registers its kernels on its own platform and no other: `TestPluginRegistration P` loads
 * OpenMM's CPU platform and this build's kernel library for P only, then checks which platforms run the kernels.
 * (A factory registered on every ReferencePlatform subclass would also claim the CPU platform and, depending on
 * the load order, replace the CPU library's kernels.) */

#include "TestPlugins.h"
#include "TestUtilities.h"
#include "openmm/Platform.h"
#include <stdexcept>
#include <string>
#include <vector>

using namespace OpenMM;

int main(int argc, char** argv) {
    return runTestProgram([&]() {
        if (argc != 2)
            throw std::runtime_error("usage: TestPluginRegistration Reference|CPU");
        const std::string loaded = argv[1];
        loadOpenMMCpuPlatform();
        const std::vector<std::string> kernels = {"CalcGenDPDEForce", "IntegrateGenDPDEStep"};
        for (const std::string name : {"Reference", "CPU"})
            if (Platform::getPlatformByName(name).supportsKernels(kernels))
                throw std::runtime_error(name + " runs GenDPDE kernels before any kernel library is loaded");
        loadGenDPDEKernels(loaded);
        for (const std::string name : {"Reference", "CPU"}) {
            bool supported = Platform::getPlatformByName(name).supportsKernels(kernels);
            if (supported != (name == loaded))
                throw std::runtime_error("with only the " + loaded + " kernel library loaded, the " + name
                                         + " platform " + (supported ? "runs" : "does not run") + " the kernels");
        }
    });
}
