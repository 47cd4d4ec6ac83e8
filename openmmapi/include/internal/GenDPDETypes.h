/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_TYPES_H_
#define GENDPDE_TYPES_H_

/* Particle types (docs/types.md): the one place where the types of a GenDPDEForce or GenDPDEIntegrator become the
 * dense per-type tables that every platform reads (Reference, CPU, and uploaded as they are by the GPU platforms).
 * Types are any integers; in a Context they are numbered 0..T-1 in ascending order of their values. */

#include "GenDPDEForce.h"
#include "GenDPDEIntegrator.h"
#include "internal/GenDPDEPhysics.h"
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
    int getNumTypes() const { return types.size(); }
    /** The distinct types, ascending: type index t stands for getTypes()[t]. */
    const std::vector<int>& getTypes() const { return types; }
    /** Each particle's type index, in [0, T). */
    const std::vector<int>& getParticleTypeIndices() const { return particleTypeIndex; }
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

/** The name of a law as the API spells it ("TaitThermalExpansion"), for messages; law must be a valid one. */
const char* equationOfStateName(GenDPDEForce::EquationOfState law);

/**
 * Per type index: the type's local equation of state (addTypeEquationOfState, else the force's
 * setEquationOfState) with its Tait parameters (taitParametersByType), in the physics core's order
 * (packEquationOfState).
 */
std::vector<Physics::LocalEquationOfState> equationsOfStateByType(const GenDPDEForce& force,
                                                                  const ParticleTypeIndex& types);

/**
 * A law and its parameters as the API takes them (already checked, GenDPDEForce::setEquationOfState) as the physics
 * core reads them: the core's parameters laid out as GenDPDEEquationsOfState.h says (a law that extends Tait: n0,
 * pi0 + p_b, B_T, gamma_T of tait, then its own; any other: its own, then p_b), padded with zeros to
 * EquationsOfState::coreStride(). backgroundPressure: p_b (kJ/mol/nm^3).
 */
Physics::LocalEquationOfState packEquationOfState(GenDPDEForce::EquationOfState law,
                                                  const std::vector<double>& parameters, const TaitParameters& tait,
                                                  double backgroundPressure);

/**
 * The integrator's per-type and per-type-pair parameters (OpenMM units), by class: each type named by an entry
 * (addTypeHeatCapacity, addTypePair) is a class of its own, and every other type shares class 0, which has the
 * integrator's own parameters. The tables therefore grow with the entries, not with the number of types: 4000
 * types without entries cost what one type costs (docs/types.md), and only types that have entries are paired.
 */
struct TypePairTable {
    int numClasses = 1;
    std::vector<int> classOfType;         // the class of type index t, T entries
    std::vector<double> heatCapacity;     // C_V of class c (kJ/(mol K)), numClasses entries
    std::vector<double> friction;         // gamma of the classes (c, d) at c*numClasses + d (amu/ps), symmetric
    std::vector<double> heatConduction; // kappa of the classes (c, d) at c*numClasses + d (kJ K/(mol ps)), symmetric
    /** The class of type index typeIndex. */
    int classOf(int typeIndex) const { return classOfType[typeIndex]; }
};

/**
 * The tables of an integrator: addTypeHeatCapacity and addTypePair entries, the integrator's defaults elsewhere.
 * An entry naming a type that no particle has is refused (ParticleTypeIndex::requireIndexOf).
 */
TypePairTable typePairTable(const GenDPDEIntegrator& integrator, const ParticleTypeIndex& types);

/** C_V of every particle (kJ/(mol K)). */
std::vector<double> particleHeatCapacities(const TypePairTable& table, const ParticleTypeIndex& types);

/**
 * The integrator's tables in one Context, as its kernels read them: the types of the Context (fixed), the tables
 * by class (re-read at each update(), since entries and parameters may change between steps) and the class of
 * every particle (rebuilt only when the entries change which types have a class of their own).
 */
class IntegratorTypeTables {
public:
    explicit IntegratorTypeTables(const ParticleTypeIndex& types) : types(types) {}
    /** Re-read the integrator's entries and parameters. Returns true if some particle's class changed. */
    bool update(const GenDPDEIntegrator& integrator);
    const ParticleTypeIndex& getTypes() const { return types; }
    /** The tables as of the last update(). */
    const TypePairTable& getTable() const { return table; }
    /** The class of every particle as of the last update() (empty before the first). */
    const std::vector<int>& getParticleClasses() const { return particleClass; }

private:
    ParticleTypeIndex types;
    TypePairTable table;
    std::vector<int> particleClass;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_TYPES_H_*/
