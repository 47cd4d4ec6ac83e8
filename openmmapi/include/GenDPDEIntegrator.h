/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_INTEGRATOR_H_
#define GENDPDE_INTEGRATOR_H_

#include "openmm/Integrator.h"
#include "openmm/Kernel.h"
#include <climits>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

class GenDPDEForceImpl;
class GenDPDEPairSource;
class IntegrateGenDPDEStepKernel;
struct GenDPDEStepTerms;

/**
 * The energy-conserving integrator of generalised DPD (GenDPDE). Each particle i carries an internal (thermal)
 * energy eps_i and temperature theta_i = eps_i/C_V besides its position and velocity. For every pair closer than
 * the cutoff R, with omega_R = 1 - r/R and omega_D = omega_q = omega_R^2 (docs/theory.md section 5):
 *
 *   dp_i = F_i dt + sum_j [ -gamma omega_D (e_ij . v_ij) e_ij dt + sigma_ij omega_R e_ij dW_ij ],
 *          sigma_ij^2 = 2 gamma k_B Theta_ij,  1/Theta_ij = (1/theta_i + 1/theta_j)/2;
 *   deps_i = sum_j [ kappa omega_q (1/theta_i - 1/theta_j) dt + alpha omega_R dW^q_ij ],  alpha^2 = 2 k_B kappa,
 *          plus half of the kinetic energy that each pair update removes (mechanical heating).
 *
 * F_i are the conservative forces of every Force in the System (in the integration force groups). Total momentum
 * and the total energy K + U + sum_i eps_i are conserved.
 *
 * Splitting. One step is a Shardlow-like splitting (Lisal, Brennan, Bonet Avalos 2011), symmetric in the
 * conservative part: a half kick v += (dt/2) F/m at positions x_n, then the pair updates at x_n, then another
 * half kick, then the drift x += dt v. Between steps the velocities are half a step behind the positions, as with
 * OpenMM's VerletIntegrator; the kinetic energy and the conserved energy are computed with on-step velocities
 * v_n = v + (dt/2) F/m. Over a run this is the sequence [velocity Verlet(dt)] [pair updates(dt)] repeated, with
 * one force evaluation per step.
 *
 * Pair updates. The pairs are visited sequentially at fixed positions in a fixed order (docs/theory.md section 6),
 * made at a build from the candidate pairs (closer than 1.1 R) and kept until some particle has moved more than
 * 0.05 R from its position at the build or the box changes; each step updates, in that order, the candidates closer
 * than R. The order: the candidates grouped by 2 x 2 x 2 blocks of cells at least 1.1 R wide, the blocks in eight
 * colours (two blocks of one colour share no particle, so a parallel platform runs them at once with the same
 * result), within a block the greedy levels of its pairs taken in (i, j) order (pairs of one level share no
 * particle, so a device runs a level at once).
 * Each update is the two-stage update of Lisal et al.: an explicit half (half the friction and half
 * the random impulse) followed by an implicit half solved exactly for the final relative velocity, i.e. a
 * Crank-Nicolson step of the pair's relative motion along e_ij, which keeps the stationary variance of the pair's
 * relative velocity exact for any dt. The kinetic energy the update removes from the pair goes, in equal halves,
 * into eps_i and eps_j, so each pair update conserves momentum and K + sum eps to rounding error. A pair update uses
 * the temperatures theta_i, theta_j that the particles have when the pair is reached (after the updates of earlier
 * pairs), for both sigma_ij and the conduction term: each pair update is then a self-contained exact-energy step of
 * the two-particle dynamics, whose equilibrium is the right one, rather than a step driven by stale temperatures.
 *
 * Random numbers are a pure function of (seed, step, i, j) (Philox4x32-10, a counter-based generator, with a
 * ziggurat for the normal variates), so a trajectory does not depend on how the pair list was built, and a run
 * continued from a checkpoint reproduces the uninterrupted run bit for bit.
 *
 * Modes. Isoenergetic is the full GenDPDE dynamics above. Isothermal is the classic DPD thermostat at the set
 * temperature (sigma^2 = 2 gamma k_B T, no internal energies, no conduction). Conservative is plain velocity
 * Verlet (no dissipation, no noise), the SPH-like limit. A term that is switched off costs nothing: no pair sweep
 * at all when gamma = 0 and kappa = 0 or in Conservative mode, no random numbers for the momentum when gamma = 0,
 * none for the heat flux when kappa = 0.
 *
 * A particle whose internal energy would become zero or negative stops the run with an OpenMMException naming the
 * particle and the step; the step is not applied, so the Context is left as it was before it. Reduce the step
 * size, or increase the heat capacity (the fluctuations of eps_i relative to its mean scale like sqrt(k_B/C_V)).
 *
 * Temperatures and internal energies. The bath temperature (setTemperature) and the particles' state eps_i are
 * separate. The particles' state belongs to the Context: it is set with setParticleTemperatures(),
 * setInternalEnergies() or setInternalEnergiesToTemperature() and travels with checkpoints and States
 * (getState(getIntegratorParameters=true), Simulation.saveState), never in the integrator's XML, which holds its
 * parameters (and the initial particle temperatures or internal energies configured before a Context existed).
 * When a Context is created, the particles start at the temperatures or internal energies given to
 * setParticleTemperatures() or setInternalEnergies() before (the later call wins), else at the bath temperature,
 * else they are not set and an Isoenergetic step refuses to run. Like every OpenMM integrator, one
 * GenDPDEIntegrator serves one Context.
 *
 * With a GenDPDEForce whose equation of state depends on temperature, the dynamics keep each particle's entropy (a
 * compressed particle heats up), and what every other call keeps of a particle's state is one rule
 * (docs/integrator.md, "The particles' thermal state: one rule"): temperatures set or loaded are those at the current
 * positions; a move from outside the dynamics (setting positions, a barostat's move) keeps each temperature, or each
 * entropy with setAdiabaticPositionChanges(true); a change of the force's parameters keeps each temperature; reading
 * changes nothing. Outside step(), getInternalEnergies() is C_V theta_i at the current positions.
 *
 * A step in which a particle would move farther than the pair range R (or by a non-finite amount), or in which a
 * force is not finite, is refused before anything changes, with an error naming the particle and the step: the
 * simulation has become unstable (reduce the step size). A run that fails so (or whose checkpoint the integrator
 * refused after OpenMM restored its part) stays stopped on every platform: step(), createCheckpoint() and
 * getState(getIntegratorParameters) raise, naming the failure, until a checkpoint or State saved before it is loaded;
 * positions that are not finite, or more than 1000 box lengths outside a periodic box, are refused when set
 * (docs/integrator.md, "Simulations that go bad").
 *
 * Particle types (docs/types.md). Every particle has a type, an integer (0 unless set). A particle's type is one
 * setting: set the types on the System's GenDPDEForce and the integrator takes them from it when the Context is
 * created (as it takes the pair range), or set them here (for a System whose GenDPDEForce treats every particle
 * alike, or that has none), or set the same types on both; types that differ for a particle are refused when the
 * Context is created, naming the particle. A type may have its own heat capacity (addTypeHeatCapacity()), and a
 * pair of types its own friction and heat conduction (addTypePair()); the others use the integrator's. A pair
 * update of particles of types a and b then uses gamma_ab, kappa_ab and theta_i = eps_i/C_V(a), theta_j =
 * eps_j/C_V(b), with the Ito term of the friction k_B (beta_i^2/C_i + beta_j^2/C_j)/(beta_i + beta_j)^2; the total
 * energy and momentum are conserved as before, and at equilibrium every particle's eps_i follows the Gamma law of
 * its own C_V (docs/types.md lists the identities).
 *
 * Parameters can be changed at any time and take effect at the next step, except the cutoff and the particle types,
 * which are read when the Context is created (or reinitialized): after that, a step is refused while the cutoff or a
 * particle's type differs from the Context's, and an entry naming a type no particle of the Context has is refused
 * when added (docs/types.md, "Changing types"). Their allowed ranges are listed in docs/integrator.md. Particles with
 * zero mass are not moved. Constraints and virtual sites are not supported (refused when the Context is created).
 */
class GenDPDEIntegrator : public OpenMM::Integrator {
public:
    /** Which physics a step includes. */
    enum Mode {
        /** Full GenDPDE: dissipation, noise, internal energies, heat conduction. */
        Isoenergetic = 0,
        /** Classic DPD thermostat at the set temperature; internal energies are not updated. */
        Isothermal = 1,
        /** Velocity Verlet only. */
        Conservative = 2
    };
    /**
     * Create a GenDPDEIntegrator.
     *
     * @param stepSize         the step size (in ps), > 0
     * @param friction         gamma (in amu/ps), >= 0
     * @param heatConduction   kappa (in kJ K/(mol ps)), >= 0
     * @param heatCapacity     C_V of each particle (in kJ/(mol K)), > 0
     */
    GenDPDEIntegrator(double stepSize, double friction, double heatConduction, double heatCapacity);
    /** Set the step size (in ps), > 0. */
    void setStepSize(double size) override;
    /** Get the friction gamma (in amu/ps). */
    double getFriction() const;
    /** Set the friction gamma (in amu/ps), >= 0. */
    void setFriction(double friction);
    /** Get the heat conduction kappa (in kJ K/(mol ps)). */
    double getHeatConduction() const;
    /** Set the heat conduction kappa (in kJ K/(mol ps)), >= 0. */
    void setHeatConduction(double heatConduction);
    /** Get the heat capacity C_V of each particle (in kJ/(mol K)). */
    double getHeatCapacity() const;
    /** Set the heat capacity C_V of each particle (in kJ/(mol K)), > 0. The internal energies are kept. */
    void setHeatCapacity(double heatCapacity);
    /** Get the cutoff R of the pair interactions (in nm); 0 means that of the System's GenDPDEForce. */
    double getCutoffDistance() const;
    /**
     * Set the cutoff R (in nm), >= 0; 0 takes that of the System's GenDPDEForce. Read when a Context is created: after
     * that a step is refused while it differs from the Context's (call Context.reinitialize() to apply it).
     */
    void setCutoffDistance(double distance);
    /**
     * Set the type of a particle: any integer (particles never given one have type 0). Read when a Context is
     * created; the particle index is checked against the System then.
     */
    void setParticleType(int index, int type);
    /** Get the type of a particle (0 if none was set). */
    int getParticleType(int index) const;
    /** The particles whose type was set, as particle -> type (every other particle has type 0). */
    const std::map<int, int>& getParticleTypes() const;
    /**
     * Give a type its own heat capacity C_V (in kJ/(mol K)), in the range of setHeatCapacity. Each type may appear
     * in one entry; the others use getHeatCapacity(). Like setHeatCapacity, a change keeps the internal energies.
     *
     * @return the index of the entry
     */
    int addTypeHeatCapacity(int type, double heatCapacity);
    /** The number of entries added with addTypeHeatCapacity(). */
    int getNumTypeHeatCapacities() const;
    /** Get an entry of addTypeHeatCapacity(): its type and C_V (in kJ/(mol K)). */
    void getTypeHeatCapacity(int index, int& type, double& heatCapacity) const;
    /** Change an entry of addTypeHeatCapacity(). */
    void setTypeHeatCapacity(int index, int type, double heatCapacity);
    /**
     * Give the pairs of particles of types type1 and type2 (in either order; type1 = type2 for like pairs) their own
     * friction gamma (in amu/ps, >= 0) and heat conduction kappa (in kJ K/(mol ps), >= 0); pairs of types without
     * an entry use getFriction() and getHeatConduction(). Each pair of types may appear in one entry.
     *
     * @return the index of the entry
     */
    int addTypePair(int type1, int type2, double friction, double heatConduction);
    /** The number of entries added with addTypePair(). */
    int getNumTypePairs() const;
    /** Get an entry of addTypePair(): its types, friction (amu/ps) and heat conduction (kJ K/(mol ps)). */
    void getTypePairParameters(int index, int& type1, int& type2, double& friction, double& heatConduction) const;
    /** Change an entry of addTypePair(). */
    void setTypePairParameters(int index, int type1, int type2, double friction, double heatConduction);
    /** Get the random number seed (0: a seed is chosen when the Context is created). */
    int getRandomNumberSeed() const;
    /** Set the random number seed; 0 chooses one when the Context is created. Read when a Context is created. */
    void setRandomNumberSeed(int seed);
    /** Get the mode. */
    Mode getMode() const;
    /** Set the mode (Isoenergetic, Isothermal or Conservative). */
    void setMode(Mode mode);
    /** Get the bath temperature (in K); 0 if none was set. */
    double getTemperature() const;
    /**
     * Set the bath temperature T (in K), in [1e-50, 1e50]: the temperature of the Isothermal mode's thermostat,
     * and the temperature at which every particle starts if no particle temperatures were set before the Context
     * was created. It never changes the internal energies of a Context that exists: to set those, call
     * setParticleTemperatures() or setInternalEnergiesToTemperature(). Takes effect at the next step.
     */
    void setTemperature(double temperature);
    /**
     * Set each particle's temperature theta_i (in K), each in [1e-50, 1e50], one per particle, i.e. eps_i = C_V
     * theta_i with the C_V of the particle's type. Before a Context exists: the initial condition, in place of any
     * internal energies set with setInternalEnergies() (its length is checked against the System when the Context
     * is created). Afterwards: the internal energies of the Context, now.
     */
    void setParticleTemperatures(const std::vector<double>& temperatures);
    /**
     * Set each particle's internal energy eps_i (in kJ/mol), each finite and in [1e-100, 1e100], one per particle:
     * the counterpart of getInternalEnergies(), and of setParticleTemperatures() for a state given as energies
     * (theta_i = eps_i/C_V). The values are kept exactly, whatever the heat capacities. Before a Context exists: the
     * initial condition, in place of any temperatures set with setParticleTemperatures() (its length is checked
     * against the System when the Context is created). Afterwards: the internal energies of the Context, now.
     */
    void setInternalEnergies(const std::vector<double>& energies);
    /**
     * Draw every particle's internal energy from its equilibrium distribution at temperature T (in K), > 0: the
     * Gamma law with shape C_V/k_B + 1 (C_V of the particle's type) and scale k_B T (docs/theory.md section 8), so that the harmonic mean of theta_i
     * is T and its mean T (1 + k_B/C_V). The counterpart of Context::setVelocitiesToTemperature() for the internal
     * energies; needs a Context. Setting every theta_i = T instead (setTemperature) leaves the internal energies
     * k_B T per particle short of equilibrium at T.
     *
     * @param temperature   T (in K)
     * @param randomSeed    the seed of the draw
     */
    void setInternalEnergiesToTemperature(double temperature, int randomSeed);
    /**
     * Each particle's temperature theta_i = eps_i/C_V (in K). Before a Context exists, those set with
     * setParticleTemperatures(), or the internal energies set with setInternalEnergies() over the C_V of the types
     * set on the integrator; if none were, the exception thrown says what the particles will start at (the bath
     * temperature, or nothing yet), since the number of particles is not known.
     */
    std::vector<double> getParticleTemperatures() const;
    /**
     * Each particle's internal energy eps_i (in kJ/mol). Before a Context exists, those set with
     * setInternalEnergies(), or the temperatures set with setParticleTemperatures() times the C_V of the types set
     * on the integrator; if neither was, as getParticleTemperatures().
     */
    std::vector<double> getInternalEnergies() const;
    /**
     * What a move of the particles from outside the dynamics keeps of each particle's thermal state, for the
     * GenDPDEForce laws that depend on temperature (docs/theory.md section 11, docs/integrator.md "The particles'
     * thermal state: one rule"). A move is Context::setPositions(), setState(), loadCheckpoint() (and the positions of
     * a refused checkpoint, which OpenMM restores before the integrator reads its part) and a barostat's accepted move.
     * false (the default): each particle keeps its temperature theta_i. true: each keeps its entropy, as the dynamics'
     * own motion does; a particle the move compresses heats up by
     * C_V theta' = C_V theta exp(-(sigma(n') - sigma(n))/C_V), e.g. for a quasi-static compression by small deformations of the box. The entropies are then fixed whenever the
     * temperatures are set (setInternalEnergies() and the like, a checkpoint or State, a change of the force's
     * parameters: each at the positions of that moment, or the first positions set), and turning this on fixes them at
     * the current positions. No effect on laws that do not depend on temperature, or in the Isothermal mode (the
     * particles' own state is then frozen).
     */
    void setAdiabaticPositionChanges(bool adiabatic);
    /** Whether setting the positions keeps the particles' entropies (see setAdiabaticPositionChanges()). */
    bool getAdiabaticPositionChanges() const;
    /**
     * The total energy K + U + sum_i eps_i (in kJ/mol) of the Context this integrator is bound to, with the on-step
     * kinetic energy and the potential energy of the integration force groups: the quantity the dynamics conserves.
     */
    double getConservedEnergy();
    /** Advance the simulation by a number of steps. */
    void step(int steps) override;
    /** The seed actually used by the Context (the chosen one if the seed is 0); throws if there is no Context. */
    int getSeedInUse() const;

protected:
    void initialize(OpenMM::ContextImpl& context) override;
    void cleanup() override;
    std::vector<std::string> getKernelNames() override;
    double computeKineticEnergy() override;
    bool kineticEnergyRequiresForce() const override { return true; }
    double getVelocityTimeOffset() const override { return 0.5 * getStepSize(); }
    void createCheckpoint(std::ostream& stream) const override;
    void loadCheckpoint(std::istream& stream) override;
    void serializeParameters(OpenMM::SerializationNode& node) const override;
    /**
     * The Context's state changed (positions, velocities, parameters, or a Force's parameters): the rule of the
     * particles' thermal state (applyThermalRule) for a position change or a change of the law.
     */
    void stateChanged(OpenMM::State::DataType changed) override;
    void deserializeParameters(const OpenMM::SerializationNode& node) override;

private:
    friend class GenDPDEIntegratorProxy; // serializes initialTemperatures and initialEnergies, the initial condition
    friend class GenDPDEIntegratorUtilities; // lends the kernel's thermal state to a GenDPDEForce's kernel
    // ---- The particles' thermal state with a law that depends on temperature (GenDPDEIntegratorThermalState.cpp;
    // docs/theory.md section 11, docs/integrator.md "The particles' thermal state: one rule"). Outside step(), every
    // particle's eps_i is C_V theta_i at the Context's current positions; with adiabatic position changes its entropy
    // is also kept (sigma_i of those positions), so that a move can keep it.
    /** What happened to the Context, for applyThermalRule(). */
    enum class ThermalEvent {
        EnergiesSet, // setInternalEnergies(), setParticleTemperatures(), ...ToTemperature(), checkpoints,
        // States
        PositionsSet, // Context.setPositions(), setState(), loadCheckpoint(), a refused checkpoint's
        // positions
        PositionsMovedByForce, // a Force's updateContextState() in step() (a barostat's move)
        LawChanged, // updateParametersInContext() of the GenDPDEForce whose laws depend on temperature
        AdiabaticChanged, // setAdiabaticPositionChanges()
        ModeChanged, // setMode()
        ParametersChanged // heat capacities, bath temperature: the forces change, the particles' state does not
    };
    /** Which positions the kernel's eps_i and sigma_i belong to. */
    enum class EntropyState {
        Unknown, // eps_i = C_V theta_i at the current positions, sigma_i not kept: the entropies are not fixed
        Current, // eps_i and sigma_i of the current positions
        Earlier // eps_i and sigma_i of earlier positions (inside step(), after its drift; or an evaluation failed)
    };
    /** The one rule: what each event does to the particles' thermal state (docs/integrator.md). */
    void applyThermalRule(ThermalEvent event);
    /**
     * Evaluate the integration groups at the current positions and keep the thermal state the GenDPDEForce found
     * there (entropies fixed at the current positions), if the positions and internal energies are set; a failed
     * evaluation leaves the state as it was (the next step reports it). The forces then serve the next step.
     */
    void settleThermalState();
    /**
     * The evaluation of a step: the integration groups' forces, and the thermal state of these positions kept. With
     * checkStep (the state was kept at the previous step's positions), a particle whose temperature the step's
     * motion changed by more than GENDPDE_STEP_TEMPERATURE_FACTOR stops the run (GenDPDEThermalState::checkStep).
     */
    void evaluateStepForces(bool checkStep);
    /** Whether the force array holds the forces of the current state (those of the last evaluation step() made). */
    bool forcesAreCurrent() const;
    /** The force array now holds the forces of the current state (after an evaluation of the integration groups). */
    void rememberForces();
    /**
     * After a step's failure: if a position is not finite, throw that, naming the particle and the step, in the same
     * words on every platform (the first check to see it may be OpenMM's own, which names neither).
     */
    void requireFinitePositions() const;
    // ---- A run that went bad (docs/integrator.md, "When a run goes bad"). The failure that stopped the run: the
    // message of a step() that failed, or of a checkpoint that was refused after OpenMM had restored its part; empty
    // if none. Until a checkpoint or a State with integrator parameters is loaded (or the Context is reinitialized
    // without its state), step() refuses to go on and no checkpoint or State of this state can be made, on every
    // platform alike: a move (setPositions() to the same positions) cannot clear it.
    std::string stoppedBy;
    /** Throw, naming the failure and the way on, if a failure stopped the run (what: what was asked). */
    void requireRunNotStopped(const std::string& what) const;
    /** Stop the run on this failure (a step's, or a refused checkpoint's); returns the message to throw. */
    std::string stopRun(const std::string& failure);
    // Positions set from outside that no step may start from (the message naming the first bad particle; empty if
    // none): a coordinate that is not finite, or, in a periodic box, one farther than maxBoxLengths box lengths from
    // the box, beyond which the platforms' periodic wrapping (double, mixed, single precision) no longer agrees.
    std::string refusedPositions;
    static constexpr double maxBoxLengths = 1000.0;
    /** Check the positions just set (Context.setPositions(), setState()); throw, and keep the refusal, if bad. */
    void checkSetPositions();
    // The pairs of particles that a Force without periodic boundary conditions bonds, in a periodic System (empty in
    // a non-periodic one): checkSetPositions() refuses positions that put such a pair more than half the box apart
    // along any box vector (a molecule split by wrapping), which the force would pull together across the box.
    struct NonPeriodicBond {
        int force, particle1, particle2; // the index of the Force in the System, and the pair
    };
    std::vector<NonPeriodicBond> nonPeriodicBonds;
    /** Collect nonPeriodicBonds: the pairs of the ForceImpls' getBondedParticles() and of angles and torsions. */
    void collectNonPeriodicBonds(OpenMM::ContextImpl& contextRef);
    /** Run steps (step()'s body between the energy guard's looks; a failure stops the run). */
    void runSteps(int steps, const GenDPDEStepTerms& terms, GenDPDEPairSource* pairSource);
    // ---- The energy guard (GenDPDEIntegratorEnergyGuard.cpp; docs/integrator.md, "Simulations that go bad"). In
    // the Isoenergetic and Conservative modes the conserved energy E = K + U + sum eps of the last mark is compared
    // with E every energyGuardSteps steps after it, however step() calls split them: a change of more than
    // energyGuardLimit of the energy the mode moves (K + sum eps, or K in the Conservative mode; the larger of the two
    // ends) stops the run. Every change of the Context from outside the dynamics, and a Force's move of the particles
    // (a barostat), sets the mark again, no sooner than energyGuardSteps steps after the last evaluation.
    struct EnergyParts {
        double kinetic = 0.0, potential = 0.0, internal = 0.0; // kJ/mol
    };
    struct EnergyMark {
        bool set = false;
        long long step = 0; // of the mark
        long long evaluated = LLONG_MIN / 2; // the step of the guard's last evaluation (none yet)
        double conserved = 0.0, moved = 0.0; // kJ/mol
    };
    static constexpr int energyGuardSteps = 100;
    static constexpr double energyGuardLimit = 0.1;
    EnergyMark energyMark;
    /** K, U of the integration force groups and sum eps now (an evaluation that changes nothing). */
    EnergyParts energyParts();
    /** The energy the mode moves (kJ/mol). */
    double movedEnergy(const EnergyParts& parts) const;
    /** The mark: these energies (an evaluation at the current step). */
    void markEnergy(const EnergyParts& parts);
    /** Whether energyGuardSteps steps have passed since the guard's last evaluation. */
    bool energyGuardMayEvaluate() const;
    /** At the start of step(): a mark where there is none and an evaluation is allowed. */
    void startEnergyGuard();
    /** How many of the remaining steps to run before the guard's next look or mark. */
    int energyGuardRun(int remaining) const;
    /** After a run: the look (compare with the mark, stop the run if E drifted, mark again) or a new mark. */
    void checkEnergyDrift();
    // The bound Context's GenDPDEForce whose laws depend on temperature (its Impl), or null if it has none.
    const GenDPDEForceImpl* thermalForce = nullptr;
    bool adiabaticPositionChanges = false;
    EntropyState entropyState = EntropyState::Unknown;
    bool positionsSet = false; // the bound Context's positions were set (its initial ones are not positions)
    bool checkingStepTemperatures = false; // inside evaluateStepForces(true)
    long long lawUpdatesSeen = 0; // thermalForce's parameter updates the rule has applied
    // The forces the last step() left (with a thermal force), reused by the next step() if nothing changed since.
    bool forcesCurrent = false;
    long long forcesEvaluation = 0; // thermalForce's evaluation count then
    OpenMM::Vec3 forcesBox[3];
    IntegrateGenDPDEStepKernel& boundKernel() const;
    /** Refuse what the integrator cannot run: constraints, virtual sites, negative or absurd masses. */
    void checkSystem(const OpenMM::System& system) const;
    /**
     * eps_i at Context creation: from initialTemperatures, else the bath temperature, else all zero (not set); types:
     * the particle types the Context will use.
     */
    std::vector<double> initialInternalEnergies(const OpenMM::System& system, const std::map<int, int>& types) const;
    /** C_V of each particle of the System (kJ/(mol K)), from these particle types and the heat capacities now. */
    std::vector<double> particleHeatCapacities(const OpenMM::System& system, const std::map<int, int>& types) const;
    /**
     * Before a Context: C_V of particles 0 .. numParticles - 1 (and of every particle with a type set), from the
     * types set on the integrator and the heat capacities now.
     */
    std::vector<double> configuredHeatCapacities(int numParticles) const;
    void checkTypeHeatCapacity(int index, int type, double heatCapacity) const;
    void checkTypePair(int index, int type1, int type2, double friction, double heatConduction) const;
    /**
     * Read a checkpoint's integrator data (any version) and check all of it: the checksum, the end, the internal
     * energies (checkInternalEnergies), the sweep order's build (positions and box, nm; built: whether the checkpoint
     * holds one). Changes nothing; throws what is wrong.
     */
    void readCheckpoint(std::istream& stream, int& seed, std::vector<double>& energies,
                        std::vector<OpenMM::Vec3>& buildPositions, OpenMM::Vec3 buildBox[3], bool& built) const;
    /** Refuse a checkpoint's or State's internal energies unless they are a valid state for the bound Context. */
    void checkInternalEnergies(const std::vector<double>& energies, const std::string& source) const;
    void requireTemperatures() const;
    double friction, heatConduction, heatCapacity, cutoff, temperature;
    double pairRange = 0.0; // the range of the pair terms in the bound Context (nm); 0 if unknown
    double boundCutoff = 0.0; // the cutoff setting when the Context was created (a step refuses another)
    int randomSeed;
    Mode mode;
    // The per-particle state lives in the kernel once a Context exists (eps_i; all zero until set). Before that,
    // the configured initial condition: these internal energies (kJ/mol) or these temperatures (at most one of the
    // two is not empty), or, if both are empty, every particle at `temperature`.
    std::vector<double> initialEnergies;
    std::vector<double> initialTemperatures;
    std::map<int, int> particleTypes;
    std::map<int, int> contextParticleTypes; // the bound Context's types (GenDPDEIntegratorUtilities::particleTypes)
    std::vector<int> contextTypes; // the distinct types of the bound Context, ascending
    bool typesChangedWhileBound = false; // setParticleType() was called since then
    /** Refuse an entry naming a type that no particle of the bound Context has (it could never take effect). */
    void requireContextType(const std::string& entry, int type) const;
    /** Refuse a step if setParticleType() changed a type since the Context was created (docs/types.md). */
    void requireBoundTypes();
    struct TypeHeatCapacity {
        int type;
        double heatCapacity;
    };
    struct TypePair {
        int type1, type2;
        double friction, heatConduction;
    };
    std::vector<TypeHeatCapacity> typeHeatCapacities;
    std::vector<TypePair> typePairs;
    OpenMM::Kernel kernel;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_INTEGRATOR_H_*/
