/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_CELL_GRID_H_
#define COMMON_GENDPDE_CELL_GRID_H_

#include "CommonGenDPDEProfiler.h"
#include "openmm/common/ComputeArray.h"
#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeKernel.h"
#include "openmm/common/ComputeProgram.h"
#include "openmm/common/ComputeVectorTypes.h"
#include <array>
#include <map>
#include <string>

namespace GenDPDEPlugin {

/**
 * The cell grid of GenDPDEForce's device kernels (kernels/gendpdeCells.cc), built on the device when the neighbour
 * list is (periodic; open boundaries: at every evaluation) and kept until then:
 * cells at least the candidate range wide (GenDPDESweepOrder::cellCounts: 1.1 R, so that the neighbour list's
 * search over the 27 cells around a particle finds every pair within 1.1 R; periodic: in the reduced box's fractional
 * coordinates, open: over the particles' bounding box), the particles listed cell by cell and by original index inside
 * a cell, with their positions copied into that order. (The integrator's sweep keeps cells of its own, of the
 * candidate range, made at its builds: CommonGenDPDEBlockSweep.)
 */
class CommonGenDPDECellGrid {
public:
    /** range: the pair range R (nm); the profiler counts the grid's launches and transfers with its owner's. */
    CommonGenDPDECellGrid(OpenMM::ComputeContext& cc, CommonGenDPDEProfiler& profiler, bool periodic, double range);
    /** The defines the grid's kernels need (add the program's own, then compile cells + the program's source). */
    std::map<std::string, std::string> defines() const { return programDefines(cc, periodic); }
    /** The defines of a program that includes kernels/gendpdeCells.cc, periodic or not. */
    static std::map<std::string, std::string> programDefines(OpenMM::ComputeContext& cc, bool periodic);
    /** Create the grid's kernels from a program compiled from kernels/gendpdeCells.cc (and more). */
    void createKernels(OpenMM::ComputeProgram program);
    /**
     * Rebuild at the current positions if rebuild[0] != 0 on the device when the kernels run (the list's mark; open
     * boundaries: always). forced: the host has asked for a list build (the cells may change only then).
     */
    void build(OpenMM::ArrayInterface& rebuild, bool forced);
    /** (n_x, n_y, n_z, n_x n_y n_z) of the last build, as a kernel argument. */
    OpenMM::mm_int4 getCellsArgument() const {
        return OpenMM::mm_int4(numCells[0], numCells[1], numCells[2], numCells[0] * numCells[1] * numCells[2]);
    }
    const std::array<int, 3>& getNumCells() const { return numCells; }
    /**
     * Set three consecutive kernel arguments to the box vectors a, b, c (mixed precision when asMixed, else real),
     * each with w = the inverse of its diagonal element (1/a_x, 1/b_y, 1/c_z).
     */
    void setBoxArguments(OpenMM::ComputeKernel& kernel, int index, bool asMixed) const;
    OpenMM::ComputeArray cellStart;    // int, n_cells + 1: the first sorted index of each cell
    OpenMM::ComputeArray sortedSlot;   // int: the slot (position in posq) of each particle in cell order
    OpenMM::ComputeArray sortedAtom;   // int: its original index
    OpenMM::ComputeArray sortedCell;   // int: its cell
    OpenMM::ComputeArray sortedPos;    // real4: its position (posq)
private:
    OpenMM::ComputeContext& cc;
    CommonGenDPDEProfiler& profiler;
    bool periodic;
    double range;
    std::array<int, 3> numCells;
    bool built = false;     // a build was launched
    bool cleared = false;   // cellCount and cellFill hold zeros (kept so by the kernels that use them)
    OpenMM::ComputeArray cellCount, cellFill, slotCell, bounds, scanTotal, always;
    OpenMM::ComputeKernel findBoundsKernel, assignKernel, scanKernel, fillKernel, sortKernel;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_CELL_GRID_H_*/
