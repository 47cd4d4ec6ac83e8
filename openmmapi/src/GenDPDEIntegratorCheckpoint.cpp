/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator's per-particle state on its way out of and into a Context: checkpoints (Context.createCheckpoint)
 * and States (getState(getIntegratorParameters=True), Simulation.saveState). docs/integrator.md describes both
 * formats; every input is read and checked in full before the integrator's state changes. */

#include "GenDPDEIntegrator.h"
#include "GenDPDEKernels.h"
#include "internal/StrictXml.h"
#include "openmm/OpenMMException.h"
#include "openmm/serialization/SerializationNode.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

using namespace GenDPDEPlugin;
using namespace OpenMM;

// Checkpoints (docs/integrator.md). Version 4: magic, version, seed in use, count, the internal energies (binary,
// exact), whether the sweep's order is built (0 or 1) and if so the box vectors (9 doubles) and positions (3 count
// doubles) of its build, what the checksum covers (0: this data, 1: also OpenMM's part of the checkpoint before it, from its header),
// the checksum (FNV-1a, 64 bits), and the magic again as an end mark; nothing may follow. Version 3 had no build
// (a run continued from it builds the order at its first step) and is still read. Versions 2 (no coverage, no
// checksum) and 1 (0.1.x, no magic: version, seed, a flag byte, count, energies) are refused, named: without a
// checksum their values cannot be checked.
namespace {
const std::int32_t checkpointMagic = 0x45504447; // "GDPE"
const std::int32_t checkpointVersion = 4;
// The header of OpenMM's checkpoints (ContextImpl::createCheckpoint writes these bytes and their terminating NUL).
const char openmmCheckpointHeader[] = "OpenMM Binary Checkpoint\n";
const std::int32_t coversIntegratorData = 0, coversWholeCheckpoint = 1;

/** FNV-1a (64 bits) of size bytes, continuing from hash: a change of any one byte always changes it. */
std::uint64_t fnv1a(const void* data, size_t size, std::uint64_t hash = 14695981039346656037ULL) {
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; i++) {
        hash ^= bytes[i];
        hash *= 1099511628211ULL;
    }
    return hash;
}

/** OpenMM's part of a checkpoint: the bytes of content before end, from the last OpenMM header on (false if none). */
bool openmmPart(const std::string& content, size_t end, std::string& part) {
    const std::string header(openmmCheckpointHeader, sizeof(openmmCheckpointHeader));
    const size_t start = content.rfind(header, end < header.size() ? 0 : end - header.size());
    if (start == std::string::npos || start + header.size() > end)
        return false;
    part = content.substr(start, end - start);
    return true;
}

/** The sweep order's build in a checkpoint (version 4): its positions and box, if an order is built. */
struct SweepBuild {
    std::int32_t built = 0;
    Vec3 box[3];
    std::vector<Vec3> positions;
};

/**
 * The checksum of versions 3 and 4: OpenMM's part (if covered), then the integrator's data up to the coverage word
 * (build: null for version 3).
 */
std::uint64_t checkpointChecksum(const std::string* openmm, std::int32_t version, std::int32_t seed,
                                 const std::vector<double>& energies, const SweepBuild* build, std::int32_t coverage) {
    std::uint64_t hash = fnv1a(openmm != nullptr ? openmm->data() : nullptr, openmm != nullptr ? openmm->size() : 0);
    const std::int32_t count = energies.size();
    for (std::int32_t word : {checkpointMagic, version, seed, count})
        hash = fnv1a(&word, sizeof(word), hash);
    hash = fnv1a(energies.data(), energies.size() * sizeof(double), hash);
    if (build != nullptr) {
        hash = fnv1a(&build->built, sizeof(build->built), hash);
        if (build->built) {
            hash = fnv1a(build->box, sizeof(build->box), hash);
            hash = fnv1a(build->positions.data(), build->positions.size() * sizeof(Vec3), hash);
        }
    }
    return fnv1a(&coverage, sizeof(coverage), hash);
}

template <class T>
void readOrFail(std::istream& stream, T& value, const char* what) {
    stream.read(reinterpret_cast<char*>(&value), sizeof(T));
    if (!stream)
        throw OpenMMException(std::string("GenDPDEIntegrator: the checkpoint ends before its ") + what
                              + " (truncated, or not written by a GenDPDEIntegrator)");
}
} // namespace

void GenDPDEIntegrator::createCheckpoint(std::ostream& stream) const {
    requireRunNotStopped("create a checkpoint");
    const IntegrateGenDPDEStepKernel& k = boundKernel();
    const std::vector<double>& energies = k.getInternalEnergies(); // C_V theta_i at the current positions
    // OpenMM's part is covered where the stream's buffer can be read back (a string buffer: Python's
    // Context.createCheckpoint, Simulation.saveCheckpoint, Context.reinitialize).
    std::string openmm;
    std::int32_t coverage = coversIntegratorData;
    if (std::stringbuf* buffer = dynamic_cast<std::stringbuf*>(stream.rdbuf())) {
        const std::streampos here = stream.tellp();
        if (here != std::streampos(-1) && openmmPart(buffer->str(), (size_t) here, openmm))
            coverage = coversWholeCheckpoint;
    }
    SweepBuild build;
    build.built = k.getSweepBuild(build.positions, build.box) ? 1 : 0;
    const std::int32_t version = checkpointVersion, seed = k.getSeed(), count = energies.size();
    const std::uint64_t checksum = checkpointChecksum(coverage == coversWholeCheckpoint ? &openmm : nullptr, version,
                                                      seed, energies, &build, coverage);
    stream.write((const char*) &checkpointMagic, sizeof(checkpointMagic));
    stream.write((const char*) &version, sizeof(version));
    stream.write((const char*) &seed, sizeof(seed));
    stream.write((const char*) &count, sizeof(count));
    stream.write((const char*) energies.data(), sizeof(double) * count);
    stream.write((const char*) &build.built, sizeof(build.built));
    if (build.built) {
        stream.write((const char*) build.box, sizeof(build.box));
        stream.write((const char*) build.positions.data(), sizeof(Vec3) * count);
    }
    stream.write((const char*) &coverage, sizeof(coverage));
    stream.write((const char*) &checksum, sizeof(checksum));
    stream.write((const char*) &checkpointMagic, sizeof(checkpointMagic));
}

void GenDPDEIntegrator::readCheckpoint(std::istream& stream, int& seedRead, std::vector<double>& energies,
                                       std::vector<Vec3>& buildPositions, Vec3 buildBox[3], bool& built) const {
    const std::streampos start = stream.tellg(); // where the integrator's data begins (-1: the stream cannot tell)
    std::int32_t first, version, seed, count;
    readOrFail(stream, first, "header");
    if (first == checkpointMagic)
        readOrFail(stream, version, "version");
    else if (first == 1)
        version = 1;
    else
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds no GenDPDEIntegrator data (it was written by "
                              "another integrator, or is corrupt)");
    if (version == 1 || version == 2)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds integrator data of version "
                              + std::to_string(version)
                              + (version == 1 ? " (openmm-gendpde 0.1)" : " (an early 0.2 development build)")
                              + ", which has no checksum: its internal energies cannot be told from corrupt ones, so "
                                "this build reads versions 3 to "
                              + std::to_string(checkpointVersion)
                              + " only. To go on from it, load it with the "
                                "openmm-gendpde that wrote it and save a State (Simulation.saveState()), which this "
                                "build reads");
    if (version < 1 || version > checkpointVersion)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds integrator data of version "
                              + std::to_string(version) + "; this build reads versions 3 to "
                              + std::to_string(checkpointVersion));
    readOrFail(stream, seed, "random seed");
    readOrFail(stream, count, "particle count");
    const int numParticles = context->getSystem().getNumParticles();
    if (count != numParticles)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint holds " + std::to_string(count)
                              + " internal energies, the System has " + std::to_string(numParticles) + " particles");
    energies.assign(count, 0.0);
    if (count > 0) {
        stream.read((char*) energies.data(), sizeof(double) * count);
        if (!stream)
            throw OpenMMException("GenDPDEIntegrator: the checkpoint ends before its internal energies (truncated)");
    }
    SweepBuild build;
    if (version >= 4) {
        readOrFail(stream, build.built, "sweep order's build");
        if (build.built != 0 && build.built != 1)
            throw OpenMMException("GenDPDEIntegrator: the checkpoint is corrupt (its sweep order's build flag is "
                                  + std::to_string(build.built) + ")");
        if (build.built) {
            readOrFail(stream, build.box, "sweep order's build");
            build.positions.resize(count);
            stream.read((char*) build.positions.data(), sizeof(Vec3) * count);
            if (!stream)
                throw OpenMMException("GenDPDEIntegrator: the checkpoint ends before its sweep order's build "
                                      "(truncated)");
        }
    }
    std::int32_t coverage;
    std::uint64_t checksum;
    readOrFail(stream, coverage, "checksum");
    readOrFail(stream, checksum, "checksum");
    if (coverage != coversIntegratorData && coverage != coversWholeCheckpoint)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint is corrupt (its checksum's coverage word is "
                              + std::to_string(coverage) + ")");
    std::string openmm;
    if (coverage == coversWholeCheckpoint) {
        // OpenMM's part, read back from the stream (a string or a file).
        std::string content;
        if (start != std::streampos(-1)) {
            const std::streampos after = stream.tellg();
            content.resize((size_t) start);
            stream.seekg(0);
            stream.read(&content[0], content.size());
            const bool read = (bool) stream;
            stream.clear();
            stream.seekg(after);
            if (!read)
                content.clear();
        }
        if (!openmmPart(content, content.size(), openmm))
            throw OpenMMException("GenDPDEIntegrator: the checkpoint's checksum covers OpenMM's part of it, which "
                                  "cannot be read back from this stream (a checkpoint is read from a string or a "
                                  "file holding it alone)");
    }
    if (checkpointChecksum(coverage == coversWholeCheckpoint ? &openmm : nullptr, version, seed, energies,
                           version >= 4 ? &build : nullptr, coverage)
        != checksum)
        throw OpenMMException(std::string("GenDPDEIntegrator: the checkpoint is corrupt: its checksum does not "
                                          "match its contents (")
                              + (coverage == coversWholeCheckpoint ? "OpenMM's part and "
                                                                     "the integrator's data"
                                                                   : "the integrator's data")
                              + "); it was changed or damaged "
                                "since it was written");
    std::int32_t end;
    readOrFail(stream, end, "end mark");
    if (end != checkpointMagic)
        throw OpenMMException("GenDPDEIntegrator: the checkpoint's integrator data has no end mark (corrupt)");
    if (stream.peek() != std::char_traits<char>::eof())
        throw OpenMMException("GenDPDEIntegrator: the checkpoint continues after its end (corrupt, or more than one "
                              "checkpoint in the stream)");
    checkInternalEnergies(energies, "the checkpoint");
    for (const Vec3& r : build.positions)
        if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2])))
            throw OpenMMException("GenDPDEIntegrator: the checkpoint is corrupt (a position of its sweep order's build "
                                  "is not finite)");
    seedRead = seed;
    built = build.built != 0;
    buildPositions.swap(build.positions);
    std::copy(build.box, build.box + 3, buildBox);
}

void GenDPDEIntegrator::loadCheckpoint(std::istream& stream) {
    int seed;
    std::vector<double> energies;
    std::vector<Vec3> buildPositions;
    Vec3 buildBox[3];
    bool built = false;
    try {
        // everything read and checked before anything changes
        readCheckpoint(stream, seed, energies, buildPositions, buildBox, built);
    } catch (const OpenMMException& error) {
        // OpenMM restored the checkpoint's positions, velocities and parameters before asking for this part, and
        // says nothing of it once this part is refused: for the particles' thermal state that is a move of the
        // particles (applyThermalRule); the integrator's own state is unchanged. The run stops there: those
        // positions belong to a checkpoint that was refused.
        stateChanged(State::Positions);
        throw OpenMMException(stopRun(std::string(error.what())
                                      + "; the Context now holds the refused checkpoint's positions, velocities, box "
                                        "and parameters (OpenMM restores its part of a checkpoint first)"));
    }
    IntegrateGenDPDEStepKernel& k = boundKernel();
    k.setSeed(seed);
    k.setInternalEnergies(energies);
    if (built)
        k.setSweepBuild(buildPositions, buildBox); // the order of the uninterrupted run
    else
        k.forgetSweepOrder();
    applyThermalRule(ThermalEvent::EnergiesSet);
    stoppedBy.clear(); // a whole saved state: the run goes on from it
}

// States (getState(getIntegratorParameters=True), Simulation.saveState): the internal energies and the sweep order's
// build (box vectors, then positions, if an order is built) as exact hex floats. Version 3 added the build (a State
// of version 2 or 1 makes the next step build the order at its own positions); version 2 dropped version 1's
// temperaturesSet flag (an unset state is all zeros), which is still accepted.
namespace {
void appendHexFloat(std::string& text, double value) {
    char buffer[40];
    std::snprintf(buffer, sizeof(buffer), "%a ", value);
    text += buffer;
}

/** The hex floats ("%a") of a State's property, separated by white space, read without streams (StrictXml). */
std::vector<double> hexFloats(const std::string& text, const std::string& what) {
    std::vector<double> values;
    for (size_t start = text.find_first_not_of(" \t\n\r"); start != std::string::npos;
         start = text.find_first_not_of(" \t\n\r", start)) {
        const size_t end = std::min(text.size(), text.find_first_of(" \t\n\r", start));
        const std::string token = text.substr(start, end - start);
        char* parsedEnd;
        const double value = std::strtod(token.c_str(), &parsedEnd);
        if (parsedEnd == token.c_str() || *parsedEnd != '\0')
            throw OpenMMException("GenDPDEIntegrator: the State's " + what + " are corrupt: '" + token + "' (entry "
                                  + std::to_string(values.size()) + ") is not a number");
        values.push_back(value);
        start = end;
    }
    return values;
}
} // namespace

void GenDPDEIntegrator::serializeParameters(SerializationNode& node) const {
    requireRunNotStopped("save its parameters in a State");
    const IntegrateGenDPDEStepKernel& k = boundKernel();
    std::string text;
    for (double e : k.getInternalEnergies())
        appendHexFloat(text, e);
    node.setIntProperty("GenDPDEIntegratorVersion", 3);
    node.setIntProperty("seedInUse", k.getSeed());
    node.setStringProperty("internalEnergies", text);
    std::vector<Vec3> positions;
    Vec3 box[3];
    std::string build;
    if (k.getSweepBuild(positions, box)) {
        for (int v = 0; v < 3; v++)
            for (int d = 0; d < 3; d++)
                appendHexFloat(build, box[v][d]);
        for (const Vec3& r : positions)
            for (int d = 0; d < 3; d++)
                appendHexFloat(build, r[d]);
    }
    node.setStringProperty("sweepBuild", build);
}

void GenDPDEIntegrator::deserializeParameters(const SerializationNode& node) {
    // Everything is read and checked before the integrator's state changes.
    if (!node.hasProperty("internalEnergies") || !node.hasProperty("GenDPDEIntegratorVersion")
        || !node.hasProperty("seedInUse"))
        throw OpenMMException("GenDPDEIntegrator: the State does not hold GenDPDEIntegrator parameters (it was saved "
                              "with another integrator, or without getIntegratorParameters=True)");
    const int version = StrictXml::integer(node, "GenDPDEIntegrator State", "GenDPDEIntegratorVersion");
    if (version < 1 || version > 3)
        throw OpenMMException("GenDPDEIntegrator: the State holds integrator parameters of version "
                              + std::to_string(version) + "; this build reads versions 1 to 3");
    const std::vector<double> energies = hexFloats(node.getStringProperty("internalEnergies"), "internal energies");
    const int seed = StrictXml::integer(node, "GenDPDEIntegrator State", "seedInUse");
    checkInternalEnergies(energies, "the State");
    std::vector<double> build;
    if (version >= 3) {
        if (!node.hasProperty("sweepBuild"))
            throw OpenMMException(
                    "GenDPDEIntegrator: the State's integrator parameters (version 3) have no sweepBuild");
        build = hexFloats(node.getStringProperty("sweepBuild"), "sweep order's build");
        const size_t expected = 9 + 3 * energies.size();
        if (!build.empty() && build.size() != expected)
            throw OpenMMException("GenDPDEIntegrator: the State's sweep order's build holds "
                                  + std::to_string(build.size()) + " numbers; " + std::to_string(expected)
                                  + " (a box and " + std::to_string(energies.size())
                                  + " positions) or none are allowed");
        for (double value : build)
            if (!std::isfinite(value))
                throw OpenMMException("GenDPDEIntegrator: the State's sweep order's build is corrupt (a number is not "
                                      "finite)");
    }
    IntegrateGenDPDEStepKernel& k = boundKernel();
    k.setSeed(seed);
    k.setInternalEnergies(energies);
    if (!build.empty()) {
        Vec3 box[3];
        std::vector<Vec3> positions(energies.size());
        for (int v = 0; v < 3; v++)
            box[v] = Vec3(build[3 * v], build[3 * v + 1], build[3 * v + 2]);
        for (size_t i = 0; i < positions.size(); i++)
            positions[i] = Vec3(build[9 + 3 * i], build[9 + 3 * i + 1], build[9 + 3 * i + 2]);
        k.setSweepBuild(positions, box); // the order of the uninterrupted run
    } else
        k.forgetSweepOrder(); // the next step builds it at the State's positions
    applyThermalRule(ThermalEvent::EnergiesSet);
    stoppedBy.clear(); // a whole saved state (Context.setState() sets the rest first): the run goes on from it
}
