/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_BUFFERS_H_
#define GENDPDE_BUFFERS_H_

/* Buffers whose size follows the pairs (a pair list, a sweep order, neighbour rows), kept from step to step so that a
 * step allocates nothing. */

#include <cstddef>
#include <vector>

namespace GenDPDEPlugin {

/** Fraction of its new size a buffer is given in spare capacity when it must grow. */
constexpr std::size_t bufferHeadroomDivisor = 16;

/**
 * Resize `buffer` to `size` elements, growing its capacity to size + size/16 when it must grow. std::vector::resize
 * grows to twice the old size when the new one is less, so a pair list that gained a few pairs after its first step
 * held twice the memory it needed (measured: the sweep order's arrays and the CPU platform's pair list, 2x at N =
 * 32,000); with this headroom a buffer holds at most 1/16 more than the largest size it has had, and the pair count's
 * step-to-step wander (a fraction of a percent) rarely makes it grow again.
 */
template <class T>
void resizeBuffer(std::vector<T>& buffer, std::size_t size) {
    if (size > buffer.capacity())
        buffer.reserve(size + size / bufferHeadroomDivisor);
    buffer.resize(size);
}

} // namespace GenDPDEPlugin

#endif /*GENDPDE_BUFFERS_H_*/
