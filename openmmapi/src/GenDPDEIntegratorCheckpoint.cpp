/* GenDPDEIntegrator's per-particle state on its way out of and into a Context: checkpoints (Context.createCheckpoint)
 * and States (getState(getIntegratorParameters=True), Simulation.saveState). docs/integrator.md describes both
 * formats; every input is read and checked in full before the integrator's state changes. */

#include "GenDPDEIntegrator.h"
#include "GenDPDEKernels.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <locale>
#include <sstream>

using namespace GenDPDEPlugin;
using namespace OpenMM;

// Checkpoints (docs/integrator.md): magic, version, seed in use, count, the internal energies (binary, exact), and
// the magic again as an end mark. Version 1 (0.1.x) had no magic: version, seed, a flag byte, count, energies.
namespace {
const std::int32_t checkpointMagic = 0x45504447;   // "GDPE"
const std::int32_t checkpointVersion = 2;

template <class T>
void readOrFail(std::istream& stream, T& value, const char* what) {
    stream.read(reinterpret_cast<char*>(&value), sizeof(T));
    if (!stream)
        throw OpenMMException(std::string("GenDPDEIntegrator: the checkpoint ends before its ") + what
                              + " (truncated, or not written by a GenDPDEIntegrator)");
}
} // namespace

void GenDPDEIntegrator::createCheckpoint(std::ostream& stream) const {
    const IntegrateGenDPDEStepKernel& k = boundKernel();
    const std::vector<double>& energies = currentInternalEnergies();
    const std::int32_t version = checkpointVersion, seed = k.getSeed(), count = energies.size();
    stream.write((const char*) &checkpointMagic, sizeof(checkpointMagic));
    stream.write((const char*) &version, sizeof(version));
    stream.write((const char*) &seed, sizeof(seed));
    stream.write((const char*) &count, sizeof(count));
    stream.write((const char*) energies.data(), sizeof(double)*count);
    stream.write((const char*) &checkpointMagic, sizeof(checkpointMagic));
}

void GenDPDEIntegrator::loadCheckpoint(std::istream& stream) {
    // Everything is read and checked before the integrator's state changes.
    std::int32_t first, version, seed, count;
    readOrFail(stream, first, "header");
    if (first == checkpointMagic)
        readOrFail(stream, version, "version");
    else if (first == 1)
        version = 1;
    else
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds no GenDPDEIntegrator data (it was written by "
                              "another integrator, or is corrupt)");
    if (version < 1 || version > checkpointVersion)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds integrator data of version "
                              + std::to_string(version) + "; this build reads versions 1 to "
                              + std::to_string(checkpointVersion));
    readOrFail(stream, seed, "random seed");
    if (version == 1) {
        char unusedFlag;
        readOrFail(stream, unusedFlag, "flags");
    }
    readOrFail(stream, count, "particle count");
    const int numParticles = context->getSystem().getNumParticles();
    if (count != numParticles)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds " + std::to_string(count)
                              + " internal energies, the System has " + std::to_string(numParticles) + " particles");
    std::vector<double> energies(count);
    if (count > 0) {
        stream.read((char*) energies.data(), sizeof(double)*count);
        if (!stream)
            throw OpenMMException("GenDPDEIntegrator: the checkpoint ends before its internal energies (truncated)");
    }
    if (version >= 2) {
        std::int32_t end;
        readOrFail(stream, end, "end mark");
        if (end != checkpointMagic)
            throw OpenMMException("GenDPDEIntegrator: the checkpoint's integrator data has no end mark (corrupt)");
    }
    checkInternalEnergies(energies, "the checkpoint");
    IntegrateGenDPDEStepKernel& k = boundKernel();
    k.setSeed(seed);
    k.setInternalEnergies(energies);
}

// States (getState(getIntegratorParameters=True), Simulation.saveState): the internal energies as exact hex floats.
// Version 2 dropped version 1's temperaturesSet flag (an unset state is all zeros), which is still accepted.
void GenDPDEIntegrator::serializeParameters(SerializationNode& node) const {
    const IntegrateGenDPDEStepKernel& k = boundKernel();
    std::string text;
    char buffer[40];
    for (double e : currentInternalEnergies()) {
        std::snprintf(buffer, sizeof(buffer), "%a ", e);
        text += buffer;
    }
    node.setIntProperty("GenDPDEIntegratorVersion", 2);
    node.setIntProperty("seedInUse", k.getSeed());
    node.setStringProperty("internalEnergies", text);
}

void GenDPDEIntegrator::deserializeParameters(const SerializationNode& node) {
    // Everything is read and checked before the integrator's state changes.
    if (!node.hasProperty("internalEnergies") || !node.hasProperty("GenDPDEIntegratorVersion")
            || !node.hasProperty("seedInUse"))
        throw OpenMMException("GenDPDEIntegrator: the State does not hold GenDPDEIntegrator parameters (it was saved "
                              "with another integrator, or without getIntegratorParameters=True)");
    const int version = node.getIntProperty("GenDPDEIntegratorVersion");
    if (version < 1 || version > 2)
        throw OpenMMException("GenDPDEIntegrator: the State holds integrator parameters of version "
                              + std::to_string(version) + "; this build reads versions 1 to 2");
    std::vector<double> energies;
    std::istringstream text(node.getStringProperty("internalEnergies"));
    text.imbue(std::locale::classic());
    std::string token;
    while (text >> token) {
        char* end;
        const double value = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0')
            throw OpenMMException("GenDPDEIntegrator: the State's internal energies are corrupt: '" + token
                                  + "' (entry " + std::to_string(energies.size()) + ") is not a number");
        energies.push_back(value);
    }
    checkInternalEnergies(energies, "the State");
    IntegrateGenDPDEStepKernel& k = boundKernel();
    k.setSeed(node.getIntProperty("seedInUse"));
    k.setInternalEnergies(energies);
}
