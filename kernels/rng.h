/* Counter-based random numbers.
 *
 * Every random number is a pure function of (seed, pixel, sample, bounce,
 * dimension): no generator state lives in the path, any device and any
 * work-group size give the same numbers, and any split of the samples between
 * waves or devices sums to the same estimate. The host includes this file too,
 * so tests can reproduce the exact numbers a kernel used.
 *
 * The mixer is Chris Wellons' "lowbias32" integer hash (a bijection on 32-bit
 * words with low avalanche bias); chaining it over the key words decorrelates
 * neighbouring counters.
 *
 * Two samplers give these numbers, chosen by WP_SAMPLER (the host always
 * passes it, from IntegratorOptions::sampler; left undefined it is the
 * independent one, which the stage tests in tests/kernels model on the host):
 *   WP_SAMPLER_INDEPENDENT (0): every number a hash of its whole key
 *     (wp_independent_random below);
 *   WP_SAMPLER_SOBOL (1): the samples of a pixel stratified, Owen-scrambled
 *     Sobol points (sobol.h).
 */
#ifndef WP_RNG_H
#define WP_RNG_H

#include "wp_shared.h"

/* Dimensions used at each bounce; a bounce owns WP_DIMS_PER_BOUNCE of them. */
#define WP_DIM_JITTER_X 0u
#define WP_DIM_JITTER_Y 1u
#define WP_DIM_LIGHT_PICK 2u
#define WP_DIM_LIGHT_U 3u
#define WP_DIM_LIGHT_V 4u
#define WP_DIM_BSDF_U 5u
#define WP_DIM_BSDF_V 6u
#define WP_DIM_ROULETTE 7u
#define WP_DIMS_PER_BOUNCE 8u
/* Past the bounce's eight: the number with which a BSDF picks its lobe after
 * its direction's microfacet normal (bsdf/roughdielectric.h picks reflection
 * or transmission by the Fresnel reflectance there), drawn only by such a
 * BSDF, so that every other path draws exactly the numbers it did. */
#define WP_DIM_BSDF_LOBE 8u

/* The thin lens's point on the aperture (kernels/camera.h). The camera ray
 * has no dimension of its own left at bounce 0 (the first hit samples its
 * light, BSDF and roulette there), and only generate ever jitters, so the
 * lens takes the jitter pair of bounce 1, which nothing else reads: with the
 * Sobol sampler the pair is stratified like the pixel's, and images without a
 * lens draw exactly the numbers they did. */
#define WP_LENS_BOUNCE 1u
#define WP_DIM_LENS_U WP_DIM_JITTER_X
#define WP_DIM_LENS_V WP_DIM_JITTER_Y

static inline wp_uint wp_mix32(wp_uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static inline wp_uint wp_hash(wp_uint seed, wp_uint pixel, wp_uint sample, wp_uint counter) {
    wp_uint h = wp_mix32(seed + 0x9e3779b9u);
    h = wp_mix32(h ^ pixel);
    h = wp_mix32(h ^ sample);
    /* Counters of one bounce differ in their low bits only; a second round
     * decorrelates them (one round left a measurable chi-square excess in
     * the joint histogram of two dimensions, tests/kernels/test_sampling.cpp). */
    return wp_mix32(wp_mix32(h ^ counter));
}

/* A float uniform in [0, 1): the top 24 bits, so every value is exact. */
static inline wp_float wp_to_unit_float(wp_uint bits) {
    return (wp_float)(bits >> 8) * (1.0f / 16777216.0f);
}

/* A bounce's eight dimensions count up from bounce * 8; those past them
 * (WP_DIM_BSDF_LOBE) count down from the top of the counter's range, so that
 * they never take a number of the next bounce's eight (the thin lens reads
 * bounce 1's first pair, camera.h). */
static inline wp_float wp_independent_random(wp_uint seed, wp_uint pixel, wp_uint sample,
                                             wp_uint bounce, wp_uint dimension) {
    wp_uint counter = bounce * WP_DIMS_PER_BOUNCE + dimension;
    if (dimension >= WP_DIMS_PER_BOUNCE)
        counter = ~(counter - WP_DIMS_PER_BOUNCE);
    return wp_to_unit_float(wp_hash(seed, pixel, sample, counter));
}

#include "sobol.h"

#define WP_SAMPLER_INDEPENDENT 0
#define WP_SAMPLER_SOBOL 1
#ifndef WP_SAMPLER
#define WP_SAMPLER WP_SAMPLER_INDEPENDENT
#endif

/* Always inlined: PoCL's inliner left it a call (six in shade), which kept
 * the parts of the numbers a bounce shares (the pixel's hashes, a pair's
 * index scramble) from being computed once. */
static inline WP_ALWAYS_INLINE wp_float wp_random(wp_uint seed, wp_uint pixel, wp_uint sample,
                                                  wp_uint bounce, wp_uint dimension) {
#if WP_SAMPLER == WP_SAMPLER_SOBOL
    return wp_sobol_random(seed, pixel, sample, bounce, dimension);
#else
    return wp_independent_random(seed, pixel, sample, bounce, dimension);
#endif
}

#ifdef __OPENCL_VERSION__
#include "computed_here.h"

/* The eight numbers of one bounce as two float4s, pair p of the bounce
 * (sobol.h) in lane p: *first holds the pairs' coordinates 0 (jitter x,
 * light pick, light u, BSDF u), *second their coordinates 1 (jitter y,
 * roulette, light v, BSDF v); each is wp_random(seed, pixel, sample, bounce,
 * d) of its dimension d, bit for bit, computed together (with the Sobol
 * sampler as one chain of vector operations, wp_sobol_bounce_bits). The
 * Sobol numbers are computed where this is called (WP_COMPUTED_HERE: the
 * compiler would sink them to their first use), so that a caller can draw
 * them early and the processor overlap their latency with other work; the
 * independent sampler's are left to the compiler (pinned, its jitter pair
 * would be computed for callers that read none of it). */
static inline WP_ALWAYS_INLINE void wp_random_bounce_pairs(wp_uint seed, wp_uint pixel,
                                                           wp_uint sample, wp_uint bounce,
                                                           float4* first, float4* second) {
#if WP_SAMPLER == WP_SAMPLER_SOBOL
    uint4 a, b;
    wp_sobol_bounce_bits(seed, pixel, sample, bounce, &a, &b);
    /* wp_to_unit_float per lane: below 2^24, every value converts exactly */
    *first = convert_float4(a >> 8u) * (1.0f / 16777216.0f);
    *second = convert_float4(b >> 8u) * (1.0f / 16777216.0f);
    WP_COMPUTED_HERE(*first);
    WP_COMPUTED_HERE(*second);
#else
    *first = (float4)(wp_independent_random(seed, pixel, sample, bounce, WP_DIM_JITTER_X),
                      wp_independent_random(seed, pixel, sample, bounce, WP_DIM_LIGHT_PICK),
                      wp_independent_random(seed, pixel, sample, bounce, WP_DIM_LIGHT_U),
                      wp_independent_random(seed, pixel, sample, bounce, WP_DIM_BSDF_U));
    *second = (float4)(wp_independent_random(seed, pixel, sample, bounce, WP_DIM_JITTER_Y),
                       wp_independent_random(seed, pixel, sample, bounce, WP_DIM_ROULETTE),
                       wp_independent_random(seed, pixel, sample, bounce, WP_DIM_LIGHT_V),
                       wp_independent_random(seed, pixel, sample, bounce, WP_DIM_BSDF_V));
#endif
}

/* wp_random_bounce_pairs's numbers by dimension: numbers[d] = wp_random(seed,
 * pixel, sample, bounce, d) for d < WP_DIMS_PER_BOUNCE. */
static inline WP_ALWAYS_INLINE void wp_bounce_numbers(float4 first, float4 second,
                                                      float numbers[WP_DIMS_PER_BOUNCE]) {
    numbers[WP_DIM_JITTER_X] = first.x;
    numbers[WP_DIM_JITTER_Y] = second.x;
    numbers[WP_DIM_LIGHT_PICK] = first.y;
    numbers[WP_DIM_ROULETTE] = second.y;
    numbers[WP_DIM_LIGHT_U] = first.z;
    numbers[WP_DIM_LIGHT_V] = second.z;
    numbers[WP_DIM_BSDF_U] = first.w;
    numbers[WP_DIM_BSDF_V] = second.w;
}
#endif

#endif /* WP_RNG_H */
