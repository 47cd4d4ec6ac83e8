#include "TestGenDPDEThermalState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadPlugins();
        platform = &OpenMM::Platform::getPlatformByName("Reference");
        ThermalTests::runThermalTests();
        ThermalTests::runThermalStateTests();
    });
}
