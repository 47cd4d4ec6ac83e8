/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef COMMON_GENDPDE_PROFILER_H_
#define COMMON_GENDPDE_PROFILER_H_

#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeEvent.h"
#include "openmm/common/ComputeKernel.h"
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Where the device time goes, part by part, and what a step or evaluation costs in launches and host transfers.
 *
 * Every kernel launch of the plugin goes through launch(), every transfer between host and device made by a step or
 * an evaluation is counted with transfer(), and each step or evaluation with countStep(): these counters always run
 * (an integer each). When the environment variable GENDPDE_PROFILE is set (to anything but 0), each timed part also
 * waits for the device before and after (so the profile slows the run; every part's time is its kernels' time plus
 * one synchronisation), and the totals, the counters per step and the sweep's counters are printed to standard error
 * when the kernel that owns the profiler is destroyed (the Context is deleted). Unset, a timed part only runs.
 */
class CommonGenDPDEProfiler {
public:
    CommonGenDPDEProfiler(OpenMM::ComputeContext& cc, const std::string& owner) : cc(cc), owner(owner) {
        const char* setting = std::getenv("GENDPDE_PROFILE");
        enabled = (setting != nullptr && std::string(setting) != "0" && std::string(setting) != "");
    }
    ~CommonGenDPDEProfiler() {
        if (!enabled || (parts.empty() && steps == 0 && notes.empty()))
            return;
        std::fprintf(stderr, "GenDPDE %s, device time per part (GENDPDE_PROFILE): part, calls, total ms, us per call\n",
                     owner.c_str());
        for (const auto& part : parts)
            std::fprintf(stderr, "  %-28s %8ld %10.3f %10.2f\n", part.first.c_str(), part.second.calls,
                         1e3 * part.second.seconds, 1e6 * part.second.seconds / part.second.calls);
        if (steps > 0)
            std::fprintf(stderr,
                         "GenDPDE %s, counts: %ld calls (steps or evaluations), %.3f launches and %.4f host "
                         "transfers per call\n",
                         owner.c_str(), steps, launches / (double) steps, transfers / (double) steps);
        if (!levels.empty()) {
            int total = 0;
            std::fprintf(stderr,
                         "GenDPDE %s, sweep: %d blocks, most particles in a region %d, most pairs in a block "
                         "%d, blocks streamed %d; most levels of a block per colour:",
                         owner.c_str(), blocks, mostParticles, mostPairs, streamed);
            for (int count : levels) {
                std::fprintf(stderr, " %d", count);
                total += count;
            }
            std::fprintf(stderr, " (critical path %d levels)\n", total);
            std::fprintf(stderr, "GenDPDE %s, sweep order: %d builds in %ld steps (%.4f per step)\n", owner.c_str(),
                         builds, steps, steps > 0 ? builds / (double) steps : 0.0);
        }
        for (const std::string& line : notes)
            std::fprintf(stderr, "GenDPDE %s, %s\n", owner.c_str(), line.c_str());
    }
    bool isEnabled() const { return enabled; }
    /** A line for the profile (printed with the totals). */
    void note(const std::string& line) { notes.push_back(line); }
    /** Run body (which launches kernels) and, when profiling, add its device time to the part's total. */
    template <class Body>
    void time(const std::string& part, Body body) {
        if (!enabled) {
            body();
            return;
        }
        finish();
        const auto start = std::chrono::steady_clock::now();
        body();
        finish();
        Total& total = parts[part];
        total.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        total.calls++;
    }
    /** Launch a kernel (counted). */
    void launch(OpenMM::ComputeKernel& kernel, int threads, int blockSize = -1) {
        kernel->execute(threads, blockSize);
        launches++;
    }
    /** A launch made by OpenMM on the plugin's behalf (clearing a buffer). */
    void launched() { launches++; }
    /** A transfer between host and device made by a step or evaluation. */
    void transfer() { transfers++; }
    /** One more step (integrator) or evaluation (force). */
    void countStep() { steps++; }
    /** The sweep's counters, as the status words give them (builds: the orders built since the Context was made). */
    void setCounters(int mostParticles, int mostPairs, int streamed, const std::vector<int>& levels, int blocks,
                     int builds) {
        this->builds = builds;
        this->mostParticles = mostParticles;
        this->mostPairs = mostPairs;
        this->streamed = streamed;
        this->levels = levels;
        this->blocks = blocks;
    }

private:
    struct Total {
        double seconds = 0.0;
        long calls = 0;
    };
    void finish() {
        OpenMM::ComputeEvent event = cc.createEvent();
        event->enqueue();
        event->wait();
    }
    OpenMM::ComputeContext& cc;
    std::string owner;
    bool enabled;
    std::map<std::string, Total> parts;
    long steps = 0, launches = 0, transfers = 0;
    int mostParticles = 0, mostPairs = 0, streamed = 0, blocks = 0, builds = 0;
    std::vector<int> levels;
    std::vector<std::string> notes;
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_PROFILER_H_*/
