/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PARTICLE_TYPES_XML_H_
#define GENDPDE_PARTICLE_TYPES_XML_H_

/* The particle types of a GenDPDEForce or GenDPDEIntegrator in XML (version 2 of both proxies, docs/types.md): a
 * ParticleTypes node with one Particle (index, type) per particle whose type was set. */

#include "internal/StrictXml.h"
#include "openmm/serialization/SerializationNode.h"
#include <map>
#include <string>

namespace GenDPDEPlugin {

inline void serializeParticleTypes(OpenMM::SerializationNode& node, const std::map<int, int>& particleTypes) {
    OpenMM::SerializationNode& types = node.createChildNode("ParticleTypes");
    for (const auto& entry : particleTypes)
        types.createChildNode("Particle").setIntProperty("index", entry.first).setIntProperty("type", entry.second);
}

/**
 * Set the types read from node's ParticleTypes on owner (its setParticleType validates them); ownerName and version
 * for StrictXml's messages.
 */
template <class Owner>
void deserializeParticleTypes(const OpenMM::SerializationNode& node, Owner& owner, const std::string& ownerName,
                              int version) {
    const OpenMM::SerializationNode& types = StrictXml::child(node, ownerName, "ParticleTypes");
    StrictXml::requireOnly(types, ownerName, version, {}, {"Particle"});
    for (const OpenMM::SerializationNode& particle : types.getChildren()) {
        StrictXml::requireOnly(particle, ownerName, version, {"index", "type"}, {});
        owner.setParticleType(StrictXml::integer(particle, ownerName, "index"),
                              StrictXml::integer(particle, ownerName, "type"));
    }
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARTICLE_TYPES_XML_H_*/
