#ifndef GENDPDE_PARALLEL_FOR_H_
#define GENDPDE_PARALLEL_FOR_H_

/* Loops over index ranges on OpenMM's ThreadPool (the CPU platform's "Threads"), for code whose result must not
 * depend on how the work is shared: the body writes only what its own range owns, so any assignment of ranges to
 * threads gives the same result. Without a pool (or with one thread) the loop runs sequentially. */

#include "openmm/internal/ThreadPool.h"
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

namespace GenDPDEPlugin {

/**
 * Call body(begin, end) on consecutive ranges covering [0, count), `chunk` indices each (the last one shorter),
 * distributed dynamically over the pool's threads. An exception thrown by a body is rethrown here (the first one
 * caught); a caller that must report a deterministic error (e.g. the lowest failing particle) records failures in
 * its own arrays instead.
 */
template <class Body>
void parallelFor(OpenMM::ThreadPool* pool, int count, int chunk, Body body) {
    if (pool == nullptr || pool->getNumThreads() < 2 || count <= chunk) {
        body(0, count);
        return;
    }
    std::atomic<int> next(0);
    std::exception_ptr failure;
    std::mutex failureLock;
    pool->execute([&](OpenMM::ThreadPool&, int) {
        try {
            for (int begin = next.fetch_add(chunk); begin < count; begin = next.fetch_add(chunk))
                body(begin, std::min(count, begin + chunk));
        }
        catch (...) {
            std::lock_guard<std::mutex> guard(failureLock);
            if (!failure)
                failure = std::current_exception();
        }
    });
    pool->waitForThreads();
    if (failure)
        std::rethrow_exception(failure);
}

/** The number of ranges of `chunk` indices that cover [0, count). */
inline int numRanges(int count, int chunk) {
    return (count + chunk - 1)/chunk;
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARALLEL_FOR_H_*/
