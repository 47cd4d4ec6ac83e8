#include "TestGenDPDEIntegrator.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        OpenMM::Platform::loadPluginsFromDirectory(OpenMM::Platform::getDefaultPluginsDirectory());
        platform = &OpenMM::Platform::getPlatformByName("CPU");
        IntegratorTests::runIntegratorTests();
    });
}
