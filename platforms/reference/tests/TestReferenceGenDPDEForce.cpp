#include "TestGenDPDEForce.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        platform = &OpenMM::Platform::getPlatformByName("Reference");
        ForceTests::runForceTests();
    });
}
