/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce on the GPU platforms: the kernel's setup (initialize) - its arrays, the V-B tables and the law table
 * uploaded, the device program compiled and each kernel's arguments bound - and the parameters read from the force.
 * The steps are in CommonGenDPDEForceKernel.cpp. */

#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEForceArguments.h"
#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEKernelSources.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/common/ComputeForceInfo.h"
#include "openmm/common/ContextSelector.h"
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>

using namespace GenDPDEPlugin;
using namespace GenDPDEPlugin::ForceKernelArguments;
using namespace OpenMM;

/** Particles of the same type interact alike: OpenMM may exchange them when it reorders the atoms. */
class CommonCalcGenDPDEForceKernel::ForceInfo : public ComputeForceInfo {
public:
    explicit ForceInfo(const std::vector<int>& typeIndex) : typeIndex(typeIndex) {}
    bool areParticlesIdentical(int particle1, int particle2) override {
        return typeIndex[particle1] == typeIndex[particle2];
    }

private:
    std::vector<int> typeIndex;
};

/** Marks the neighbour list for a rebuild when OpenMM reorders the atoms (the list holds slots). */
class CommonCalcGenDPDEForceKernel::ReorderListener : public ComputeContext::ReorderListener {
public:
    explicit ReorderListener(std::shared_ptr<bool> needsRebuild) : needsRebuild(needsRebuild) {}
    void execute() override { *needsRebuild = true; }

private:
    std::shared_ptr<bool> needsRebuild;
};

void CommonCalcGenDPDEForceKernel::initialize(const System& system, const GenDPDEForce& force) {
    ContextSelector selector(cc);
    cutoff = force.getCutoffDistance();
    periodic = force.usesPeriodicBoundaryConditions();
    types.reset(new ParticleTypeIndex(force.getParticleTypes(), system.getNumParticles(), "GenDPDEForce"));
    readParameters(force);
    allocateArrays(system);
    uploadVolumeTables();
    uploadTypeTables();
    grid.reset(new CommonGenDPDECellGrid(cc, profiler, periodic, cutoff));
    std::map<std::string, std::string> defines = grid->defines();
    defines["LAW_PARAMETER_STRIDE"] = std::to_string(EquationsOfState::coreStride());
    ComputeProgram program =
            cc.compileProgram(CommonGenDPDEKernelSources::physicsCore("real") + CommonGenDPDEKernelSources::gendpdeCells
                                      + CommonGenDPDEKernelSources::gendpdeForce,
                              defines);
    grid->createKernels(program);
    createListKernels(program);
    createSharedListKernel(program);
    createDensityKernel(program);
    createForceKernels(program);
    // Atom reordering moves particles between slots, which the list holds: it is rebuilt after.
    cc.addReorderListener(new ReorderListener(needsRebuild));
    cc.addForce(new ForceInfo(types->getParticleTypeIndices()));
}

void CommonCalcGenDPDEForceKernel::allocateArrays(const System& system) {
    const int numAtoms = cc.getNumAtoms();
    const bool useDouble = cc.getUseDoublePrecision();
    const int realSize = useDouble ? sizeof(double) : sizeof(float);
    primitiveDensity.initialize(cc, numAtoms, realSize, "gendpdePrimitiveDensity");
    volume.initialize(cc, numAtoms, realSize, "gendpdeVolume");
    pressure.initialize(cc, numAtoms, realSize, "gendpdePressure");
    forceCoefficient.initialize(cc, numAtoms, realSize, "gendpdeForceCoefficient");
    particleVirial.initialize(cc, numAtoms, realSize, "gendpdeParticleVirial");
    particleVirialTensor.initialize(cc, 9 * numAtoms, realSize, "gendpdeParticleVirialTensor");
    momentForce.initialize(cc, numAtoms, 4 * realSize, "gendpdeMomentForce");   // (used only by V-C)
    errors.initialize<int>(cc, 6, "gendpdeForceErrors");   // two flags, then the list's counters
    errors.upload(std::vector<int>({noValue, noValue, 0, 0, 0, 0}));
    // The neighbour list (rows by slot), marked for a rebuild at the first evaluation.
    listCount.initialize<int>(cc, numAtoms, "gendpdeListCount");
    buildPosition.initialize(cc, numAtoms, cc.getPosq().getElementSize(), "gendpdeListBuildPosition");
    rebuild.initialize<int>(cc, 1, "gendpdeListRebuild");
    rebuild.upload(std::vector<int>(1, 1));
    if (periodic) {
        Vec3 box[3];
        system.getDefaultPeriodicBoxVectors(box[0], box[1], box[2]);
        const double density = system.getNumParticles() / (box[0][0] * box[1][1] * box[2][2]);
        const double range = (1 + listSkin) * cutoff;
        listCapacity = roundUp(1.4 * (4 * M_PI / 3) * range * range * range * density + 16, 8);
    } else
        listCapacity = 64;   // grows when exceeded (particles beyond it meanwhile use the cells)
    // A developer's setting (the tests force the cells' path with it): a fixed capacity.
    const char* fixedCapacity = std::getenv("GENDPDE_LIST_CAPACITY");
    if (fixedCapacity != nullptr && *fixedCapacity != '\0') {
        listCapacity = std::max(1, std::atoi(fixedCapacity));
        wantedCapacity = INT_MIN;   // never grows
    }
    neighbours.initialize<int>(cc, (size_t) numAtoms * listCapacity, "gendpdeListNeighbours");
    needsRebuild = std::make_shared<bool>(true);
    // Per-type parameters (GenDPDETypes.h): each particle's type index by original index, the Tait table by type.
    const int numTypes = types->getNumTypes();
    std::vector<int> typeIndex = types->getParticleTypeIndices();
    typeIndex.resize(numAtoms, 0);   // padding atoms
    atomType.initialize<int>(cc, numAtoms, "gendpdeAtomType");
    atomType.upload(typeIndex);
    lawParameterTable.initialize(cc, numTypes * EquationsOfState::coreStride(), realSize, "gendpdeLawParameters");
    taitPowerTable.initialize<int>(cc, numTypes, "gendpdeTaitPowerTable");
    lawTable.initialize<int>(cc, numTypes, "gendpdeLawTable");
    const int mixedSize = mixedIsDouble(cc) ? sizeof(double) : sizeof(float);
    const int thermalSize = dependsOnTemperature ? numAtoms : 1;
    thermalEnergyOut.initialize(cc, thermalSize, mixedSize, "gendpdeThermalEnergy");
    densityEntropyOut.initialize(cc, thermalSize, mixedSize, "gendpdeDensityEntropy");
    placeholderInt.initialize<int>(cc, 1, "gendpdeThermalPlaceholder");
}

void CommonCalcGenDPDEForceKernel::uploadVolumeTables() {
    const bool useDouble = cc.getUseDoublePrecision();
    const int realSize = useDouble ? sizeof(double) : sizeof(float);
    // The V-B tables from the host's arrays (one source for every platform), in the context's precision, as the
    // physics core reads them (gendpdeVolumeIntegralsVB).
    using namespace Physics;
    const int numPieces = (VolumeVBPolynomials::lastOctave - VolumeVBPolynomials::firstOctave + 1)
            * VolumeVBPolynomials::subintervals;
    const int numCoefficients = numPieces * (VolumeVBPolynomials::degree + 1) * 2;
    const std::vector<double> polynomials(Physics::volumePolynomials(), Physics::volumePolynomials() + numCoefficients);
    polynomialTable.initialize(cc, numCoefficients, realSize, "gendpdeVolumePolynomials");
    std::vector<double> quadrature;
    for (const double* table :
         {VolumeVBQuadrature::nodeSquared, VolumeVBQuadrature::mirrorNodeSquared, VolumeVBQuadrature::coefficient})
        quadrature.insert(quadrature.end(), table, table + VolumeVBQuadrature::numPairs);
    quadratureTable.initialize(cc, quadrature.size(), realSize, "gendpdeVolumeQuadrature");
    uploadValues(polynomialTable, polynomials, useDouble);
    uploadValues(quadratureTable, quadrature, useDouble);
}

void CommonCalcGenDPDEForceKernel::createListKernels(ComputeProgram& program) {
    checkKernel = program->createKernel("checkList");
    {
        using namespace CheckArgument;
        KernelArguments(checkKernel, "checkList")
                .array(Posq, cc.getPosq())
                .array(BuildPosition, buildPosition)
                .later(MaxDrift)
                .later(ForceRebuild)
                .array(Rebuild, rebuild)
                .array(Errors, errors)
                .done(Count);
    }
    buildKernel = program->createKernel("buildList");
    {
        using namespace BuildArgument;
        KernelArguments(buildKernel, "buildList")
                .later(Cells)
                .array(CellStart, grid->cellStart)
                .array(SortedCell, grid->sortedCell)
                .array(SortedSlot, grid->sortedSlot)
                .array(SortedPos, grid->sortedPos)
                .array(AtomIndex, cc.getAtomIndexArray())
                .later(BoxA)
                .later(BoxB)
                .later(BoxC)
                .later(Cutoff)
                .later(ListRange)
                .later(Capacity)
                .array(Rebuild, rebuild)
                .array(BuildPosition, buildPosition)
                .array(ListCount, listCount)
                .later(Neighbours)
                .array(Errors, errors)
                .done(Count);
    }
}

void CommonCalcGenDPDEForceKernel::createSharedListKernel(ComputeProgram& program) {
    sharedBuildKernel = program->createKernel("buildSharedList");
    using namespace SharedBuildArgument;
    KernelArguments(sharedBuildKernel, "buildSharedList")
            .later(Cells)
            .later(CellStart)
            .later(OrderAtom)
            .later(AtomCell)
            .later(SlotOfAtom)
            .later(OrderPosition)
            .later(BoxA)
            .later(BoxB)
            .later(BoxC)
            .later(Cutoff)
            .later(ListRange)
            .later(Capacity)
            .array(Rebuild, rebuild)
            .array(SortedSlot, grid->sortedSlot)
            .array(SortedAtom, grid->sortedAtom)
            .array(SortedCell, grid->sortedCell)
            .array(BuildPosition, buildPosition)
            .array(ListCount, listCount)
            .later(Neighbours)
            .array(Errors, errors)
            .done(Count);
}

void CommonCalcGenDPDEForceKernel::createDensityKernel(ComputeProgram& program) {
    densityKernel = program->createKernel("computeDensities");
    {
        using namespace DensityArgument;
        addNeighbourArguments(densityKernel, "computeDensities")
                .array(AtomIndex, cc.getAtomIndexArray())
                .later(Model)
                .array(AtomType, atomType)
                .array(LawParameters, lawParameterTable)
                .array(TaitPower, taitPowerTable)
                .later(VolumeConstants)
                .later(MomentConstants)
                .later(Estimator)
                .array(Polynomials, polynomialTable)
                .array(Quadrature, quadratureTable)
                .array(PrimitiveDensity, primitiveDensity)
                .array(Volume, volume)
                .array(Pressure, pressure)
                .array(ForceCoefficient, forceCoefficient)
                .array(MomentForce, momentForce)
                .array(Energy, cc.getEnergyBuffer())
                .array(Rebuild, rebuild)
                .array(Errors, errors)
                .later(Thermal)
                .later(Isothermal)
                .later(Temperature)
                .later(EntropyKnown)
                .later(CheckStep)
                .array(LawTable, lawTable)
                .later(StoredEnergy)
                .later(StoredEntropy)
                .later(ParticleClass)
                .later(ClassHeatCapacity)
                .array(ThermalEnergyOut, thermalEnergyOut)
                .array(DensityEntropyOut, densityEntropyOut)
                .done(Count);
        // Without a law that depends on temperature the thermal arguments are placeholders, never read.
        densityKernel->setArg(Thermal, 0);
        densityKernel->setArg(Isothermal, 0);
        setReal(cc, densityKernel, Temperature, 0.0);
        densityKernel->setArg(EntropyKnown, 0);
        densityKernel->setArg(CheckStep, 0);
        for (int argument : {StoredEnergy, StoredEntropy, ClassHeatCapacity})
            densityKernel->setArg(argument, thermalEnergyOut);
        densityKernel->setArg(ParticleClass, placeholderInt);
    }
}

void CommonCalcGenDPDEForceKernel::createForceKernels(ComputeProgram& program) {
    forceKernel = program->createKernel("computeForces");
    {
        using namespace ForceArgument;
        addNeighbourArguments(forceKernel, "computeForces")
                .later(Model)
                .array(ForceCoefficient, forceCoefficient)
                .later(Moments)
                .array(MomentForce, momentForce)
                .array(ForceBuffers, cc.getLongForceBuffer())
                .done(Count);
    }
    virialKernel = program->createKernel("computeVirials");
    {
        using namespace VirialArgument;
        addNeighbourArguments(virialKernel, "computeVirials")
                .later(Model)
                .array(ForceCoefficient, forceCoefficient)
                .later(Moments)
                .array(MomentForce, momentForce)
                .later(Tensors)
                .array(ParticleVirial, particleVirial)
                .array(ParticleVirialTensor, particleVirialTensor)
                .done(Count);
    }
}

void CommonCalcGenDPDEForceKernel::readParameters(const GenDPDEForce& force) {
    GenDPDEForceErrors::checkUnchangeableParameters(force, cutoff, periodic, *types);
    std::vector<Physics::LocalEquationOfState> laws = equationsOfStateByType(force, *types);   // checked first
    estimator = (int) force.getDensityEstimator();
    cutoffScaling = force.getCutoffScaling();
    lawByType = laws;
    dependsOnTemperature = force.dependsOnTemperature();
    if (lawParameterTable.isInitialized())
        uploadTypeTables();
}

void CommonCalcGenDPDEForceKernel::uploadTypeTables() {
    // The law of each type (Physics::LocalEquationOfState): its core parameters, EquationsOfState::coreStride() per
    // type (LAW_PARAMETER_STRIDE), the integer power and the law.
    std::vector<double> parameters;
    std::vector<int> power, law;
    for (const Physics::LocalEquationOfState& p : lawByType) {
        parameters.insert(parameters.end(), p.parameter.begin(), p.parameter.end());
        power.push_back(p.integerPower);
        law.push_back(p.law);
    }
    uploadValues(lawParameterTable, parameters, cc.getUseDoublePrecision());
    taitPowerTable.upload(power);
    lawTable.upload(law);
}

KernelArguments CommonCalcGenDPDEForceKernel::addNeighbourArguments(ComputeKernel& kernel, const std::string& name) {
    using namespace NeighbourArgument;
    KernelArguments arguments(kernel, name);
    arguments.array(ListCount, listCount)
            .later(Neighbours)
            .later(Capacity)
            .later(Cells)
            .array(CellStart, grid->cellStart)
            .array(SortedCell, grid->sortedCell)
            .array(SortedAtom, grid->sortedAtom)
            .array(SortedSlot, grid->sortedSlot)
            .array(SortedPos, grid->sortedPos)
            .array(Posq, cc.getPosq())
            .later(BoxA)
            .later(BoxB)
            .later(BoxC);
    return arguments;
}
