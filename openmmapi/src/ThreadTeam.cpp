/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#include "internal/ThreadTeam.h"
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>
#include <pthread.h>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

using namespace GenDPDEPlugin;

namespace {

/** A hint to the processor that this thread is spinning (frees the core's resources for its sibling). */
inline void spinPause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

std::atomic<unsigned> forkCount{0};   // fork() leaves a child process without the workers of its teams

thread_local bool insideLoop = false;   // this thread is a worker, or a caller running a loop

/** The teams of this thread, by number of workers (two Contexts with different Threads each keep their own). */
struct CallerTeams {
    std::map<int, std::unique_ptr<ThreadTeam>> byWorkers;
    unsigned forks = 0;
};
thread_local CallerTeams callerTeams;

} // namespace

int ThreadTeam::spinMicroseconds() {
    static const int spin = []() {
        const char* setting = std::getenv("GENDPDE_THREAD_SPIN_US");
        return setting != nullptr ? std::max(0, std::atoi(setting)) : 20;
    }();
    return spin;
}

ThreadTeam* ThreadTeam::forCaller(int numThreads) {
    if (insideLoop)
        return nullptr;
    static std::once_flag atFork;
    std::call_once(atFork, []() { pthread_atfork(nullptr, nullptr, []() { forkCount++; }); });
    CallerTeams& teams = callerTeams;
    if (teams.forks != forkCount.load()) {
        // In a child of fork(): the teams' threads do not exist here, so they can be neither used nor joined.
        for (auto& team : teams.byWorkers)
            team.second.release();
        teams.byWorkers.clear();
        teams.forks = forkCount.load();
    }
    std::unique_ptr<ThreadTeam>& team = teams.byWorkers[numThreads - 1];
    if (team == nullptr)
        team.reset(new ThreadTeam(numThreads - 1));
    return team.get();
}

ThreadTeam::ThreadTeam(int numWorkers) {
    for (int worker = 0; worker < numWorkers; worker++)
        workers.emplace_back(&ThreadTeam::workerLoop, this, worker);
}

ThreadTeam::~ThreadTeam() {
    stopping.store(true, std::memory_order_relaxed);
    generation.fetch_add(1, std::memory_order_release);
    {
        std::lock_guard<std::mutex> guard(lock);   // see await()
    }
    jobPosted.notify_all();
    for (std::thread& worker : workers)
        worker.join();
}

template <class Ready>
void ThreadTeam::await(Ready ready, std::condition_variable& wake) {
    if (ready())
        return;
    const int spin = spinMicroseconds();
    if (spin > 0) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::microseconds(spin);
        for (int k = 1;; k++) {
            spinPause();
            if (ready())
                return;
            if (k % 64 == 0 && std::chrono::steady_clock::now() >= deadline)
                break;
        }
    }
    // Sleep. A thread that makes ready() true changes it before taking the lock to notify, so it cannot notify
    // between this thread's last look and its wait.
    std::unique_lock<std::mutex> guard(lock);
    wake.wait(guard, ready);
}

void ThreadTeam::run(const Job& next) {
    job = next;
    remaining.store((int) workers.size(), std::memory_order_relaxed);
    generation.fetch_add(1, std::memory_order_release);
    {
        std::lock_guard<std::mutex> guard(lock);   // see await()
    }
    jobPosted.notify_all();
    insideLoop = true;
    job.work(job.data, 0);
    insideLoop = false;
    await([this]() { return remaining.load(std::memory_order_acquire) == 0; }, jobDone);
}

void ThreadTeam::workerLoop(int worker) {
    insideLoop = true;
    unsigned seen = 0;
    while (true) {
        await([&]() { return generation.load(std::memory_order_acquire) != seen; }, jobPosted);
        seen = generation.load(std::memory_order_acquire);
        if (stopping.load(std::memory_order_relaxed))
            return;
        job.work(job.data, worker + 1);
        if (remaining.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            {
                std::lock_guard<std::mutex> guard(lock);   // see await()
            }
            jobDone.notify_one();
        }
    }
}
