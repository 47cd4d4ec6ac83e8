/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* parallelFor and its ThreadTeam (internal/ParallelFor.h, internal/ThreadTeam.h), the threads of the CPU platform:
 * every index exactly once at any thread count and chunk; a loop inside a loop; an exception reaches the caller and
 * the team goes on; two calling threads at once; a child process of fork(); and threads that wait for the next loop
 * sleep instead of spinning once the bounded spin is over. */

#include "TestUtilities.h"
#include "internal/ParallelFor.h"
#include <atomic>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

/** Every index of [0, count) is visited exactly once, for several thread counts, chunks and counts. */
void testEveryIndexOnce() {
    for (int threads : {1, 2, 3, 8})
        for (int chunk : {1, 7, 1000})
            for (int count : {0, 1, 999, 20000}) {
                std::vector<std::atomic<int>> visits(count);
                parallelFor(threads, count, chunk, [&visits](int begin, int end) {
                    for (int i = begin; i < end; i++)
                        visits[i]++;
                });
                for (int i = 0; i < count; i++)
                    ASSERT_EQUAL(1, visits[i].load());
            }
}

/** A loop inside a loop runs (on the thread that meets it) and covers its range. */
void testNestedLoops() {
    std::vector<std::atomic<int>> visits(64 * 100);
    parallelFor(4, 64, 1, [&visits](int begin, int end) {
        for (int outer = begin; outer < end; outer++)
            parallelFor(4, 100, 10, [&visits, outer](int b, int e) {
                for (int inner = b; inner < e; inner++)
                    visits[outer * 100 + inner]++;
            });
    });
    for (auto& v : visits)
        ASSERT_EQUAL(1, v.load());
}

/** An exception thrown by a body reaches the caller; the team runs the next loop. */
void testExceptions() {
    bool caught = false;
    try {
        parallelFor(3, 1000, 1, [](int begin, int end) {
            if (begin <= 500 && 500 < end)
                throw std::runtime_error("range with 500");
        });
    } catch (const std::runtime_error& e) {
        caught = std::string(e.what()) == "range with 500";
    }
    ASSERT(caught);
    std::atomic<int> sum{0};
    parallelFor(3, 1000, 1, [&sum](int begin, int end) { sum += end - begin; });
    ASSERT_EQUAL(1000, sum.load());
}

/** Two calling threads each run loops at once (each has its own team). */
void testTwoCallers() {
    std::atomic<long long> total{0};
    auto caller = [&total]() {
        for (int repeat = 0; repeat < 200; repeat++)
            parallelFor(2, 1000, 10, [&total](int begin, int end) { total += end - begin; });
    };
    std::thread a(caller), b(caller);
    a.join();
    b.join();
    ASSERT_EQUAL(2LL * 200 * 1000, total.load());
}

/** A child process of fork() (multiprocessing does this) runs loops: its teams are made anew. */
void testFork() {
    parallelFor(2, 100, 1, [](int, int) {});   // the parent has a team
    const pid_t child = fork();
    if (child == 0) {
        alarm(20);   // a child that hangs is killed, and fails
        std::atomic<int> sum{0};
        parallelFor(2, 100, 1, [&sum](int begin, int end) { sum += end - begin; });
        _exit(sum.load() == 100 ? 0 : 1);
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

double processCpuSeconds() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/**
 * Between loops the workers spin for ThreadTeam::spinMicroseconds() (20 us), then sleep: over 300 ms without loops a
 * team of 3 workers uses about 3 x 20 us of processor time. The bound, 30 ms, allows for the processor time of
 * waking and of scheduling noise; workers that kept spinning would use up to 3 x 300 ms.
 */
void testIdleWorkersSleep() {
    for (int repeat = 0; repeat < 10; repeat++)
        parallelFor(4, 4000, 10, [](int, int) {});
    std::this_thread::sleep_for(std::chrono::milliseconds(5));   // past any spin
    const double start = processCpuSeconds();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const double used = processCpuSeconds() - start;
    if (!(used < 0.030))
        throw std::runtime_error("idle workers used " + std::to_string(1e3 * used) + " ms of processor time in 300 ms");
}

int main() {
    return runTestProgram([]() {
        testEveryIndexOnce();
        testNestedLoops();
        testExceptions();
        testTwoCallers();
        testFork();
        testIdleWorkersSleep();
    });
}
