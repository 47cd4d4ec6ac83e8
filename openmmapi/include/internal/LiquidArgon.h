/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_LIQUID_ARGON_H_
#define GENDPDE_LIQUID_ARGON_H_

/* -------------------------------------------------------------------------- *
 * The liquid-argon model of Colella et al. (J. Chem. Theory Comput. 2025),   *
 * docs/theory.md section 9: the one home of its numbers. GenDPDEForce takes  *
 * its default Tait parameters from here, the C++ tests their argon scenes,   *
 * and the Python presets (openmmgendpde.presets) everything, through SWIG.   *
 * -------------------------------------------------------------------------- */

#include "openmm/OpenMMException.h"
#include <string>

namespace GenDPDEPlugin {

/** The parameters that depend on the cutoff (reduced units). */
struct LiquidArgonCutoff {
    double cutoff;           // R_cut*
    int neighbors;           // particles within range at n0* = 1
    double friction;         // gamma*
    double heatConduction;   // kappa*
    double cutoffScaling;    // f_cut of the V-B estimator (published)
    double cutoffScalingVC;  // f_cut of the V-C estimator where tuned (n-bar* = 1 at the state point,
                             // docs/interfaces.md), else 0: then V-B's, from which it differs little
};

/** One particle = 5 argon atoms. Reduced units: mass m, length L, energy u, k_B = 1. */
struct LiquidArgon {
    // The reduced units, in SI.
    static constexpr double particleMass = 3.3211e-25;   // m (kg)
    static constexpr double length = 0.61616;            // L (nm), so that n0* = 1
    static constexpr double energy = 1.5700e-19;         // u = L^3/kappa_T0 (J)
    // The state point and equation of state (reduced).
    static constexpr double temperature = 0.011054;      // T0* (printed 0.0111 in the paper)
    static constexpr double pressure = 0.12711;          // P0* (printed 0.127)
    static constexpr double density = 1.0;               // n0*
    static constexpr double taitExponent = 6.0;          // gamma_T
    static constexpr double compressibility = 1.0;       // kappa_T0* (u sets the energy unit so that it is 1)
    static constexpr double bulkModulus = 1.0 / (taitExponent * compressibility);   // B_T* = 1/(gamma_T kappa_T0*)
    static constexpr double heatCapacity = 12.51;        // C_V* per particle (units of k_B)
    // The three published cutoffs.
    static constexpr int numCutoffs = 3;
    static LiquidArgonCutoff getCutoff(int index) {
        constexpr LiquidArgonCutoff cutoffs[numCutoffs] = {
                {1.3365, 10, 23.42, 0.0079, 1.41, 0.0},
                {1.6839, 20, 7.37, 0.0025, 1.35, 1.3525},
                {2.1564, 42, 2.14, 0.0007, 1.33, 0.0},
        };
        if (index < 0 || index >= numCutoffs)
            throw OpenMM::OpenMMException("LiquidArgon: cutoff index = " + std::to_string(index)
                                          + " is not allowed; it must be 0, 1 or 2");
        return cutoffs[index];
    }
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_LIQUID_ARGON_H_*/
