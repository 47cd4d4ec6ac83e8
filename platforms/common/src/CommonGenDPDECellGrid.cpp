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
}

CommonGenDPDECellGrid::CommonGenDPDECellGrid(ComputeContext& cc, bool periodic, double range) :
        cc(cc), periodic(periodic), range(range), numCells({1, 1, 1}) {
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
}

std::map<std::string, std::string> CommonGenDPDECellGrid::defines() const {
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
    assignKernel->addArg(cc.getPosq());
    assignKernel->addArg(cc.getPosqCorrection());
    for (int i = 0; i < 6; i++)
        assignKernel->addArg();   // box vectors, low corner, extent, cells: set by build()
    assignKernel->addArg(slotCell);
    assignKernel->addArg(cellCount);
    scanKernel = program->createKernel("exclusiveScan");
    for (int i = 0; i < 5; i++)
        scanKernel->addArg();
    fillKernel = program->createKernel("fillCells");
    fillKernel->addArg(slotCell);
    fillKernel->addArg(cellStart);
    fillKernel->addArg(cellFill);
    fillKernel->addArg(sortedSlot);
    sortKernel = program->createKernel("sortCells");
    sortKernel->addArg();   // cells
    sortKernel->addArg(cellStart);
    sortKernel->addArg(sortedSlot);
    sortKernel->addArg(cc.getAtomIndexArray());
    sortKernel->addArg(sortedAtom);
    sortKernel->addArg(sortedCell);
    sortKernel->addArg(cc.getPosq());
    sortKernel->addArg(sortedPos);
}

void CommonGenDPDECellGrid::setBoxArguments(ComputeKernel& kernel, int index, bool asMixed) const {
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    const bool asDouble = asMixed ? mixedIsDouble(cc) : cc.getUseDoublePrecision();
    for (int k = 0; k < 3; k++)
        setVector4(kernel, index + k, asDouble, box[k][0], box[k][1], box[k][2], 0.0);
}

void CommonGenDPDECellGrid::exclusiveScan(ArrayInterface& counts, ArrayInterface& starts, int n,
                                          ArrayInterface& totalOut, int totalIndex) {
    scanKernel->setArg(0, counts);
    scanKernel->setArg(1, starts);
    scanKernel->setArg(2, n);
    scanKernel->setArg(3, totalOut);
    scanKernel->setArg(4, totalIndex);
    scanKernel->execute(scanGroupSize, scanGroupSize);
}

void CommonGenDPDECellGrid::build() {
    // The region the cells divide, as GenDPDESweepOrder::computeCells chooses it (the same cells, so the same order).
    Vec3 low, extent;
    if (periodic) {
        Vec3 box[3];
        cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
        extent = BoxGeometry::perpendicularWidths(box);
    }
    else {
        findBoundsKernel->execute(boundsGroupSize, boundsGroupSize);
        std::vector<double> corners;
        bounds.download(corners, true);
        low = Vec3(corners[0], corners[1], corners[2]);
        extent = Vec3(corners[3], corners[4], corners[5]) - low;
    }
    numCells = GenDPDESweepOrder::cellCounts(extent, range, periodic);
    const long long total = (long long) numCells[0]*numCells[1]*numCells[2];
    if (total > 100000000)
        throw OpenMMException("GenDPDE: the particles span " + std::to_string(total) + " cells of the pair range; "
                              "more than 1e8 cells are not supported on this platform (is the system blowing apart?)");
    if ((long long) cellCount.getSize() < total) {
        cellCount.resize(total);
        cellFill.resize(total);
        cellStart.resize(total + 1);
    }
    cc.clearBuffer(cellCount);
    cc.clearBuffer(cellFill);
    const mm_int4 cells = getCellsArgument();
    setBoxArguments(assignKernel, 2, true);
    setMixed4(cc, assignKernel, 5, low[0], low[1], low[2], 0.0);
    setMixed4(cc, assignKernel, 6, extent[0], extent[1], extent[2], 0.0);
    assignKernel->setArg(7, cells);
    const int numAtoms = cc.getNumAtoms();
    assignKernel->execute(numAtoms);
    exclusiveScan(cellCount, cellStart, (int) total, scanTotal, 0);
    fillKernel->execute(numAtoms);
    sortKernel->setArg(0, cells);
    sortKernel->execute((int) total);
}
