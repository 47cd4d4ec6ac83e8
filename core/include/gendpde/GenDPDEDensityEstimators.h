/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_DENSITY_ESTIMATORS_H_
#define GENDPDE_DENSITY_ESTIMATORS_H_

/* The one description of the density (volume) estimators (docs/theory.md section 3): for each its API name, its
 * physics-core id and what the engines and tools need to know about it. GenDPDEForce's checks and messages, the XML
 * serialization, the LAMMPS pair style's names (lower case), and the Python package (through SWIG: the choices of
 * every command, the model files, the time-step suggestion) all read this table.
 *
 * A new estimator is: its volume in the physics core (a GENDPDE_ESTIMATOR_* id and a branch of gendpdeParticleVolume,
 * GenDPDEPhysicsCore.h; gendpdeEstimatorNeedsMoments if it reads the moments), an entry here, its enum value in
 * GenDPDEForce.h (python/tests/test_tables.py checks through the bindings that every entry's name is the enum value
 * of its place), and its oracle in the tests (tests/BruteForceGenDPDE.h). Engine-neutral (core/): no OpenMM header. */

#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include <cctype>
#include <string>

namespace GenDPDEPlugin {
namespace DensityEstimators {

/** An estimator. */
struct Estimator {
    const char* name;          // as the API spells it, GenDPDEForce::DensityEstimator ("VB"); LAMMPS: lower case
    const char* description;   // for messages and help ("partition of unity")
    int coreId;                // its GENDPDE_ESTIMATOR_* number in the physics core
    bool readsCutoffScaling;   // whether f_cut (GenDPDEForce::setCutoffScaling) changes it: Rt = R/f_cut
    bool needsMoments; // whether it reads the first moments of the neighbourhoods (gendpdeEstimatorNeedsMoments)
    /**
     * What a suggested time step is multiplied by, for the same conserved-energy drift as V-B's where the estimator
     * matters most (1 where it behaves as V-B). V-C: 0.1. Its surface factor makes a free-surface particle's energy
     * much stiffer; the drift is second order in dt and ~100 times V-B's at the same step (liquid argon slab and
     * droplet, docs/interfaces.md "V-C's energy error"), so a step sqrt(100) = 10 times smaller.
     */
    double stableStepFactor;
};

/** Every estimator, at its GenDPDEForce::DensityEstimator number. */
constexpr Estimator estimators[] = {
        {"VA", "traditional, V = 1/n0", GENDPDE_ESTIMATOR_VA, false, false, 1.0},
        {"VB", "partition of unity", GENDPDE_ESTIMATOR_VB, true, false, 1.0},
        {"VC", "partition of unity with a surface correction", GENDPDE_ESTIMATOR_VC, true, true, 0.1},
};

/** The number of estimators. */
constexpr int numEstimators = sizeof(estimators) / sizeof(estimators[0]);

constexpr bool numberedInOrder() {
    for (int k = 0; k < numEstimators; k++)
        if (estimators[k].coreId != k)
            return false;
    return true;
}
static_assert(numberedInOrder(), "each estimator's core id must be its place in the table");

/** The estimator numbered estimator (a GenDPDEForce::DensityEstimator value), or nullptr if there is none. */
inline const Estimator* find(int estimator) {
    return (estimator >= 0 && estimator < numEstimators) ? &estimators[estimator] : nullptr;
}

/** The estimator of this name, compared without case ("vb" is V-B, as LAMMPS spells it), or nullptr. */
inline const Estimator* findByName(const std::string& name) {
    for (const Estimator& estimator : estimators) {
        const std::string candidate = estimator.name;
        bool same = candidate.size() == name.size();
        for (size_t k = 0; same && k < name.size(); k++)
            same = std::tolower((unsigned char) candidate[k]) == std::tolower((unsigned char) name[k]);
        if (same)
            return &estimator;
    }
    return nullptr;
}

/** The estimators for messages, "VA (0), VB (1) or VC (2)", or with lowerCase and without numbers "va, vb or vc". */
inline std::string listOfEstimators(bool lowerCase = false) {
    std::string list;
    for (int k = 0; k < numEstimators; k++) {
        std::string name = estimators[k].name;
        if (lowerCase)
            for (char& c : name)
                c = (char) std::tolower((unsigned char) c);
        list += std::string(k == 0 ? "" : (k + 1 == numEstimators ? " or " : ", ")) + name;
        if (!lowerCase)
            list += " (" + std::to_string(k) + ")";
    }
    return list;
}

} // namespace DensityEstimators
} // namespace GenDPDEPlugin

#endif /*GENDPDE_DENSITY_ESTIMATORS_H_*/
