/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_PARALLEL_FOR_H_
#define GENDPDE_PARALLEL_FOR_H_

/* Loops over index ranges on several threads (the CPU platform's "Threads"), for code whose result must not depend on
 * how the work is shared: the body writes only what its own range owns, so any assignment of ranges to threads gives
 * the same result. One thread runs the loop sequentially. The threads are the caller's ThreadTeam (ThreadTeam.h:
 * kept between loops; waiting threads spin briefly, then sleep). */

#include "internal/ThreadTeam.h"
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

namespace GenDPDEPlugin {

/**
 * Call body(begin, end) on consecutive ranges covering [0, count), `chunk` indices each (the last one shorter),
 * distributed dynamically over numThreads threads. An exception thrown by a body is rethrown here (the first one
 * caught); a caller that must report a deterministic error (e.g. the lowest failing particle) records failures in
 * its own arrays instead.
 *
 * Each thread runs its own copy of body. A body should capture by value the scalars and pointers its inner loop
 * reads: a reference capture reads the caller's stack, a cache line the calling thread (one of the team) keeps
 * writing, and that sharing halved the speed of two threads (measured; see docs/performance.md).
 */
template <class Body>
void parallelFor(int numThreads, int count, int chunk, Body body) {
    ThreadTeam* team = (numThreads < 2 || count <= chunk) ? nullptr : ThreadTeam::forCaller(numThreads);
    if (team == nullptr) {
        body(0, count);
        return;
    }
    struct Shared {
        Shared(const Body& body, int count, int chunk) : body(body), count(count), chunk(chunk) {}
        const Body& body;
        const int count, chunk;
        alignas(64) std::atomic<int> next{0};   // a cache line of its own: every thread writes it
        alignas(64) std::exception_ptr failure;
        std::mutex failureLock;
    } shared(body, count, chunk);
    ThreadTeam::Job job;
    job.data = &shared;
    job.work = [](void* data, int) {
        Shared& s = *static_cast<Shared*>(data);
        try {
            Body local = s.body;
            for (int begin = s.next.fetch_add(s.chunk); begin < s.count; begin = s.next.fetch_add(s.chunk))
                local(begin, std::min(s.count, begin + s.chunk));
        } catch (...) {
            std::lock_guard<std::mutex> guard(s.failureLock);
            if (!s.failure)
                s.failure = std::current_exception();
        }
    };
    team->run(job);
    if (shared.failure)
        std::rethrow_exception(shared.failure);
}

/** The number of ranges of `chunk` indices that cover [0, count). */
inline int numRanges(int count, int chunk) {
    return (count + chunk - 1) / chunk;
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARALLEL_FOR_H_*/
