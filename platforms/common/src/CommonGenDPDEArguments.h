/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_ARGUMENTS_H_
#define COMMON_GENDPDE_ARGUMENTS_H_

/* Kernel arguments and small uploads in a context's precisions: `real` is double in double precision only, `mixed`
 * in mixed and double precision. Values come as doubles and are narrowed where the device type is float. */

#include "openmm/common/ArrayInterface.h"
#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeKernel.h"
#include "openmm/common/ComputeVectorTypes.h"
#include "openmm/OpenMMException.h"
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Adds a kernel's arguments in order, each with its named index (an enum beside the kernel's addArg list, in the
 * order of the kernel's parameters), so that every later setArg() names the argument instead of counting it:
 *     KernelArguments(kernel, "computeForces").array(ForceArgument::CellStart, cellStart).later(ForceArgument::Box)
 * Throws if an index is out of order (an enum that no longer matches the list).
 */
class KernelArguments {
public:
    KernelArguments(OpenMM::ComputeKernel& kernel, const std::string& name) : kernel(kernel), name(name) {}
    /** An array argument. */
    KernelArguments& array(int index, OpenMM::ArrayInterface& value) {
        next(index);
        kernel->addArg(value);
        return *this;
    }
    /** A value set before each launch with setArg(index, ...). */
    KernelArguments& later(int index) {
        next(index);
        kernel->addArg();
        return *this;
    }
    /** A value fixed now. */
    template <class T>
    KernelArguments& value(int index, const T& value) {
        next(index);
        kernel->addArg(value);
        return *this;
    }
    /** Check that every argument up to count (the enum's last entry) was added. */
    void done(int count) const {
        if (added != count)
            throw OpenMM::OpenMMException("GenDPDE: kernel " + name + " got " + std::to_string(added)
                                          + " arguments, its enum lists " + std::to_string(count));
    }

private:
    void next(int index) {
        if (index != added)
            throw OpenMM::OpenMMException("GenDPDE: argument " + std::to_string(index) + " of kernel " + name
                                          + " added in place " + std::to_string(added));
        added++;
    }
    OpenMM::ComputeKernel& kernel;
    std::string name;
    int added = 0;
};

inline bool mixedIsDouble(OpenMM::ComputeContext& cc) {
    return cc.getUseDoublePrecision() || cc.getUseMixedPrecision();
}

inline void setVector4(OpenMM::ComputeKernel& kernel, int index, bool asDouble, double x, double y, double z,
                       double w) {
    if (asDouble)
        kernel->setArg(index, OpenMM::mm_double4(x, y, z, w));
    else
        kernel->setArg(index, OpenMM::mm_float4((float) x, (float) y, (float) z, (float) w));
}

inline void setReal4(OpenMM::ComputeContext& cc, OpenMM::ComputeKernel& kernel, int index, double x, double y, double z,
                     double w) {
    setVector4(kernel, index, cc.getUseDoublePrecision(), x, y, z, w);
}

inline void setMixed4(OpenMM::ComputeContext& cc, OpenMM::ComputeKernel& kernel, int index, double x, double y,
                      double z, double w) {
    setVector4(kernel, index, mixedIsDouble(cc), x, y, z, w);
}

inline void setReal(OpenMM::ComputeContext& cc, OpenMM::ComputeKernel& kernel, int index, double value) {
    if (cc.getUseDoublePrecision())
        kernel->setArg(index, value);
    else
        kernel->setArg(index, (float) value);
}

inline void setMixed(OpenMM::ComputeContext& cc, OpenMM::ComputeKernel& kernel, int index, double value) {
    if (mixedIsDouble(cc))
        kernel->setArg(index, value);
    else
        kernel->setArg(index, (float) value);
}

/** Upload ``values`` into ``array`` (elements of any width: real, real2, real4 ...), as doubles or as floats. */
inline void uploadValues(OpenMM::ArrayInterface& array, const std::vector<double>& values, bool asDouble) {
    if (asDouble)
        array.upload(values.data());
    else {
        const std::vector<float> single(values.begin(), values.end());
        array.upload(single.data());
    }
}

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_ARGUMENTS_H_*/
