#include "TestGenDPDEThermal.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main(int argc, char** argv) {
    const std::string precision = (argc > 1 ? argv[1] : "double");
    return runTestProgram([&]() {
        loadComputePlugins(GENDPDE_TEST_PLATFORM);
        platform = &OpenMM::Platform::getPlatformByName(GENDPDE_TEST_PLATFORM);
        // The shared tests in the precision named on the command line (double by default); their tolerances follow
        // it (precisionTolerance in TestUtilities.h).
        platform->setPropertyDefaultValue("Precision", precision);
        testPrecision() = precision;
        ThermalTests::runThermalTests();
    });
}
