#include "TestGenDPDEForce.h"

OpenMM::Platform* platform;

// The CPU platform runs the Reference kernels of this plugin; this checks that they are registered and work there.
int main() {
    return runTestProgram([]() {
        OpenMM::Platform::loadPluginsFromDirectory(OpenMM::Platform::getDefaultPluginsDirectory());
        platform = &OpenMM::Platform::getPlatformByName("CPU");
        ForceTests::runForceTests();
    });
}
