#ifndef GENDPDE_PARTICLE_TYPES_XML_H_
#define GENDPDE_PARTICLE_TYPES_XML_H_

/* The particle types of a GenDPDEForce or GenDPDEIntegrator in XML (version 2 of both proxies, docs/types.md): a
 * ParticleTypes node with one Particle (index, type) per particle whose type was set. */

#include "openmm/serialization/SerializationNode.h"
#include <map>

namespace GenDPDEPlugin {

inline void serializeParticleTypes(OpenMM::SerializationNode& node, const std::map<int, int>& particleTypes) {
    OpenMM::SerializationNode& types = node.createChildNode("ParticleTypes");
    for (const auto& entry : particleTypes)
        types.createChildNode("Particle").setIntProperty("index", entry.first).setIntProperty("type", entry.second);
}

/** Set the types read from node's ParticleTypes on owner (its setParticleType validates them). */
template <class Owner>
void deserializeParticleTypes(const OpenMM::SerializationNode& node, Owner& owner) {
    for (const OpenMM::SerializationNode& particle : node.getChildNode("ParticleTypes").getChildren())
        owner.setParticleType(particle.getIntProperty("index"), particle.getIntProperty("type"));
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARTICLE_TYPES_XML_H_*/
