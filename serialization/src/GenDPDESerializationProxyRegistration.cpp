/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "GenDPDEForce.h"
#include "GenDPDEForceProxy.h"
#include "GenDPDEIntegrator.h"
#include "GenDPDEIntegratorProxy.h"
#include "openmm/serialization/SerializationProxy.h"

using namespace GenDPDEPlugin;
using namespace OpenMM;

// Runs when the library is loaded, so that XmlSerializer knows the plugin's types before anything is read.
extern "C" __attribute__((constructor)) void registerGenDPDESerializationProxies() {
    SerializationProxy::registerProxy(typeid(GenDPDEForce), new GenDPDEForceProxy());
    SerializationProxy::registerProxy(typeid(GenDPDEIntegrator), new GenDPDEIntegratorProxy());
}
