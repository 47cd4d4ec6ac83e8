#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEThermalArrays.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/common/ComputeForceInfo.h"
#include "openmm/common/ContextSelector.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>

using namespace GenDPDEPlugin;
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

namespace {

const int noValue = INT_MAX;

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

/** The list's skin, as a fraction of the cutoff (the Reference platform's neighbour list uses the same). */
const double listSkin = 0.1;

int roundUp(double value, int multiple) {
    return multiple * (int) std::ceil(value / multiple);
}

} // namespace

void CommonCalcGenDPDEForceKernel::initialize(const System& system, const GenDPDEForce& force) {
    ContextSelector selector(cc);
    cutoff = force.getCutoffDistance();
    periodic = force.usesPeriodicBoundaryConditions();
    types.reset(new ParticleTypeIndex(force.getParticleTypes(), system.getNumParticles(), "GenDPDEForce"));
    readParameters(force);
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

    uploadTypeTables();
    grid.reset(new CommonGenDPDECellGrid(cc, profiler, periodic, cutoff));
    std::map<std::string, std::string> defines = grid->defines();
    defines["LAW_PARAMETER_STRIDE"] = std::to_string(EquationsOfState::coreStride());
    ComputeProgram program =
            cc.compileProgram(CommonGenDPDEKernelSources::physicsCore("real") + CommonGenDPDEKernelSources::gendpdeCells
                                      + CommonGenDPDEKernelSources::gendpdeForce,
                              defines);
    grid->createKernels(program);
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
    // Atom reordering moves particles between slots, which the list holds: it is rebuilt after.
    cc.addReorderListener(new ReorderListener(needsRebuild));
    cc.addForce(new ForceInfo(types->getParticleTypeIndices()));
}

CommonCalcGenDPDEForceKernel::~CommonCalcGenDPDEForceKernel() {
    // The list's counters for the profile (GENDPDE_PROFILE): entries and pairs in range at the last build.
    if (!profiler.isEnabled() || !errors.isInitialized())
        return;
    ContextSelector selector(cc);
    std::vector<int> found;
    errors.download(found);
    const double particles = cc.getNumAtoms();
    profiler.note("neighbour list: " + std::to_string(found[5]) + " builds, skin " + std::to_string(listSkin)
                  + " R, capacity " + std::to_string(listCapacity) + "; at the last build "
                  + std::to_string(found[3] / particles) + " entries and " + std::to_string(found[4] / particles)
                  + " neighbours closer than R per particle: "
                  + std::to_string(found[4] > 0 ? 2.0 * found[3] / found[4] : 0.0)
                  + " distances per pair in range and pass");
}

void CommonCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    ContextSelector selector(cc);   // (the tables are uploaded: CUDA needs its context current on this thread)
    readParameters(force);
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

void CommonCalcGenDPDEForceKernel::setModelArguments() {
    // The constants of the physics core (gendpdeDensityWeightScales, gendpdeEstimatorConstants), computed on the host.
    const Physics::DensityWeight weight(cutoff);
    const Physics::VolumeEstimator constants(estimator, cutoff, cutoff / cutoffScaling);
    const mm_int4 cells = grid->getCellsArgument();
    for (ComputeKernel* kernel : {&densityKernel, &forceKernel, &virialKernel}) {
        using namespace NeighbourArgument;
        (*kernel)->setArg(Neighbours, neighbours);
        (*kernel)->setArg(Capacity, listCapacity);
        (*kernel)->setArg(Cells, cells);
        grid->setBoxArguments(*kernel, BoxA, false);
    }
    buildKernel->setArg(BuildArgument::Cells, cells);
    grid->setBoxArguments(buildKernel, BuildArgument::BoxA, false);
    setReal(cc, buildKernel, BuildArgument::Cutoff, cutoff);
    setReal(cc, buildKernel, BuildArgument::ListRange, (1 + listSkin) * cutoff);
    buildKernel->setArg(BuildArgument::Capacity, listCapacity);
    buildKernel->setArg(BuildArgument::Neighbours, neighbours);
    setReal(cc, checkKernel, CheckArgument::MaxDrift, 0.5 * listSkin * cutoff);
    for (auto kernelAndIndex : {std::make_pair(&densityKernel, (int) DensityArgument::Model),
                                std::make_pair(&forceKernel, (int) ForceArgument::Model),
                                std::make_pair(&virialKernel, (int) VirialArgument::Model)})
        setReal4(cc, *kernelAndIndex.first, kernelAndIndex.second, cutoff, weight.getInverseCutoff(),
                 weight.getValueScale(), weight.getDerivativeScale());
    setReal4(cc, densityKernel, DensityArgument::VolumeConstants, constants.getKPerDensity(),
             constants.getVolumeScale(), constants.getDerivativeScale(), 0.0);
    setReal4(cc, densityKernel, DensityArgument::MomentConstants, constants.getMomentScale(),
             constants.getDensitySoftening(), 0.0, 0.0);
    densityKernel->setArg(DensityArgument::Estimator, estimator);
    forceKernel->setArg(ForceArgument::Moments, constants.needsMoments() ? 1 : 0);
    virialKernel->setArg(VirialArgument::Moments, constants.needsMoments() ? 1 : 0);
}

void CommonCalcGenDPDEForceKernel::setThermalArguments(ContextImpl& context) {
    using namespace DensityArgument;
    const GenDPDEIntegrator* integrator;
    IntegrateGenDPDEStepKernel& holder = GenDPDEIntegratorUtilities::thermalStateHolder(context, integrator);
    CommonGenDPDEThermalArrays* state = holder.getDeviceThermalState(*integrator);
    if (state == nullptr)
        throw OpenMMException("GenDPDEForce: the GenDPDEIntegrator's kernel does not hold its thermal state on the "
                              "device");
    densityKernel->setArg(Thermal, 1);
    densityKernel->setArg(Isothermal, state->isothermal ? 1 : 0);
    setReal(cc, densityKernel, Temperature, state->temperature);
    densityKernel->setArg(EntropyKnown, state->entropiesKnown ? 1 : 0);
    densityKernel->setArg(CheckStep, state->checkStep ? 1 : 0);
    densityKernel->setArg(StoredEnergy, *state->internalEnergies);
    densityKernel->setArg(StoredEntropy, *state->densityEntropies);
    densityKernel->setArg(ParticleClass, *state->particleClass);
    densityKernel->setArg(ClassHeatCapacity, *state->classHeatCapacity);
}

bool CommonCalcGenDPDEForceKernel::giveThermalState(IntegrateGenDPDEStepKernel& integratorKernel) {
    if (dependsOnTemperature)
        integratorKernel.keepDeviceThermalState(thermalEnergyOut, densityEntropyOut);
    return dependsOnTemperature;
}

void CommonCalcGenDPDEForceKernel::computeDensities(ContextImpl& context) {
    if (dependsOnTemperature)
        setThermalArguments(context);
    densityPass();
    if (deferred)
        return; // the integrator's run checks the flags on the device
    std::vector<int> found;
    profiler.transfer();
    errors.download(found);
    growList(found[2]);
    if (found[0] != noValue || found[1] != noValue)
        throwErrors(context, found[0], found[1], cc.getStepCount());
}

void CommonCalcGenDPDEForceKernel::densityPass() {
    Vec3 box[3];
    cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
    if (periodic) {
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", cutoff, box);
        if (box[0] != listBox[0] || box[1] != listBox[1] || box[2] != listBox[2])
            *needsRebuild = true; // (a barostat) the list's positions and images belong to another box
    }
    if (wantedCapacity > listCapacity) {
        listCapacity = wantedCapacity;
        neighbours.resize((size_t) cc.getNumAtoms() * listCapacity);
        *needsRebuild = true;
    }
    profiler.countStep();
    profiler.time("cell grid", [&]() { grid->build(); });
    setModelArguments();
    profiler.time("neighbour list", [&]() {
        checkKernel->setArg(CheckArgument::ForceRebuild, *needsRebuild ? 1 : 0);
        profiler.launch(checkKernel, cc.getNumAtoms());
        profiler.launch(buildKernel, cc.getNumAtoms());
    });
    *needsRebuild = false;
    for (int k = 0; k < 3; k++)
        listBox[k] = box[k];
    profiler.time("densities, particle state", [&]() { profiler.launch(densityKernel, cc.getNumAtoms()); });
    pairsFound(cutoff, cc.getStepCount());
}

void CommonCalcGenDPDEForceKernel::setDeferred(bool deferred) {
    if (this->deferred && !deferred) {
        // The end of an integrator's run of steps: the list's largest count, read once per run.
        ContextSelector selector(cc);
        std::vector<int> found;
        profiler.transfer();
        errors.download(found);
        growList(found[2]);
    }
    this->deferred = deferred;
}

void CommonCalcGenDPDEForceKernel::growList(int mostNeighbours) {
    // Some particles had more neighbours than the list holds (they used the cells): room for them at the start of
    // the next evaluation (this one's passes may still read the list).
    if (mostNeighbours > listCapacity && wantedCapacity != INT_MIN)
        wantedCapacity = std::max(wantedCapacity, roundUp(1.25 * mostNeighbours, 8));
}

void CommonCalcGenDPDEForceKernel::throwErrors(ContextImpl& context, int nonFinite, int invalid, long long step) {
    // The first particle in index order whose position, then whose state, is bad (as the Reference platform checks).
    std::vector<Vec3> positions;
    context.getPositions(positions);
    for (int i = 0; i < (int) positions.size(); i++)
        if (!(std::isfinite(positions[i][0]) && std::isfinite(positions[i][1]) && std::isfinite(positions[i][2])))
            throw OpenMMException(GenDPDEForceErrors::nonFinitePosition(i, positions[i], step));
    if (invalid == noValue)
        throw OpenMMException("GenDPDEForce: a particle's position is not finite at step " + std::to_string(step)
                              + " (particle " + std::to_string(nonFinite) + ")");
    const int particle = invalid / GENDPDE_PARTICLE_STATUSES, status = invalid % GENDPDE_PARTICLE_STATUSES;
    if (status == GENDPDE_PARTICLE_NO_NEIGHBOR)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(particle, cutoff, step));
    const Physics::LocalEquationOfState& law = lawByType[types->getParticleTypeIndices()[particle]];
    // The density of the particle at these positions (the flags came from an evaluation at them; the atoms may have
    // been reordered since, so the pass runs again).
    densityPass();
    std::vector<double> volumes;
    volume.download(volumes, true);
    const double density = 1.0 / volumes[slotOf(particle)];
    if (status == GENDPDE_PARTICLE_OUTSIDE_DOMAIN)
        throw OpenMMException(GenDPDEForceErrors::outsideDomain(particle, density, law, step));
    if (status == GENDPDE_PARTICLE_TEMPERATURE_JUMP) {
        // theta where the integrator kept the state (the last step's positions; it kept none from the failed
        // evaluation) and here
        const GenDPDEIntegrator* integrator;
        CommonGenDPDEThermalArrays* state =
                GenDPDEIntegratorUtilities::thermalStateHolder(context, integrator).getDeviceThermalState(*integrator);
        std::vector<double> stored, found, capacity;
        std::vector<int> particleClass;
        state->internalEnergies->download(stored, true);
        thermalEnergyOut.download(found, true);
        state->classHeatCapacity->download(capacity, true);
        state->particleClass->download(particleClass);
        const double c = capacity[particleClass[particle]];
        throw OpenMMException(GenDPDEForceErrors::temperatureJump(particle, stored[particle] / c, found[particle] / c,
                                                                  density, step));
    }
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(particle, density, law, step));
}

int CommonCalcGenDPDEForceKernel::slotOf(int particle) const {
    const std::vector<int>& atomIndex = cc.getAtomIndex();
    return (int) (std::find(atomIndex.begin(), atomIndex.end(), particle) - atomIndex.begin());
}

double CommonCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    ContextSelector selector(cc);
    computeDensities(context);
    if (includeForces)
        profiler.time("forces", [&]() { profiler.launch(forceKernel, cc.getNumAtoms()); });
    return 0.0; // the energy is in the context's energy buffer
}

const GenDPDEObservables& CommonCalcGenDPDEForceKernel::getObservables(ContextImpl& context, bool particleVirials) {
    ContextSelector selector(cc);
    computeDensities(context);
    virialKernel->setArg(VirialArgument::Tensors, particleVirials ? 1 : 0);
    profiler.time("virials", [&]() { profiler.launch(virialKernel, cc.getNumAtoms()); });
    std::vector<double> n0, v, pi, w, tensors;
    primitiveDensity.download(n0, true);
    volume.download(v, true);
    pressure.download(pi, true);
    particleVirial.download(w, true);
    if (particleVirials)
        particleVirialTensor.download(tensors, true);
    const int numAtoms = cc.getNumAtoms();
    observables.primitiveDensities.resize(numAtoms);
    observables.volumes.resize(numAtoms);
    observables.densities.resize(numAtoms);
    observables.pressures.resize(numAtoms);
    observables.particleVirials.assign(particleVirials ? 9 * numAtoms : 0, 0.0);
    std::vector<double> virial(numAtoms);
    const std::vector<int>& atomIndex = cc.getAtomIndex(); // the values are by slot
    for (int slot = 0; slot < numAtoms; slot++) {
        const int i = atomIndex[slot];
        observables.primitiveDensities[i] = n0[slot];
        observables.volumes[i] = v[slot];
        observables.densities[i] = 1.0 / v[slot];
        observables.pressures[i] = pi[slot];
        virial[i] = w[slot];
        if (particleVirials)
            std::copy(&tensors[9 * slot], &tensors[9 * slot] + 9, &observables.particleVirials[9 * i]);
    }
    FixedOrderSum::Accumulator sum;
    for (double value : virial)
        sum.add(value);
    observables.virial = sum.sum();
    return observables;
}
