/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadPlugins();
        platform = &OpenMM::Platform::getPlatformByName("Reference");
        IntegratorStateTests::runIntegratorStateTests();
    });
}
