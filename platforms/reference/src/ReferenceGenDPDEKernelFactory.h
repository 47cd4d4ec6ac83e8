/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_REFERENCE_KERNEL_FACTORY_H_
#define GENDPDE_REFERENCE_KERNEL_FACTORY_H_

#include "openmm/KernelFactory.h"
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/** Creates the Reference kernels of GenDPDEForce and GenDPDEIntegrator. */
class ReferenceGenDPDEKernelFactory : public OpenMM::KernelFactory {
public:
    OpenMM::KernelImpl* createKernelImpl(std::string name, const OpenMM::Platform& platform,
                                         OpenMM::ContextImpl& context) const override;
    /** The names of the kernels this factory creates. */
    static std::vector<std::string> kernelNames();
    /**
     * Register a new factory for every kernel on the platform called platformName, if that platform is loaded
     * (the platform owns the factory). Used by the kernel library of each platform that runs these kernels.
     */
    static void registerOn(const std::string& platformName);
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_REFERENCE_KERNEL_FACTORY_H_*/
