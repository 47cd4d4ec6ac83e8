/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_INTEGRATOR_PROXY_H_
#define GENDPDE_INTEGRATOR_PROXY_H_

#include "openmm/serialization/SerializationProxy.h"

namespace GenDPDEPlugin {

/**
 * Serializes a GenDPDEIntegrator's parameters (XML element type "GenDPDEIntegrator"). The internal energies are
 * the state of a Context, not parameters: they travel with checkpoints and States.
 * Version 1: stepSize, constraintTolerance, integrationForceGroups, friction, heatConduction, heatCapacity, cutoff,
 * randomSeed, mode, temperature (0 if unset), and the particle temperatures set before a Context existed.
 */
class GenDPDEIntegratorProxy : public OpenMM::SerializationProxy {
public:
    GenDPDEIntegratorProxy();
    void serialize(const void* object, OpenMM::SerializationNode& node) const override;
    void* deserialize(const OpenMM::SerializationNode& node) const override;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_INTEGRATOR_PROXY_H_*/
