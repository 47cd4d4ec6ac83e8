#include "CommonGenDPDEForceKernel.h"
#include "CommonGenDPDEArguments.h"
#include "CommonGenDPDEKernelSources.h"
#include "internal/BoxGeometry.h"
#include "internal/FixedOrderSum.h"
#include "internal/GenDPDEForceErrors.h"
#include "internal/GenDPDEPhysics.h"
#include "openmm/OpenMMException.h"
#include "openmm/common/ComputeForceInfo.h"
#include "openmm/common/ContextSelector.h"
#include "openmm/internal/ContextImpl.h"
#include <algorithm>
#include <climits>
#include <cmath>

using namespace GenDPDEPlugin;
using namespace OpenMM;

/** Particles of the same type interact alike: OpenMM may exchange them when it reorders the atoms. */
class CommonCalcGenDPDEForceKernel::ForceInfo : public ComputeForceInfo {
public:
    explicit ForceInfo(const std::vector<int>& typeIndex) : typeIndex(typeIndex) {
    }
    bool areParticlesIdentical(int particle1, int particle2) override {
        return typeIndex[particle1] == typeIndex[particle2];
    }
private:
    std::vector<int> typeIndex;
};

namespace {

const int noValue = INT_MAX;

/** The arguments of kernels/gendpdeForce.cc's kernels, in the order of their parameters. */
namespace DensityArgument {
enum {Cells, CellStart, SortedCell, SortedAtom, SortedPos, BoxA, BoxB, BoxC, Model, AtomType, TaitTable, TaitPower,
      VolumeConstants, MomentConstants, Estimator, Polynomials, Quadrature, PrimitiveDensity, Volume, Pressure,
      ForceCoefficient, MomentForce, Energy, Errors, Count};
}
namespace ForceArgument {
enum {Cells, CellStart, SortedCell, SortedSlot, SortedPos, BoxA, BoxB, BoxC, Model, ForceCoefficient, Moments,
      MomentForce, ForceBuffers, Count};
}
namespace VirialArgument {
enum {Cells, CellStart, SortedCell, SortedPos, BoxA, BoxB, BoxC, Model, ForceCoefficient, Moments, MomentForce,
      Tensors, ParticleVirial, ParticleVirialTensor, Count};
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
    particleVirialTensor.initialize(cc, 9*numAtoms, realSize, "gendpdeParticleVirialTensor");
    momentForce.initialize(cc, numAtoms, 4*realSize, "gendpdeMomentForce");   // (used only by V-C)
    errors.initialize<int>(cc, 2, "gendpdeForceErrors");
    errors.upload(std::vector<int>(2, noValue));
    // Per-type parameters (GenDPDETypes.h): each particle's type index by original index, the Tait table by type.
    const int numTypes = types->getNumTypes();
    std::vector<int> typeIndex = types->getParticleTypeIndices();
    typeIndex.resize(numAtoms, 0);   // padding atoms
    atomType.initialize<int>(cc, numAtoms, "gendpdeAtomType");
    atomType.upload(typeIndex);
    taitTable.initialize(cc, numTypes, 4*realSize, "gendpdeTaitTable");
    taitPowerTable.initialize<int>(cc, numTypes, "gendpdeTaitPowerTable");

    // The V-B tables from the host's arrays (one source for every platform), in the context's precision, as the
    // physics core reads them (gendpdeVolumeIntegralsVB).
    using namespace Physics;
    const int numPieces = (VolumeVBPolynomials::lastOctave - VolumeVBPolynomials::firstOctave + 1)
                          *VolumeVBPolynomials::subintervals;
    const int numCoefficients = numPieces*(VolumeVBPolynomials::degree + 1)*2;
    const std::vector<double> polynomials(Physics::volumePolynomials(), Physics::volumePolynomials() + numCoefficients);
    polynomialTable.initialize(cc, numCoefficients, realSize, "gendpdeVolumePolynomials");
    std::vector<double> quadrature;
    for (const double* table : {VolumeVBQuadrature::nodeSquared, VolumeVBQuadrature::mirrorNodeSquared,
                                VolumeVBQuadrature::coefficient})
        quadrature.insert(quadrature.end(), table, table + VolumeVBQuadrature::numPairs);
    quadratureTable.initialize(cc, quadrature.size(), realSize, "gendpdeVolumeQuadrature");
    uploadValues(polynomialTable, polynomials, useDouble);
    uploadValues(quadratureTable, quadrature, useDouble);

    uploadTypeTables();
    grid.reset(new CommonGenDPDECellGrid(cc, profiler, periodic, cutoff));
    ComputeProgram program = cc.compileProgram(CommonGenDPDEKernelSources::physicsCore("real")
            + CommonGenDPDEKernelSources::gendpdeCells + CommonGenDPDEKernelSources::gendpdeForce, grid->defines());
    grid->createKernels(program);
    resetErrorsKernel = program->createKernel("resetErrors");
    resetErrorsKernel->addArg(errors);
    densityKernel = program->createKernel("computeDensities");
    {
        using namespace DensityArgument;
        KernelArguments(densityKernel, "computeDensities").later(Cells).array(CellStart, grid->cellStart)
                .array(SortedCell, grid->sortedCell).array(SortedAtom, grid->sortedAtom)
                .array(SortedPos, grid->sortedPos).later(BoxA).later(BoxB).later(BoxC).later(Model)
                .array(AtomType, atomType).array(TaitTable, taitTable).array(TaitPower, taitPowerTable)
                .later(VolumeConstants).later(MomentConstants).later(Estimator).array(Polynomials, polynomialTable)
                .array(Quadrature, quadratureTable).array(PrimitiveDensity, primitiveDensity).array(Volume, volume)
                .array(Pressure, pressure).array(ForceCoefficient, forceCoefficient).array(MomentForce, momentForce)
                .array(Energy, cc.getEnergyBuffer()).array(Errors, errors).done(Count);
    }
    forceKernel = program->createKernel("computeForces");
    {
        using namespace ForceArgument;
        KernelArguments(forceKernel, "computeForces").later(Cells).array(CellStart, grid->cellStart)
                .array(SortedCell, grid->sortedCell).array(SortedSlot, grid->sortedSlot)
                .array(SortedPos, grid->sortedPos).later(BoxA).later(BoxB).later(BoxC).later(Model)
                .array(ForceCoefficient, forceCoefficient).later(Moments).array(MomentForce, momentForce)
                .array(ForceBuffers, cc.getLongForceBuffer()).done(Count);
    }
    virialKernel = program->createKernel("computeVirials");
    {
        using namespace VirialArgument;
        KernelArguments(virialKernel, "computeVirials").later(Cells).array(CellStart, grid->cellStart)
                .array(SortedCell, grid->sortedCell).array(SortedPos, grid->sortedPos).later(BoxA).later(BoxB)
                .later(BoxC).later(Model).array(ForceCoefficient, forceCoefficient).later(Moments)
                .array(MomentForce, momentForce).later(Tensors).array(ParticleVirial, particleVirial)
                .array(ParticleVirialTensor, particleVirialTensor).done(Count);
    }
    cc.addForce(new ForceInfo(types->getParticleTypeIndices()));
}

void CommonCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    readParameters(force);
}

void CommonCalcGenDPDEForceKernel::readParameters(const GenDPDEForce& force) {
    GenDPDEForceErrors::checkUnchangeableParameters(force, cutoff, periodic, *types);
    std::vector<TaitParameters> tait = taitParametersByType(force, *types);   // checked before anything changes
    estimator = (int) force.getDensityEstimator();
    cutoffScaling = force.getCutoffScaling();
    taitByType = tait;
    if (taitTable.isInitialized())
        uploadTypeTables();
}

void CommonCalcGenDPDEForceKernel::uploadTypeTables() {
    // The Tait equation of state of each type (Physics::TaitEquationOfState).
    std::vector<double> tait;
    std::vector<int> power;
    for (const TaitParameters& p : taitByType) {
        tait.insert(tait.end(), {p.referenceDensity, p.referencePressure, p.bulkModulus, p.exponent});
        power.push_back(Physics::TaitEquationOfState::integerPowerOf(p.exponent));
    }
    uploadValues(taitTable, tait, cc.getUseDoublePrecision());
    taitPowerTable.upload(power);
}

void CommonCalcGenDPDEForceKernel::setModelArguments() {
    // The constants of the physics core (gendpdeDensityWeightScales, gendpdeEstimatorConstants), computed on the host.
    const Physics::DensityWeight weight(cutoff);
    const Physics::VolumeEstimator constants(estimator, cutoff, cutoff/cutoffScaling);
    const mm_int4 cells = grid->getCellsArgument();
    densityKernel->setArg(DensityArgument::Cells, cells);
    forceKernel->setArg(ForceArgument::Cells, cells);
    virialKernel->setArg(VirialArgument::Cells, cells);
    grid->setBoxArguments(densityKernel, DensityArgument::BoxA, false);
    grid->setBoxArguments(forceKernel, ForceArgument::BoxA, false);
    grid->setBoxArguments(virialKernel, VirialArgument::BoxA, false);
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

void CommonCalcGenDPDEForceKernel::computeDensities(ContextImpl& context) {
    if (periodic) {
        Vec3 box[3];
        cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", cutoff, box);
    }
    profiler.countStep();
    profiler.time("cell grid", [&]() { grid->build(); });
    setModelArguments();
    profiler.time("densities, particle state", [&]() {
        profiler.launch(resetErrorsKernel, 1);
        profiler.launch(densityKernel, cc.getNumAtoms());
    });
    pairsFound(cutoff, cc.getStepCount());
    if (deferred)
        return;   // the integrator's run checks the flags on the device
    std::vector<int> found;
    profiler.transfer();
    errors.download(found);
    if (found[0] != noValue || found[1] != noValue)
        throwErrors(context, found[0], found[1], cc.getStepCount());
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
    const int particle = invalid/4, status = invalid%4;
    if (status == GENDPDE_PARTICLE_NO_NEIGHBOR)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(particle, cutoff, step));
    // The density of the particle at these positions (the flags came from an evaluation at them).
    if (deferred)
        throw OpenMMException("GenDPDEForce: internal error: throwErrors() while the checks are deferred");
    computeDensitiesQuietly();
    std::vector<int> atoms;
    std::vector<double> volumes;
    grid->sortedAtom.download(atoms);
    volume.download(volumes, true);
    double density = 0.0;
    for (int k = 0; k < (int) atoms.size(); k++)
        if (atoms[k] == particle)
            density = 1.0/volumes[k];
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(particle, density,
            taitByType[types->getParticleTypeIndices()[particle]].referenceDensity, step));
}

void CommonCalcGenDPDEForceKernel::computeDensitiesQuietly() {
    grid->build();
    setModelArguments();
    profiler.launch(resetErrorsKernel, 1);
    profiler.launch(densityKernel, cc.getNumAtoms());
}

double CommonCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    ContextSelector selector(cc);
    computeDensities(context);
    if (includeForces)
        profiler.time("forces", [&]() { profiler.launch(forceKernel, cc.getNumAtoms()); });
    return 0.0;   // the energy is in the context's energy buffer
}

const GenDPDEObservables& CommonCalcGenDPDEForceKernel::getObservables(ContextImpl& context, bool particleVirials) {
    ContextSelector selector(cc);
    computeDensities(context);
    virialKernel->setArg(VirialArgument::Tensors, particleVirials ? 1 : 0);
    profiler.time("virials", [&]() { profiler.launch(virialKernel, cc.getNumAtoms()); });
    std::vector<int> atoms;
    std::vector<double> n0, v, pi, w, tensors;
    grid->sortedAtom.download(atoms);
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
    observables.particleVirials.assign(particleVirials ? 9*numAtoms : 0, 0.0);
    std::vector<double> virial(numAtoms);
    for (int k = 0; k < numAtoms; k++) {
        const int i = atoms[k];
        observables.primitiveDensities[i] = n0[k];
        observables.volumes[i] = v[k];
        observables.densities[i] = 1.0/v[k];
        observables.pressures[i] = pi[k];
        virial[i] = w[k];
        if (particleVirials)
            std::copy(&tensors[9*k], &tensors[9*k] + 9, &observables.particleVirials[9*i]);
    }
    FixedOrderSum::Accumulator sum;
    for (double value : virial)
        sum.add(value);
    observables.virial = sum.sum();
    return observables;
}
