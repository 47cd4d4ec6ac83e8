/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_THERMAL_ARRAYS_H_
#define COMMON_GENDPDE_THERMAL_ARRAYS_H_

#include "openmm/common/ComputeArray.h"

namespace GenDPDEPlugin {

/**
 * The particles' thermal state on the device, as the GPU platforms' integrator kernel holds it, read by the force
 * kernel when a law depends on temperature (docs/theory.md section 11; GenDPDEThermalState on the host). Every array
 * is by original particle index.
 */
struct CommonGenDPDEThermalArrays {
    bool isothermal;                           // Isothermal mode: every particle at temperature
    double temperature;                        // the bath temperature T (K)
    OpenMM::ComputeArray* internalEnergies;    // eps_i (kJ/mol, mixed)
    OpenMM::ComputeArray* densityEntropies;    // sigma_i (kJ/(mol K), mixed), valid if entropiesKnown
    bool entropiesKnown;
    OpenMM::ComputeArray* particleClass;       // int
    OpenMM::ComputeArray* classHeatCapacity;   // C_V by class (kJ/(mol K), mixed)
    bool checkStep;                            // an evaluation of a step (GenDPDEThermalState::checkStep)
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_THERMAL_ARRAYS_H_*/
