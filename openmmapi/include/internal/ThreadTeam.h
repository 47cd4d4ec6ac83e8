/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_THREAD_TEAM_H_
#define GENDPDE_THREAD_TEAM_H_

/* The threads of the CPU platform's parallel loops (internal/ParallelFor.h): a team of worker threads per calling
 * thread, kept between loops. A thread waiting for the next loop (a worker) or for the others to finish one (the
 * caller) spins for a bounded time, then sleeps on a condition variable. The spin makes the short loops of a step
 * (a sweep runs eight in a row, microseconds apart) start without a system call; the bound keeps a machine shared
 * with other jobs usable: an OpenMP team whose threads spun between loops for milliseconds made two simulations at
 * once 30x slower each on 2 cores (docs/performance.md, "Threads on a shared machine", measures both). */

#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace GenDPDEPlugin {

class ThreadTeam {
public:
    /** One parallel loop: work(data, thread) is called once on every thread of the team (thread 0: the caller). */
    struct Job {
        void (*work)(void* data, int thread) = nullptr;
        void* data = nullptr;
    };
    /**
     * The calling thread's team of numThreads - 1 workers (made on first use and kept until the thread ends), or
     * null if the caller is itself running a loop (a loop inside a loop runs on the thread that meets it).
     */
    static ThreadTeam* forCaller(int numThreads);
    /** Run job on the caller and every worker; return when all are done. work must not throw. */
    void run(const Job& job);
    /**
     * How long a waiting thread spins before it sleeps (microseconds): 20, or the developer setting
     * GENDPDE_THREAD_SPIN_US read when the first team is made. Chosen by measurement (docs/performance.md, "Threads
     * on a shared machine"): 20 us keeps a lone job's step as fast as OpenMP's spinning team; shorter spins slow it
     * (0: 1.6x), longer ones slow two jobs at once (200 us: 5.8x).
     */
    static int spinMicroseconds();
    ~ThreadTeam();

private:
    explicit ThreadTeam(int numWorkers);
    void workerLoop(int worker);
    template <class Ready>
    void await(Ready ready, std::condition_variable& wake);
    std::vector<std::thread> workers;
    std::mutex lock;
    std::condition_variable jobPosted, jobDone;
    std::atomic<unsigned> generation{0};   // incremented for each job posted
    std::atomic<int> remaining{0};         // workers still running the current job
    std::atomic<bool> stopping{false};
    Job job;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_THREAD_TEAM_H_*/
