/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main(int argc, char** argv) {
    return runComputeTestProgram(argc, argv, GENDPDE_TEST_PLATFORM, platform,
                                 []() { IntegratorStateTests::runIntegratorStateTests(); });
}
