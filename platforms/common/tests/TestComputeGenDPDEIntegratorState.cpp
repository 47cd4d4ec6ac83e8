#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadComputePlugins(GENDPDE_TEST_PLATFORM);
        platform = &OpenMM::Platform::getPlatformByName(GENDPDE_TEST_PLATFORM);
        // The shared tests, whose tolerances are those of double precision (TestComputeGenDPDEEqualsReference
        // compares single and mixed precision with Reference).
        platform->setPropertyDefaultValue("Precision", "double");
        IntegratorStateTests::runIntegratorStateTests();
    });
}
