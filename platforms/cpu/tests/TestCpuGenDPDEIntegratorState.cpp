/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadPlugins();
        platform = &OpenMM::Platform::getPlatformByName("CPU");
        // The shared tests with 1, 2 and 3 threads (the results must not depend on the thread count).
        for (const char* threads : {"1", "2", "3"}) {
            platform->setPropertyDefaultValue("Threads", threads);
            IntegratorStateTests::runIntegratorStateTests();
        }
    });
}
