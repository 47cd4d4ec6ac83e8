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
}

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
    momentForce.initialize(cc, numAtoms, 4*realSize, "gendpdeMomentForce");   // V-C's q_i (used only by V-C)
    errors.initialize<int>(cc, 2, "gendpdeForceErrors");
    // Per-type parameters (GenDPDETypes.h): each particle's type index by original index, the Tait table by type.
    const int numTypes = types->getNumTypes();
    std::vector<int> typeIndex = types->getParticleTypeIndices();
    typeIndex.resize(numAtoms, 0);   // padding atoms
    atomType.initialize<int>(cc, numAtoms, "gendpdeAtomType");
    atomType.upload(typeIndex);
    taitTable.initialize(cc, numTypes, 4*realSize, "gendpdeTaitTable");
    taitPowerTable.initialize<int>(cc, numTypes, "gendpdeTaitPowerTable");

    // The V-B tables from the host's arrays (one source for every platform), in the context's precision.
    using namespace Physics;
    const int numPieces = (VolumeVBPolynomials::lastOctave - VolumeVBPolynomials::firstOctave + 1)
                          *VolumeVBPolynomials::subintervals;
    std::vector<double> coefficients(&VolumeVBPolynomials::coefficients[0][0][0],
                                     &VolumeVBPolynomials::coefficients[0][0][0] + numPieces*14*2);
    vbCoefficients.initialize(cc, numPieces*14, 2*realSize, "gendpdeVBCoefficients");
    std::vector<double> quadrature;
    for (const double* table : {VolumeVBQuadrature::nodeSquared, VolumeVBQuadrature::mirrorNodeSquared,
                                VolumeVBQuadrature::coefficient})
        quadrature.insert(quadrature.end(), table, table + VolumeVBQuadrature::numPairs);
    vbQuadrature.initialize(cc, quadrature.size(), realSize, "gendpdeVBQuadrature");
    uploadValues(vbCoefficients, coefficients, useDouble);
    uploadValues(vbQuadrature, quadrature, useDouble);

    uploadTypeTables();
    grid.reset(new CommonGenDPDECellGrid(cc, periodic, cutoff));
    std::map<std::string, std::string> defines = grid->defines();
    defines["VB_FIRST_OCTAVE"] = cc.intToString(VolumeVBPolynomials::firstOctave);
    defines["VB_LAST_OCTAVE"] = cc.intToString(VolumeVBPolynomials::lastOctave);
    defines["VB_QUADRATURE_PAIRS"] = cc.intToString(VolumeVBQuadrature::numPairs);
    ComputeProgram program = cc.compileProgram(CommonGenDPDEKernelSources::physicsCore("real")
            + CommonGenDPDEKernelSources::gendpdeCells + CommonGenDPDEKernelSources::gendpdeForce, defines);
    grid->createKernels(program);
    resetErrorsKernel = program->createKernel("resetErrors");
    resetErrorsKernel->addArg(errors);
    densityKernel = program->createKernel("computeDensities");
    densityKernel->addArg();   // cells
    densityKernel->addArg(grid->cellStart);
    densityKernel->addArg(grid->sortedCell);
    densityKernel->addArg(grid->sortedAtom);
    densityKernel->addArg(grid->sortedPos);
    for (int i = 0; i < 4; i++)
        densityKernel->addArg();   // box (3), model
    densityKernel->addArg(atomType);
    densityKernel->addArg(taitTable);
    densityKernel->addArg(taitPowerTable);
    densityKernel->addArg();   // vb
    densityKernel->addArg();   // estimator
    densityKernel->addArg(vbCoefficients);
    densityKernel->addArg(vbQuadrature);
    densityKernel->addArg(primitiveDensity);
    densityKernel->addArg(volume);
    densityKernel->addArg(pressure);
    densityKernel->addArg(forceCoefficient);
    densityKernel->addArg(cc.getEnergyBuffer());
    densityKernel->addArg(errors);
    densityKernel->addArg();   // vc
    densityKernel->addArg(momentForce);
    forceKernel = program->createKernel("computeForces");
    forceKernel->addArg();   // cells
    forceKernel->addArg(grid->cellStart);
    forceKernel->addArg(grid->sortedCell);
    forceKernel->addArg(grid->sortedSlot);
    forceKernel->addArg(grid->sortedPos);
    for (int i = 0; i < 4; i++)
        forceKernel->addArg();   // box (3), model
    forceKernel->addArg(forceCoefficient);
    forceKernel->addArg(cc.getLongForceBuffer());
    forceKernel->addArg();   // includeForces
    forceKernel->addArg();   // includeVirial
    forceKernel->addArg(particleVirial);
    forceKernel->addArg();   // moments (V-C)
    forceKernel->addArg(momentForce);
    cc.addForce(new ForceInfo(types->getParticleTypeIndices()));
}

void CommonCalcGenDPDEForceKernel::copyParametersToContext(ContextImpl& context, const GenDPDEForce& force) {
    readParameters(force);
}

void CommonCalcGenDPDEForceKernel::readParameters(const GenDPDEForce& force) {
    GenDPDEForceErrors::checkUnchangeableParameters(force, cutoff, periodic, *types);
    std::vector<TaitParameters> tait = taitParametersByType(force, *types);   // checked before anything changes
    estimator = force.getDensityEstimator();
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
    // The same constants as Physics::DensityWeight, TaitEquationOfState and VolumeEstimatorVB.
    const Physics::DensityWeight weight(cutoff);
    const Physics::VolumeEstimatorVB volumeVB(cutoff/cutoffScaling);
    const double model[4] = {cutoff, weight.getInverseCutoff(), weight.getValueScale(), weight.getDerivativeScale()};
    const double vb4[4] = {volumeVB.getKPerDensity(), volumeVB.getVolumeScale(), volumeVB.getDerivativeScale(), 0.0};
    const mm_int4 cells = grid->getCellsArgument();
    densityKernel->setArg(0, cells);
    forceKernel->setArg(0, cells);
    grid->setBoxArguments(densityKernel, 5, false);
    grid->setBoxArguments(forceKernel, 5, false);
    for (ComputeKernel* kernel : {&densityKernel, &forceKernel})
        setReal4(cc, *kernel, 8, model[0], model[1], model[2], model[3]);
    setReal4(cc, densityKernel, 12, vb4[0], vb4[1], vb4[2], vb4[3]);
    densityKernel->setArg(13, estimator == GenDPDEForce::VA ? 0 : estimator == GenDPDEForce::VB ? 1 : 2);
    const Physics::VolumeEstimatorVC volumeVC(cutoff, cutoff/cutoffScaling);
    setReal4(cc, densityKernel, 22, volumeVC.getMomentScale(), volumeVC.getDensitySoftening(), 0.0, 0.0);
    forceKernel->setArg(14, estimator == GenDPDEForce::VC ? 1 : 0);
}

void CommonCalcGenDPDEForceKernel::computeDensities(ContextImpl& context) {
    if (periodic) {
        Vec3 box[3];
        cc.getPeriodicBoxVectors(box[0], box[1], box[2]);
        BoxGeometry::checkCutoffAgainstBox("GenDPDEForce", cutoff, box);
    }
    profiler.time("cell grid", [&]() { grid->build(); });
    setModelArguments();
    profiler.time("densities, particle state", [&]() {
        resetErrorsKernel->execute(1);
        densityKernel->execute(cc.getNumAtoms());
    });
    std::vector<int> found;
    errors.download(found);
    if (found[0] == noValue && found[1] == noValue)
        return;
    // The first particle in index order whose position, then whose state, is bad (as the Reference platform checks).
    std::vector<Vec3> positions;
    context.getPositions(positions);
    for (int i = 0; i < (int) positions.size(); i++)
        if (!(std::isfinite(positions[i][0]) && std::isfinite(positions[i][1]) && std::isfinite(positions[i][2])))
            throw OpenMMException(GenDPDEForceErrors::nonFinitePosition(i, positions[i], cc.getStepCount()));
    const int particle = found[1]/4, status = found[1]%4;
    if (status == 1)
        throw OpenMMException(GenDPDEForceErrors::noNeighbor(particle, cutoff, cc.getStepCount()));
    std::vector<int> atoms;
    std::vector<double> densities;
    grid->sortedAtom.download(atoms);
    primitiveDensity.download(densities, true);
    double n0 = 0.0;
    for (int k = 0; k < (int) atoms.size(); k++)
        if (atoms[k] == particle)
            n0 = densities[k];
    // (V-C: the density of V-B at this n0, without the surface factor, whose moment is not kept.)
    const double density = 1.0/(estimator == GenDPDEForce::VA ? Physics::volumeVA(n0)
                                : Physics::volumeVB(n0, cutoff/cutoffScaling)).volume;
    throw OpenMMException(GenDPDEForceErrors::equationOfStateOverflow(particle, density,
            taitByType[types->getParticleTypeIndices()[particle]].referenceDensity, cc.getStepCount()));
}

void CommonCalcGenDPDEForceKernel::computeForces(bool includeForces, bool includeVirial) {
    forceKernel->setArg(11, includeForces ? 1 : 0);
    forceKernel->setArg(12, includeVirial ? 1 : 0);
    profiler.time(includeForces ? "forces" : "virial", [&]() { forceKernel->execute(cc.getNumAtoms()); });
}

double CommonCalcGenDPDEForceKernel::execute(ContextImpl& context, bool includeForces, bool includeEnergy) {
    ContextSelector selector(cc);
    computeDensities(context);
    if (includeForces)
        computeForces(true, false);
    return 0.0;   // the energy is in the context's energy buffer
}

const GenDPDEObservables& CommonCalcGenDPDEForceKernel::getObservables(ContextImpl& context) {
    ContextSelector selector(cc);
    computeDensities(context);
    computeForces(false, true);
    std::vector<int> atoms;
    std::vector<double> n0, v, pi, w;
    grid->sortedAtom.download(atoms);
    primitiveDensity.download(n0, true);
    volume.download(v, true);
    pressure.download(pi, true);
    particleVirial.download(w, true);
    const int numAtoms = cc.getNumAtoms();
    observables.primitiveDensities.resize(numAtoms);
    observables.volumes.resize(numAtoms);
    observables.densities.resize(numAtoms);
    observables.pressures.resize(numAtoms);
    std::vector<double> virial(numAtoms);
    for (int k = 0; k < numAtoms; k++) {
        const int i = atoms[k];
        observables.primitiveDensities[i] = n0[k];
        observables.volumes[i] = v[k];
        observables.densities[i] = 1.0/v[k];
        observables.pressures[i] = pi[k];
        virial[i] = w[k];
    }
    FixedOrderSum::Accumulator sum;
    for (double value : virial)
        sum.add(value);
    observables.virial = sum.sum();
    return observables;
}
