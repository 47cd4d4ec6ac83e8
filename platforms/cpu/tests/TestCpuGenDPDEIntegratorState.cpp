#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadPlugins();
        platform = &OpenMM::Platform::getPlatformByName("CPU");
        IntegratorStateTests::runIntegratorStateTests();
    });
}
