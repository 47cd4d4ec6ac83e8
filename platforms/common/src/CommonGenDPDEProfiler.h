#ifndef COMMON_GENDPDE_PROFILER_H_
#define COMMON_GENDPDE_PROFILER_H_

#include "openmm/common/ComputeContext.h"
#include "openmm/common/ComputeEvent.h"
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

namespace GenDPDEPlugin {

/**
 * Where the device time goes, part by part, when the environment variable GENDPDE_PROFILE is set (to anything but
 * 0): each timed part waits for the device before and after (so the profile slows the run; every part's time is
 * its kernels' time plus one synchronisation), and the totals are printed to standard error when the kernel that
 * owns the profiler is destroyed (the Context is deleted). Unset, a timed part only runs its kernels.
 */
class CommonGenDPDEProfiler {
public:
    CommonGenDPDEProfiler(OpenMM::ComputeContext& cc, const std::string& owner) : cc(cc), owner(owner) {
        const char* setting = std::getenv("GENDPDE_PROFILE");
        enabled = (setting != nullptr && std::string(setting) != "0" && std::string(setting) != "");
    }
    ~CommonGenDPDEProfiler() {
        if (!enabled || parts.empty())
            return;
        std::fprintf(stderr, "GenDPDE %s, device time per part (GENDPDE_PROFILE): part, calls, total ms, us per call\n",
                     owner.c_str());
        for (const auto& part : parts)
            std::fprintf(stderr, "  %-28s %8ld %10.3f %10.2f\n", part.first.c_str(), part.second.calls,
                         1e3*part.second.seconds, 1e6*part.second.seconds/part.second.calls);
    }
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
};

} // namespace GenDPDEPlugin

#endif /*COMMON_GENDPDE_PROFILER_H_*/
