#include "internal/GenDPDEForceImpl.h"
#include "internal/BoxGeometry.h"
#include "openmm/OpenMMException.h"
#include "openmm/internal/ContextImpl.h"
#include <sstream>

using namespace GenDPDEPlugin;
using namespace OpenMM;

GenDPDEForceImpl::GenDPDEForceImpl(const GenDPDEForce& owner) : owner(owner) {
}

void GenDPDEForceImpl::initialize(ContextImpl& context) {
    const System& system = context.getSystem();
    if (owner.usesPeriodicBoundaryConditions()) {
        Vec3 box[3];
        system.getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", owner.getCutoffDistance(), box);
    }
    kernel = context.getPlatform().createKernel(CalcGenDPDEForceKernel::Name(), context);
    kernel.getAs<CalcGenDPDEForceKernel>().initialize(system, owner);
}

double GenDPDEForceImpl::calcForcesAndEnergy(ContextImpl& context, bool includeForces, bool includeEnergy, int groups) {
    if ((groups & (1<<owner.getForceGroup())) != 0)
        return kernel.getAs<CalcGenDPDEForceKernel>().execute(context, includeForces, includeEnergy);
    return 0.0;
}

std::vector<std::string> GenDPDEForceImpl::getKernelNames() {
    return {CalcGenDPDEForceKernel::Name()};
}

void GenDPDEForceImpl::updateParametersInContext(ContextImpl& context) {
    kernel.getAs<CalcGenDPDEForceKernel>().copyParametersToContext(context, owner);
    context.systemChanged();
}

const GenDPDEObservables& GenDPDEForceImpl::getObservables(ContextImpl& context, bool particleVirials) {
    return kernel.getAs<CalcGenDPDEForceKernel>().getObservables(context, particleVirials);
}

GenDPDEPairSource* GenDPDEForceImpl::getPairSource() {
    return kernel.getAs<CalcGenDPDEForceKernel>().getPairSource();
}
