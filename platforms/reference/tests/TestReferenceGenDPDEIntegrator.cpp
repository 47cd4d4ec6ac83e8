#include "TestGenDPDEIntegrator.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        platform = &OpenMM::Platform::getPlatformByName("Reference");
        IntegratorTests::runIntegratorTests();
    });
}
