/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_COUNTER_RANDOM_H_
#define GENDPDE_COUNTER_RANDOM_H_

/* Counter-based random numbers: every variate is a pure function of (seed, step, i, j), so noise does not depend on
 * the order in which pairs are processed, on threads, or on any generator state (nothing to checkpoint but the seed
 * and the step count).
 *
 * - Philox4x32-10 (Salmon, Moraes, Dror, Shaw, SC'11): 128-bit counter, 64-bit key, ten rounds of two 32x32->64
 *   multiplications; verified against the Random123 known-answer vectors in the tests.
 * - A stream for one pair at one step: counter = (i, j, step low, step high), key = (seed, block), where the block
 *   index grows when the first four 32-bit words are used up (rarely: only the ziggurat's rejections need more).
 * - Normal variates by the 256-layer ziggurat (Marsaglia and Tsang 2000), with the layer index and the uniform taken
 *   from disjoint bits of one 64-bit word as Doornik (2005) recommends, and the exact tail and wedge tests, so the
 *   variates are exactly normal up to the 2^-53 resolution of the uniforms. */

#include <cmath>
#include <cstdint>

namespace GenDPDEPlugin {
namespace CounterRandom {

/** One Philox4x32-10 block: four 32-bit words from a 128-bit counter and a 64-bit key. */
inline void philox4x32(const std::uint32_t counter[4], const std::uint32_t key[2], std::uint32_t output[4]) {
    const std::uint32_t multiplier0 = 0xD2511F53u, multiplier1 = 0xCD9E8D57u;
    const std::uint32_t weyl0 = 0x9E3779B9u, weyl1 = 0xBB67AE85u;
    std::uint32_t c0 = counter[0], c1 = counter[1], c2 = counter[2], c3 = counter[3];
    std::uint32_t k0 = key[0], k1 = key[1];
    for (int round = 0; round < 10; round++) {
        const std::uint64_t product0 = (std::uint64_t) multiplier0 * c0;
        const std::uint64_t product1 = (std::uint64_t) multiplier1 * c2;
        const std::uint32_t high0 = (std::uint32_t) (product0 >> 32), low0 = (std::uint32_t) product0;
        const std::uint32_t high1 = (std::uint32_t) (product1 >> 32), low1 = (std::uint32_t) product1;
        c0 = high1 ^ c1 ^ k0;
        c1 = low1;
        c2 = high0 ^ c3 ^ k1;
        c3 = low0;
        k0 += weyl0;
        k1 += weyl1;
    }
    output[0] = c0;
    output[1] = c1;
    output[2] = c2;
    output[3] = c3;
}

/** The ziggurat's layers: x[0] = V/f(R), x[1] = R, ..., x[256] = 0, with f(x) = exp(-x^2/2). */
struct ZigguratTable {
    double x[257], f[257], ratio[256];
    ZigguratTable() {
        const double tailStart = 3.6541528853610088;   // R: the layers close at the top for 256 layers
        const double layerArea = tailStart * std::exp(-0.5 * tailStart * tailStart)
                + std::sqrt(M_PI / 2.0) * std::erfc(tailStart / std::sqrt(2.0));
        x[0] = layerArea / std::exp(-0.5 * tailStart * tailStart);
        x[1] = tailStart;
        for (int i = 1; i < 255; i++)
            x[i + 1] = std::sqrt(-2.0 * std::log(layerArea / x[i] + std::exp(-0.5 * x[i] * x[i])));
        x[256] = 0.0;
        for (int i = 0; i <= 256; i++)
            f[i] = std::exp(-0.5 * x[i] * x[i]);
        for (int i = 0; i < 256; i++)
            ratio[i] = x[i + 1] / x[i];
    }
    static const ZigguratTable& get() {
        static const ZigguratTable table;
        return table;
    }
};

/**
 * A stream of random numbers: Philox blocks for one 128-bit counter and a seed, the block index in the key. The
 * counter says whose numbers they are (see PairStream, ParticleStream), so that distinct uses never share one.
 */
class Stream {
public:
    Stream(std::uint32_t seed, std::uint32_t c0, std::uint32_t c1, std::uint32_t c2, std::uint32_t c3) :
            counter{c0, c1, c2, c3}, key{seed, 0}, used(0) {
        philox4x32(counter, key, words);   // every stream is used at least once
        key[1]++;
    }
    Stream(const Stream&) = delete;
    /** 64 random bits. */
    std::uint64_t bits64() {
        if (used == 4) {
            philox4x32(counter, key, words);
            key[1]++;
            used = 0;
        }
        std::uint64_t result = ((std::uint64_t) words[used] << 32) | words[used + 1];
        used += 2;
        return result;
    }
    /** Uniform in (0, 1], 53 bits. */
    double uniformPositive() { return ((bits64() >> 11) + 1) * (1.0 / 9007199254740992.0); }
    /** A standard normal variate. */
    double normal() {
        const ZigguratTable& table = ZigguratTable::get();
        const std::uint64_t bits = bits64();
        const int layer = (int) (bits & 0xFF);
        const double u = 2.0 * ((bits >> 11) * (1.0 / 9007199254740992.0)) - 1.0;   // [-1, 1)
        if (std::abs(u) < table.ratio[layer])
            return u * table.x[layer];          // inside the layer's rectangle: 98.8% of draws
        return normalSlowPath(layer, u);
    }
    /**
     * A Gamma variate of the given shape >= 1 and scale 1, by Marsaglia and Tsang (2000): a transformed normal
     * variate accepted with an exact test (a squeeze first), so the variates follow the Gamma law exactly up to the
     * resolution of the uniforms; 1-2% of proposals are rejected for shape >= 2.
     */
    double gamma(double shape) {
        const double d = shape - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
        while (true) {
            const double x = normal();
            double v = 1.0 + c * x;
            if (v <= 0.0)
                continue;
            v = v * v * v;
            const double u = uniformPositive(), x2 = x * x;
            if (u < 1.0 - 0.0331 * x2 * x2 || std::log(u) < 0.5 * x2 + d * (1.0 - v + std::log(v)))
                return d * v;
        }
    }

private:
    /** The tail beyond R and the wedges, then new draws until one is accepted. */
    __attribute__((noinline)) double normalSlowPath(int layer, double u) {
        const ZigguratTable& table = ZigguratTable::get();
        while (true) {
            if (layer == 0) {
                // The tail beyond R (Marsaglia 1964): exponential proposals accepted against the normal density.
                double a, b;
                do {
                    a = -std::log(uniformPositive()) / table.x[1];
                    b = -std::log(uniformPositive());
                } while (2.0 * b <= a * a);
                return u < 0.0 ? -(table.x[1] + a) : table.x[1] + a;
            }
            // The wedge between the rectangle and the density.
            const double x = u * table.x[layer];
            const double height = table.f[layer] + uniformPositive() * (table.f[layer + 1] - table.f[layer]);
            if (height < std::exp(-0.5 * x * x))
                return x;
            const std::uint64_t bits = bits64();
            layer = (int) (bits & 0xFF);
            u = 2.0 * ((bits >> 11) * (1.0 / 9007199254740992.0)) - 1.0;
            if (std::abs(u) < table.ratio[layer])
                return u * table.x[layer];
        }
    }

private:
    std::uint32_t counter[4], key[2], words[4];
    int used;
};

/** The random numbers of one pair (i, j) at one step: counter (i, j, step). */
class PairStream : public Stream {
public:
    PairStream(std::uint32_t seed, std::uint64_t step, std::uint32_t i, std::uint32_t j) :
            Stream(seed, i, j, (std::uint32_t) step, (std::uint32_t) (step >> 32)) {}
};

/**
 * The random numbers of one particle i for a one-off draw (not tied to a step): counter (i, 2^32 - 1, 2^32 - 1,
 * 2^32 - 1), which no PairStream uses (it would need j = 2^32 - 1 and a step count of 2^64 - 1).
 */
class ParticleStream : public Stream {
public:
    ParticleStream(std::uint32_t seed, std::uint32_t i) : Stream(seed, i, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu) {}
};

} // namespace CounterRandom
} // namespace GenDPDEPlugin

#endif /*GENDPDE_COUNTER_RANDOM_H_*/
