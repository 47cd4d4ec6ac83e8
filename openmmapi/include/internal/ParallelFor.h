#ifndef GENDPDE_PARALLEL_FOR_H_
#define GENDPDE_PARALLEL_FOR_H_

/* Loops over index ranges on several threads (the CPU platform's "Threads"), for code whose result must not depend on
 * how the work is shared: the body writes only what its own range owns, so any assignment of ranges to threads gives
 * the same result. One thread runs the loop sequentially.
 *
 * The threads are an OpenMP team. Its threads wait for the next loop spinning for a while before they sleep, so the
 * short loops of a step (a sweep runs eight in a row) start in microseconds; OpenMM's ThreadPool wakes its threads
 * through a condition variable, measured at 35-45 us per loop on the 2-core development machine
 * (docs/performance.md). */

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
    if (numThreads < 2 || count <= chunk) {
        body(0, count);
        return;
    }
    struct alignas(64) Counter {   // a cache line of its own: every thread writes it
        std::atomic<int> next{0};
    } counter;
    std::exception_ptr failure;
    std::mutex failureLock;
    #pragma omp parallel num_threads(numThreads)
    {
        try {
            Body local = body;
            for (int begin = counter.next.fetch_add(chunk); begin < count; begin = counter.next.fetch_add(chunk))
                local(begin, std::min(count, begin + chunk));
        }
        catch (...) {
            std::lock_guard<std::mutex> guard(failureLock);
            if (!failure)
                failure = std::current_exception();
        }
    }
    if (failure)
        std::rethrow_exception(failure);
}

/** The number of ranges of `chunk` indices that cover [0, count). */
inline int numRanges(int count, int chunk) {
    return (count + chunk - 1)/chunk;
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_PARALLEL_FOR_H_*/
