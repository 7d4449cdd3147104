/* Owen-scrambled Sobol samples with hash-based scrambling (Burley 2020,
 * "Practical Hash-based Owen Scrambling", JCGT 9(4)).
 *
 * Like the independent sampler in rng.h, every number is a pure function of
 * (seed, pixel, sample, bounce, dimension), so any device split, wave split or
 * resume gives the same image. Unlike it, the samples of one pixel are
 * stratified: the dimensions of a bounce come in pairs, and the first 2^m
 * samples of a pair form a (0, m, 2)-net (every elementary interval of area
 * 2^-m, [a/2^j, (a+1)/2^j) x [b/2^(m-j), (b+1)/2^(m-j)), holds exactly one).
 * Near a light's edge, where a pixel's samples read either the light or the
 * wall beside it, this is worth an order of magnitude in error.
 *
 * Each pair takes the first two Sobol dimensions (a (0, 2)-sequence in base
 * 2: the van der Corput sequence and the Pascal-matrix dimension):
 *   1. the sample index is shuffled by a nested uniform (Owen) scramble of
 *      its bits, seeded per (seed, pixel, bounce, pair). The scramble maps
 *      indices 0 .. 2^m - 1 onto one aligned block of 2^m indices, so every
 *      power-of-two prefix of a pixel's samples stays a net, while different
 *      pairs, bounces and pixels walk the sequence in unrelated orders
 *      (Burley's "padding": without it all pairs would be the same points);
 *   2. each coordinate is Owen-scrambled with its own seed, which keeps the
 *      net and makes every point uniform in [0, 1)^2 on its own (so the
 *      estimate is unbiased).
 * The scramble is the Laine-Karras hash permutation with Burley's improved
 * constants, applied to the bit-reversed value: it flips each bit by a hash of
 * the bits above it, as an Owen scramble does.
 *
 * The pairs of a bounce: (jitter x, jitter y), (light pick, roulette),
 * (light u, light v), (bsdf u, bsdf v). Dimensions past WP_DIMS_PER_BOUNCE
 * (the BSDF's lobe number, WP_DIM_BSDF_LOBE) each get a pair of their own,
 * of which they take the first coordinate.
 *
 * rng.h includes this file and chooses it with WP_SAMPLER; include rng.h.
 */
#ifndef WP_SOBOL_H
#define WP_SOBOL_H

#ifndef WP_RNG_H
#error sobol.h belongs to rng.h, which brings it in
#endif

/* Which pair of the bounce a dimension belongs to, and which of its two
 * coordinates it is. */
static inline wp_uint wp_sobol_pair(wp_uint dimension) {
    if (dimension <= WP_DIM_JITTER_Y)
        return 0u;
    if (dimension == WP_DIM_LIGHT_PICK || dimension == WP_DIM_ROULETTE)
        return 1u;
    if (dimension <= WP_DIM_LIGHT_V)
        return 2u;
    if (dimension <= WP_DIM_BSDF_V)
        return 3u;
    return dimension - WP_DIMS_PER_BOUNCE + 4u;
}

static inline wp_uint wp_sobol_coordinate(wp_uint dimension) {
    return (dimension == WP_DIM_JITTER_Y || dimension == WP_DIM_LIGHT_V ||
            dimension == WP_DIM_BSDF_V || dimension == WP_DIM_ROULETTE)
               ? 1u
               : 0u;
}

/* Bit 0 to bit 31 and so on, without builtins (OpenCL C 1.2 has none). */
#if defined(__OPENCL_VERSION__) && defined(WP_BIT_REVERSAL_TABLE)
/* On Oclgrind only (the host sets WP_BIT_REVERSAL_TABLE there: it cannot run
 * llvm.bitreverse, the intrinsic clang makes of the swaps below), the bytes
 * are reversed through a table: the same bits. */
#define WP_REVERSED_2(n) n, n + 2 * 64, n + 1 * 64, n + 3 * 64
#define WP_REVERSED_4(n)                                                                           \
    WP_REVERSED_2(n), WP_REVERSED_2(n + 2 * 16), WP_REVERSED_2(n + 1 * 16),                        \
        WP_REVERSED_2(n + 3 * 16)
#define WP_REVERSED_6(n)                                                                           \
    WP_REVERSED_4(n), WP_REVERSED_4(n + 2 * 4), WP_REVERSED_4(n + 1 * 4), WP_REVERSED_4(n + 3 * 4)
__constant uchar wp_reversed_bytes[256] = {WP_REVERSED_6(0), WP_REVERSED_6(2), WP_REVERSED_6(1),
                                           WP_REVERSED_6(3)};
static inline wp_uint wp_reverse_bits(wp_uint x) {
    return ((wp_uint)wp_reversed_bytes[x & 255u] << 24) |
           ((wp_uint)wp_reversed_bytes[(x >> 8) & 255u] << 16) |
           ((wp_uint)wp_reversed_bytes[(x >> 16) & 255u] << 8) |
           (wp_uint)wp_reversed_bytes[x >> 24];
}
#else
static inline wp_uint wp_reverse_bits(wp_uint x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}
#endif

/* Laine and Karras' permutation with Burley's constants: adding the seed and
 * xoring in multiples by even constants changes each bit by a function of the
 * bits below it only, so it is a bijection, and on bit-reversed values it is
 * a (hashed) Owen scramble. */
static inline wp_uint wp_laine_karras_permutation(wp_uint x, wp_uint seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* A nested uniform scramble of x read as a binary fraction, most significant
 * bit first: each bit is flipped by a hash of the seed and the bits above it. */
static inline wp_uint wp_nested_uniform_scramble(wp_uint x, wp_uint seed) {
    return wp_reverse_bits(wp_laine_karras_permutation(wp_reverse_bits(x), seed));
}

/* The first two Sobol dimensions at an index, with their binary digits in
 * reverse order (bit j holds the digit of weight 2^-(j+1)), the order the
 * scramble works in. The first is the van der Corput sequence: reversed, the
 * index itself. The second has the generator matrix of Pascal's triangle mod
 * 2 (direction numbers v_1 = 1/2, v_{k+1} = v_k xor v_k / 2; Joe and Kuo's
 * second dimension, m = 1, 3, 5, 15, 17, 51, ...): digit j is the xor of the
 * index bits k with C(k, j) odd, that is (Lucas) with k's bits a superset of
 * j's. A superset sum over the five bits of j takes five shifts, not a loop
 * over the 32 bits of the index. */
static inline wp_uint wp_sobol_second_reversed(wp_uint index) {
    index ^= (index >> 1) & 0x55555555u;
    index ^= (index >> 2) & 0x33333333u;
    index ^= (index >> 4) & 0x0f0f0f0fu;
    index ^= (index >> 8) & 0x00ff00ffu;
    index ^= (index >> 16) & 0x0000ffffu;
    return index;
}

/* The two dimensions as 0.32 fixed-point fractions (for the tests). */
static inline wp_uint wp_sobol_first(wp_uint index) {
    return wp_reverse_bits(index);
}

static inline wp_uint wp_sobol_second(wp_uint index) {
    return wp_reverse_bits(wp_sobol_second_reversed(index));
}

/* The seed of one pair of one bounce of one pixel. */
static inline wp_uint wp_sobol_pair_seed(wp_uint seed, wp_uint pixel, wp_uint bounce,
                                         wp_uint pair) {
    wp_uint h = wp_mix32(seed ^ 0x5b0b01d5u);
    h = wp_mix32(h ^ pixel);
    h = wp_mix32(h ^ bounce);
    return wp_mix32(wp_mix32(h ^ pair));
}

/* The 32 bits of one coordinate of one sample. */
static inline wp_uint wp_sobol_bits(wp_uint seed, wp_uint pixel, wp_uint sample, wp_uint bounce,
                                    wp_uint dimension) {
    wp_uint pair_seed = wp_sobol_pair_seed(seed, pixel, bounce, wp_sobol_pair(dimension));
    wp_uint coordinate = wp_sobol_coordinate(dimension);
    wp_uint index = wp_nested_uniform_scramble(sample, wp_mix32(pair_seed ^ 0x3c6ef372u));
    wp_uint reversed = coordinate == 0u ? index : wp_sobol_second_reversed(index);
    wp_uint coordinate_seed = wp_mix32(pair_seed ^ (coordinate == 0u ? 0xa54ff53au : 0x510e527fu));
    /* wp_nested_uniform_scramble of the point, whose first reversal is undone
     * by taking its digits reversed already. */
    return wp_reverse_bits(wp_laine_karras_permutation(reversed, coordinate_seed));
}

static inline wp_float wp_sobol_random(wp_uint seed, wp_uint pixel, wp_uint sample, wp_uint bounce,
                                       wp_uint dimension) {
    return wp_to_unit_float(wp_sobol_bits(seed, pixel, sample, bounce, dimension));
}

#ifdef __OPENCL_VERSION__
/* The same bits for the four pairs of one bounce at once, pair p in lane p:
 * *first the coordinates 0 (jitter x, light pick, light u, BSDF u), *second
 * the coordinates 1 (jitter y, roulette, light v, BSDF v). A pair's number is
 * a serial chain of about a hundred integer operations, which for one pair at
 * a time the compiler leaves scalar; the four chains side by side take one
 * chain of 4-lane operations instead. Integer arithmetic: exactly
 * wp_sobol_bits's words. */
static inline uint4 wp_mix32_4(uint4 x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static inline uint4 wp_reverse_bits_4(uint4 x) {
#ifdef WP_BIT_REVERSAL_TABLE
    return (uint4)(wp_reverse_bits(x.x), wp_reverse_bits(x.y), wp_reverse_bits(x.z),
                   wp_reverse_bits(x.w));
#else
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
#endif
}

static inline uint4 wp_laine_karras_permutation_4(uint4 x, uint4 seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

static inline uint4 wp_sobol_second_reversed_4(uint4 index) {
    index ^= (index >> 1) & 0x55555555u;
    index ^= (index >> 2) & 0x33333333u;
    index ^= (index >> 4) & 0x0f0f0f0fu;
    index ^= (index >> 8) & 0x00ff00ffu;
    index ^= (index >> 16) & 0x0000ffffu;
    return index;
}

static inline void wp_sobol_bounce_bits(wp_uint seed, wp_uint pixel, wp_uint sample, wp_uint bounce,
                                        uint4* first, uint4* second) {
    /* wp_sobol_pair_seed, its last two rounds per pair */
    wp_uint h = wp_mix32(seed ^ 0x5b0b01d5u);
    h = wp_mix32(h ^ pixel);
    h = wp_mix32(h ^ bounce);
    uint4 pair_seed = wp_mix32_4(wp_mix32_4((uint4)(h) ^ (uint4)(0u, 1u, 2u, 3u)));
    /* wp_nested_uniform_scramble of the sample index, per pair */
    uint4 index = wp_reverse_bits_4(wp_laine_karras_permutation_4(
        (uint4)(wp_reverse_bits(sample)), wp_mix32_4(pair_seed ^ 0x3c6ef372u)));
    *first = wp_reverse_bits_4(
        wp_laine_karras_permutation_4(index, wp_mix32_4(pair_seed ^ 0xa54ff53au)));
    *second = wp_reverse_bits_4(wp_laine_karras_permutation_4(wp_sobol_second_reversed_4(index),
                                                              wp_mix32_4(pair_seed ^ 0x510e527fu)));
}
#endif

#endif /* WP_SOBOL_H */
