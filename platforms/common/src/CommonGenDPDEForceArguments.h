/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_FORCE_ARGUMENTS_H_
#define COMMON_GENDPDE_FORCE_ARGUMENTS_H_

/* What the force kernel's setup (CommonGenDPDEForceSetup.cpp) and its steps (CommonGenDPDEForceKernel.cpp) share:
 * the order of the arguments of kernels/gendpdeForce.cc's kernels, and the neighbour list's skin. */

#include <climits>
#include <cmath>

namespace GenDPDEPlugin {
namespace ForceKernelArguments {

/** An error flag's value when nothing is flagged. */
const int noValue = INT_MAX;

/** The list's skin, as a fraction of the cutoff (the Reference platform's neighbour list uses the same). */
const double listSkin = 0.1;

/** value rounded up to a multiple of multiple. */
inline int roundUp(double value, int multiple) {
    return multiple * (int) std::ceil(value / multiple);
}

/** The arguments of kernels/gendpdeForce.cc's kernels, in the order of their parameters. */
namespace CheckArgument {
enum { Posq, BuildPosition, MaxDrift, ForceRebuild, Rebuild, Errors, Count };
}
namespace BuildArgument {
enum {
    Cells,
    CellStart,
    SortedCell,
    SortedSlot,
    SortedPos,
    AtomIndex,
    BoxA,
    BoxB,
    BoxC,
    Cutoff,
    ListRange,
    Capacity,
    Rebuild,
    BuildPosition,
    ListCount,
    Neighbours,
    Errors,
    Count
};
}
namespace SharedBuildArgument {
enum {
    Cells,
    CellStart,
    OrderAtom,
    AtomCell,
    SlotOfAtom,
    OrderPosition,
    BoxA,
    BoxB,
    BoxC,
    Cutoff,
    ListRange,
    Capacity,
    Rebuild,
    SortedSlot,
    SortedAtom,
    SortedCell,
    BuildPosition,
    ListCount,
    Neighbours,
    Errors,
    Count
};
}
/** The leading arguments of every pass (NEIGHBOUR_ARGUMENTS). */
namespace NeighbourArgument {
enum {
    ListCount,
    Neighbours,
    Capacity,
    Cells,
    CellStart,
    SortedCell,
    SortedAtom,
    SortedSlot,
    SortedPos,
    Posq,
    BoxA,
    BoxB,
    BoxC,
    Count
};
}
namespace DensityArgument {
enum {
    AtomIndex = NeighbourArgument::Count,
    Model,
    AtomType,
    LawParameters,
    TaitPower,
    VolumeConstants,
    MomentConstants,
    Estimator,
    Polynomials,
    Quadrature,
    PrimitiveDensity,
    Volume,
    Pressure,
    ForceCoefficient,
    MomentForce,
    Energy,
    Rebuild,
    Errors,
    Thermal,
    Isothermal,
    Temperature,
    EntropyKnown,
    CheckStep,
    LawTable,
    StoredEnergy,
    StoredEntropy,
    ParticleClass,
    ClassHeatCapacity,
    ThermalEnergyOut,
    DensityEntropyOut,
    Count
};
}
namespace ForceArgument {
enum { Model = NeighbourArgument::Count, ForceCoefficient, Moments, MomentForce, ForceBuffers, Count };
}
namespace VirialArgument {
enum {
    Model = NeighbourArgument::Count,
    ForceCoefficient,
    Moments,
    MomentForce,
    Tensors,
    ParticleVirial,
    ParticleVirialTensor,
    Count
};
}

} // namespace ForceKernelArguments
} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_FORCE_ARGUMENTS_H_*/
