/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_FIXED_ORDER_SUM_H_
#define GENDPDE_FIXED_ORDER_SUM_H_

/* Sums whose rounding does not depend on how the work is shared among threads: the terms are summed left to right
 * in chunks of a fixed size, and the chunk sums left to right. A sequential platform and a parallel one (each chunk
 * summed by one thread, the chunk sums combined in chunk order) then give the same bits for the energy and the
 * virial. */

#include "internal/ParallelFor.h"
#include <algorithm>
#include <vector>

namespace GenDPDEPlugin {
namespace FixedOrderSum {

/** Terms per chunk. */
constexpr int chunkSize = 1024;

/** The number of chunks for count terms. */
inline int numChunks(int count) {
    return (count + chunkSize - 1) / chunkSize;
}

/** Accumulates terms one by one in the fixed order (the sequential form). */
class Accumulator {
public:
    void add(double term) {
        partial += term;
        if (++inChunk == chunkSize) {
            total += partial;
            partial = 0.0;
            inChunk = 0;
        }
    }
    double sum() const { return inChunk == 0 ? total : total + partial; }

private:
    double total = 0.0, partial = 0.0;
    int inChunk = 0;
};

/** The total of chunk sums computed separately (the parallel form): the same bits as Accumulator. */
inline double combine(const std::vector<double>& chunkSums) {
    double total = 0.0;
    for (double s : chunkSums)
        total += s;
    return total;
}

/**
 * sum_i term(i) over [0, count) in the fixed order, the chunks summed on numThreads threads (the parallel form;
 * chunkSums is the caller's scratch). term must be safe to call from several threads at once.
 */
template <class Term>
double parallelSum(int numThreads, int count, Term term, std::vector<double>& chunkSums) {
    const int chunks = numChunks(count);
    chunkSums.assign(chunks, 0.0);
    double* sums = chunkSums.data();
    parallelFor(numThreads, chunks, 1, [=](int chunkBegin, int chunkEnd) {
        for (int c = chunkBegin; c < chunkEnd; c++) {
            double partial = 0.0;
            const int last = std::min(count, (c + 1) * chunkSize);
            for (int i = c * chunkSize; i < last; i++)
                partial += term(i);
            sums[c] = partial;
        }
    });
    return combine(chunkSums);
}

} // namespace FixedOrderSum
} // namespace GenDPDEPlugin

#endif /*GENDPDE_FIXED_ORDER_SUM_H_*/
