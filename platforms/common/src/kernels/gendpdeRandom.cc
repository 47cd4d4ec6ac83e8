/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* The counter-based random numbers of CounterRandom.h on the device: Philox4x32-10 keyed on (seed, step) and
 * counted by the original indices of a pair, so a pair's variates do not depend on the platform, the thread or the
 * order of the particles in memory; normal variates by the same ziggurat, whose tables come from the host
 * (CounterRandom::ZigguratTable). With GENDPDE_DOUBLE_RANDOM (the device has double precision) the variates are
 * those of the host to the last bit except in the rare slow path, where exp and log may differ by an ulp. */

#ifdef GENDPDE_DOUBLE_RANDOM
typedef double randomReal;
#else
typedef float randomReal;
#endif

typedef struct {
    unsigned int counter[4], key[2], words[4];
    int used;
} GenDPDEStream;

inline DEVICE void philox4x32(GenDPDEStream* s) {
    unsigned int c0 = s->counter[0], c1 = s->counter[1], c2 = s->counter[2], c3 = s->counter[3];
    unsigned int k0 = s->key[0], k1 = s->key[1];
    for (int round = 0; round < 10; round++) {
        const mm_ulong product0 = (mm_ulong) 0xD2511F53u*c0;
        const mm_ulong product1 = (mm_ulong) 0xCD9E8D57u*c2;
        c0 = ((unsigned int) (product1 >> 32)) ^ c1 ^ k0;
        c1 = (unsigned int) product1;
        c2 = ((unsigned int) (product0 >> 32)) ^ c3 ^ k1;
        c3 = (unsigned int) product0;
        k0 += 0x9E3779B9u;
        k1 += 0xBB67AE85u;
    }
    s->words[0] = c0;
    s->words[1] = c1;
    s->words[2] = c2;
    s->words[3] = c3;
}

/** CounterRandom::PairStream(seed, step, i, j). */
inline DEVICE void initPairStream(GenDPDEStream* s, unsigned int seed, unsigned int stepLow, unsigned int stepHigh,
                                  unsigned int i, unsigned int j) {
    s->counter[0] = i;
    s->counter[1] = j;
    s->counter[2] = stepLow;
    s->counter[3] = stepHigh;
    s->key[0] = seed;
    s->key[1] = 0;
    philox4x32(s);
    s->key[1]++;
    s->used = 0;
}

inline DEVICE mm_ulong randomBits64(GenDPDEStream* s) {
    if (s->used == 4) {
        philox4x32(s);
        s->key[1]++;
        s->used = 0;
    }
    mm_ulong result = (((mm_ulong) s->words[s->used]) << 32) | s->words[s->used + 1];
    s->used += 2;
    return result;
}

inline DEVICE randomReal uniformPositive(GenDPDEStream* s) {
    return ((randomReal) ((randomBits64(s) >> 11) + 1))*(randomReal) (1.0/9007199254740992.0);
}

/** A standard normal variate (CounterRandom::Stream::normal). */
DEVICE randomReal randomNormal(GenDPDEStream* s, GLOBAL const randomReal* RESTRICT zigguratX,
                               GLOBAL const randomReal* RESTRICT zigguratF, GLOBAL const randomReal* RESTRICT zigguratRatio) {
    mm_ulong bits = randomBits64(s);
    int layer = (int) (bits & 0xFF);
    randomReal u = 2*(((randomReal) (bits >> 11))*(randomReal) (1.0/9007199254740992.0)) - 1;
    if (fabs(u) < zigguratRatio[layer])
        return u*zigguratX[layer];
    while (true) {
        if (layer == 0) {
            randomReal a, b;
            do {
                a = -log(uniformPositive(s))/zigguratX[1];
                b = -log(uniformPositive(s));
            } while (2*b <= a*a);
            return u < 0 ? -(zigguratX[1] + a) : zigguratX[1] + a;
        }
        const randomReal x = u*zigguratX[layer];
        const randomReal height = zigguratF[layer] + uniformPositive(s)*(zigguratF[layer + 1] - zigguratF[layer]);
        if (height < exp(-(randomReal) 0.5*x*x))
            return x;
        bits = randomBits64(s);
        layer = (int) (bits & 0xFF);
        u = 2*(((randomReal) (bits >> 11))*(randomReal) (1.0/9007199254740992.0)) - 1;
        if (fabs(u) < zigguratRatio[layer])
            return u*zigguratX[layer];
    }
}

/**
 * The random stream of one pair of the sweep, with the ziggurat's tables: what the sweep's pair step
 * (GenDPDESweepPair.h, which follows this file in the sweep's program) draws its variates from.
 */
typedef struct {
    GenDPDEStream stream;
    GLOBAL const randomReal* zigguratX;
    GLOBAL const randomReal* zigguratF;
    GLOBAL const randomReal* zigguratRatio;
} GenDPDEPairRandom;
#define GENDPDE_PAIR_STREAM GenDPDEPairRandom
#define GENDPDE_PAIR_NORMAL(s) randomNormal(&(s)->stream, (s)->zigguratX, (s)->zigguratF, (s)->zigguratRatio)
