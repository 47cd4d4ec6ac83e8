/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "CommonGenDPDECellGrid.h"
#include "CommonGenDPDEArguments.h"
#include "internal/BoxGeometry.h"
#include "internal/GenDPDESweepOrder.h"
#include "openmm/OpenMMException.h"
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

const int scanGroupSize = 256;
const int boundsGroupSize = 128;

/** The arguments of kernels/gendpdeCells.cc's kernels, in the order of their parameters. */
namespace AssignArgument {
enum { Gate, Posq, PosqCorrection, BoxA, BoxB, BoxC, Low, Extent, Cells, SlotCell, CellCount, Count };
}
namespace ScanArgument {
enum { Gate, Counts, Starts, Size, TotalOut, TotalIndex, Count };
}
namespace SortArgument {
enum { Gate, Cells, CellStart, CellFill, SortedSlot, AtomIndex, SortedAtom, SortedCell, Posq, SortedPos, Count };
}

} // namespace

CommonGenDPDECellGrid::CommonGenDPDECellGrid(ComputeContext& cc, CommonGenDPDEProfiler& profiler, bool periodic,
                                             double range) :
        cc(cc), profiler(profiler), periodic(periodic), range(range), numCells({1, 1, 1}) {
    const int numAtoms = cc.getNumAtoms();
    cellCount.initialize<int>(cc, 1, "gendpdeCellCount");
    cellFill.initialize<int>(cc, 1, "gendpdeCellFill");
    cellStart.initialize<int>(cc, 2, "gendpdeCellStart");
    slotCell.initialize<int>(cc, numAtoms, "gendpdeSlotCell");
    sortedSlot.initialize<int>(cc, numAtoms, "gendpdeSortedSlot");
    sortedAtom.initialize<int>(cc, numAtoms, "gendpdeSortedAtom");
    sortedCell.initialize<int>(cc, numAtoms, "gendpdeSortedCell");
    sortedPos.initialize(cc, numAtoms, cc.getPosq().getElementSize(), "gendpdeSortedPos");
    bounds.initialize(cc, 6, mixedIsDouble(cc) ? sizeof(double) : sizeof(float), "gendpdeBounds");
    scanTotal.initialize<int>(cc, 1, "gendpdeScanTotal");
    always.initialize<int>(cc, 1, "gendpdeGridAlways");
    always.upload(std::vector<int>(1, 1));
}

std::map<std::string, std::string> CommonGenDPDECellGrid::programDefines(ComputeContext& cc, bool periodic) {
    std::map<std::string, std::string> result;
    result["NUM_ATOMS"] = cc.intToString(cc.getNumAtoms());
    result["PADDED_NUM_ATOMS"] = cc.intToString(cc.getPaddedNumAtoms());
    result["SCAN_GROUP_SIZE"] = cc.intToString(scanGroupSize);
    result["BOUNDS_GROUP_SIZE"] = cc.intToString(boundsGroupSize);
    if (periodic)
        result["USE_PERIODIC"] = "1";
    return result;
}

void CommonGenDPDECellGrid::createKernels(ComputeProgram program) {
    findBoundsKernel = program->createKernel("findBounds");
    findBoundsKernel->addArg(cc.getPosq());
    findBoundsKernel->addArg(cc.getPosqCorrection());
    findBoundsKernel->addArg(bounds);
    assignKernel = program->createKernel("assignCells");
    {
        using namespace AssignArgument;
        KernelArguments(assignKernel, "assignCells")
                .later(Gate)
                .array(Posq, cc.getPosq())
                .array(PosqCorrection, cc.getPosqCorrection())
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(Low)
                .later(Extent)
                .later(Cells)
                .array(SlotCell, slotCell)
                .array(CellCount, cellCount)
                .done(Count);
    }
    scanKernel = program->createKernel("exclusiveScan");
    {
        using namespace ScanArgument;
        KernelArguments(scanKernel, "exclusiveScan")
                .later(Gate)
                .later(Counts)
                .later(Starts)
                .later(Size)
                .later(TotalOut)
                .later(TotalIndex)
                .done(Count);
    }
    fillKernel = program->createKernel("fillCells");
    fillKernel->addArg(); // the gate
    fillKernel->addArg(slotCell);
    fillKernel->addArg(cellStart);
    fillKernel->addArg(cellFill);
    fillKernel->addArg(sortedSlot);
    sortKernel = program->createKernel("sortCells");
    {
        using namespace SortArgument;
        KernelArguments(sortKernel, "sortCells")
                .later(Gate)
                .later(Cells)
                .array(CellStart, cellStart)
                .array(CellFill, cellFill)
                .array(SortedSlot, sortedSlot)
                .array(AtomIndex, cc.getAtomIndexArray())
                .array(SortedAtom, sortedAtom)
                .array(SortedCell, sortedCell)
                .array(Posq, cc.getPosq())
                .array(SortedPos, sortedPos)
                .done(Count);
    }
}

void CommonGenDPDECellGrid::setBoxArguments(ComputeKernel& kernel, int index, bool asMixed) const {
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    const bool asDouble = asMixed ? mixedIsDouble(cc) : cc.getUseDoublePrecision();
    for (int k = 0; k < 3; k++)   // w: the inverse of the diagonal element, for the nearest image
        setVector4(kernel, index + k, asDouble, box[k][0], box[k][1], box[k][2], 1.0 / box[k][k]);
}

void CommonGenDPDECellGrid::build(ArrayInterface& rebuild, bool forced) {
    // Periodic: the cells depend on the box alone, and a new box forces a list build; the grid is built on the device
    // when the list is (rebuild[0]). Open boundaries: the cells follow the particles' bounding box, read by the host
    // at every evaluation, so the grid is built at every evaluation.
    ArrayInterface& gate = periodic ? rebuild : always;
    // The region the cells divide, as GenDPDESweepOrder::computeCells chooses it (the same cells, so the same order).
    Vec3 low, extent;
    if (periodic) {
        Vec3 box[3];
        cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
        extent = BoxGeometry::perpendicularWidths(box);
    } else {
        profiler.launch(findBoundsKernel, boundsGroupSize, boundsGroupSize);
        std::vector<double> corners;
        profiler.transfer(); // the cells depend on the bounds: the one wait of open boundaries
        bounds.download(corners, true);
        low = Vec3(corners[0], corners[1], corners[2]);
        extent = Vec3(corners[3], corners[4], corners[5]) - low;
    }
    const std::array<int, 3> previous = numCells;
    numCells = GenDPDESweepOrder::cellCounts(extent, range, periodic);
    if (periodic && built && numCells != previous && !forced)
        throw OpenMMException("GenDPDE: internal error: the cell grid changed without a rebuild of the list");
    built = true;
    const long long total = (long long) numCells[0] * numCells[1] * numCells[2];
    if (total > 100000000)
        throw OpenMMException(
                "GenDPDE: the particles span " + std::to_string(total)
                + " cells of the pair range; "
                  "more than 1e8 cells are not supported on this platform (is the system blowing apart?)");
    if ((long long) cellCount.getSize() < total || !cleared) {
        // The counters start at zero; afterwards the scan and the sort leave them zero (no clearing launches).
        if ((long long) cellCount.getSize() < total) {
            cellCount.resize(total);
            cellFill.resize(total);
            cellStart.resize(total + 1);
        }
        cc.clearBuffer(cellCount);
        cc.clearBuffer(cellFill);
        profiler.launched();
        profiler.launched();
        cleared = true;
    }
    const mm_int4 cells = getCellsArgument();
    assignKernel->setArg(AssignArgument::Gate, gate);
    setBoxArguments(assignKernel, AssignArgument::BoxA, true);
    setMixed4(cc, assignKernel, AssignArgument::Low, low[0], low[1], low[2], 0.0);
    setMixed4(cc, assignKernel, AssignArgument::Extent, extent[0], extent[1], extent[2], 0.0);
    assignKernel->setArg(AssignArgument::Cells, cells);
    const int numAtoms = cc.getNumAtoms();
    profiler.launch(assignKernel, numAtoms);
    scanKernel->setArg(ScanArgument::Gate, gate);
    scanKernel->setArg(ScanArgument::Counts, cellCount);
    scanKernel->setArg(ScanArgument::Starts, cellStart);
    scanKernel->setArg(ScanArgument::Size, (int) total);
    scanKernel->setArg(ScanArgument::TotalOut, scanTotal);
    scanKernel->setArg(ScanArgument::TotalIndex, 0);
    profiler.launch(scanKernel, scanGroupSize, scanGroupSize);
    fillKernel->setArg(0, gate);
    profiler.launch(fillKernel, numAtoms);
    sortKernel->setArg(SortArgument::Gate, gate);
    sortKernel->setArg(SortArgument::Cells, cells);
    profiler.launch(sortKernel, (int) total);
}
