#include "TestGenDPDEIntegratorState.h"
#include "TestPlugins.h"

OpenMM::Platform* platform;

int main() {
    return runTestProgram([]() {
        loadComputePlugins("OpenCL");
        platform = &OpenMM::Platform::getPlatformByName("OpenCL");
        // The shared tests, whose tolerances are those of double precision (TestOpenCLGenDPDEEqualsReference
        // compares single and mixed precision with Reference).
        platform->setPropertyDefaultValue("Precision", "double");
        IntegratorStateTests::runIntegratorStateTests();
    });
}
