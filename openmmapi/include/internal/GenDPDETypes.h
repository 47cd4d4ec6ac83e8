#ifndef GENDPDE_TYPES_H_
#define GENDPDE_TYPES_H_

/* Particle types (docs/types.md): the one place where the types of a GenDPDEForce or GenDPDEIntegrator become the
 * dense per-type tables that every platform reads (Reference, CPU, and uploaded as they are by the GPU platforms).
 * Types are any integers; in a Context they are numbered 0..T-1 in ascending order of their values. */

#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** The particle types of one Force or Integrator in a Context: the distinct types and each particle's type index. */
class ParticleTypeIndex {
public:
    /**
     * @param particleTypes   particle -> type, as set with setParticleType (particles not listed have type 0)
     * @param numParticles    the number of particles in the System; a listed particle beyond it is refused
     * @param owner           the class name for messages ("GenDPDEForce", "GenDPDEIntegrator")
     */
    ParticleTypeIndex(const std::map<int, int>& particleTypes, int numParticles, const std::string& owner);
    /** The number T of distinct types the particles have. */
    int getNumTypes() const {
        return types.size();
    }
    /** The distinct types, ascending: type index t stands for getTypes()[t]. */
    const std::vector<int>& getTypes() const {
        return types;
    }
    /** Each particle's type index, in [0, T). */
    const std::vector<int>& getParticleTypeIndices() const {
        return particleTypeIndex;
    }
    /** The type index of type, or -1 if no particle has it. */
    int indexOf(int type) const;
    /** The type index of type named by entry (e.g. "type pair 2"); refused if no particle has that type. */
    int requireIndexOf(int type, const std::string& entry) const;
    bool operator==(const ParticleTypeIndex& other) const {
        return types == other.types && particleTypeIndex == other.particleTypeIndex;
    }
private:
    std::string owner;
    std::vector<int> types, particleTypeIndex;
};

/** setParticleType() of a GenDPDEForce or GenDPDEIntegrator (owner: its class name): a negative index is refused. */
void setParticleTypeIn(std::map<int, int>& particleTypes, const std::string& owner, int index, int type);

/** getParticleType(): the type of particle index, 0 if none was set. */
int particleTypeIn(const std::map<int, int>& particleTypes, int index);

/** The four parameters of a Tait equation of state (OpenMM units, as GenDPDEForce::setTaitParameters). */
struct TaitParameters {
    double referenceDensity, referencePressure, bulkModulus, exponent;
};

/** Per type index: the type's own Tait parameters (addTypeParameters), else the force's. */
std::vector<TaitParameters> taitParametersByType(const GenDPDEForce& force, const ParticleTypeIndex& types);

/** The integrator's per-type and per-type-pair parameters, by type index (OpenMM units). */
struct TypePairTable {
    int numTypes = 1;
    std::vector<double> heatCapacity;     // C_V of type t (kJ/(mol K)), T entries
    std::vector<double> friction;         // gamma of the pair (t, u) at t*T + u (amu/ps), T*T entries, symmetric
    std::vector<double> heatConduction;   // kappa of the pair (t, u) at t*T + u (kJ K/(mol ps)), symmetric
};

/** The tables of an integrator: addTypeHeatCapacity and addTypePair entries, the integrator's defaults elsewhere. */
TypePairTable typePairTable(const GenDPDEIntegrator& integrator, const ParticleTypeIndex& types);

/** C_V of every particle (kJ/(mol K)). */
std::vector<double> particleHeatCapacities(const TypePairTable& table, const ParticleTypeIndex& types);

} // namespace GenDPDEPlugin

#endif /*GENDPDE_TYPES_H_*/
