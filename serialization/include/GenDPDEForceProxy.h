/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_FORCE_PROXY_H_
#define GENDPDE_FORCE_PROXY_H_

#include "openmm/serialization/SerializationProxy.h"

namespace GenDPDEPlugin {

/**
 * Serializes a GenDPDEForce (XML element type "GenDPDEForce").
 * Version 1: cutoff, method, estimator, cutoffScaling, n0, pi0, bulkModulus, gammaT, forceGroup, name.
 */
class GenDPDEForceProxy : public OpenMM::SerializationProxy {
public:
    GenDPDEForceProxy();
    void serialize(const void* object, OpenMM::SerializationNode& node) const override;
    void* deserialize(const OpenMM::SerializationNode& node) const override;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_FORCE_PROXY_H_*/
