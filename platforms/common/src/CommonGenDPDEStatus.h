/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_STATUS_H_
#define COMMON_GENDPDE_STATUS_H_

#include <map>
#include <string>

namespace GenDPDEPlugin {

/**
 * The integrator's status words on the device (ints), written by its kernels and read by the host once per run of
 * steps (CommonIntegrateGenDPDEStepKernel::finishSteps), so that a steady-state step never waits for the device.
 * Once a step fails, every later kernel of the run does nothing, so the state stays that of before the failing step;
 * the host then names the particle and the step. The same numbers reach the device code as STATUS_* defines
 * (defines()), so host and device read one layout.
 */
namespace DeviceStatus {
enum Word {
    Halted,           // 0 while the run goes on; else why it stopped (a Reason)
    HaltStep,         // the step, counted from the start of the run, at which it stopped
    Unstable,         // the smallest original index of a particle whose step was unstable (NoValue if none)
    FailedRank,       // the smallest sweep rank of a block whose sweep made an internal energy <= 0 (NoValue)
    ForceNonFinite,   // the force's error flags when it stopped for them (GenDPDEForce's device checks)
    ForceInvalid,
    Streamed,         // blocks swept by the streaming path since the Context was created (capacities exceeded)
    MostParticles,    // the most particles in a block's region, and
    MostPairs,        // the most pairs of a block, since the Context was created
    Builds,           // the sweep orders built since the Context was created
    Levels,           // 8 words: per colour, the most levels of a block in the last step (counters)
    Size = Levels + 8
};
enum Reason { Running = 0, HaltUnstable = 1, HaltSweep = 2, HaltForce = 3, HaltLevels = 4 };
/** "None yet" for the words set by an atomic minimum. */
const int NoValue = 0x7FFFFFFF;

/** The layout as device defines. */
inline std::map<std::string, std::string> defines() {
    return {{"STATUS_HALTED", std::to_string(Halted)},
            {"STATUS_HALT_STEP", std::to_string(HaltStep)},
            {"STATUS_UNSTABLE", std::to_string(Unstable)},
            {"STATUS_FAILED_RANK", std::to_string(FailedRank)},
            {"STATUS_FORCE_NON_FINITE", std::to_string(ForceNonFinite)},
            {"STATUS_FORCE_INVALID", std::to_string(ForceInvalid)},
            {"STATUS_STREAMED", std::to_string(Streamed)},
            {"STATUS_MOST_PARTICLES", std::to_string(MostParticles)},
            {"STATUS_MOST_PAIRS", std::to_string(MostPairs)},
            {"STATUS_BUILDS", std::to_string(Builds)},
            {"STATUS_LEVELS", std::to_string(Levels)},
            {"HALT_UNSTABLE", std::to_string(HaltUnstable)},
            {"HALT_SWEEP", std::to_string(HaltSweep)},
            {"HALT_FORCE", std::to_string(HaltForce)},
            {"HALT_LEVELS", std::to_string(HaltLevels)},
            {"NO_VALUE", std::to_string(NoValue)}};
}
} // namespace DeviceStatus

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_STATUS_H_*/
