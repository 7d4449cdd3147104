/* Mitsuba 3's `envmap` emitter: radiance arriving from every direction, read
 * from an equirectangular (latitude-longitude) image, docs/lights-and-camera.md.
 *
 * The image's conventions are Mitsuba 3.9.1's, measured with its Python API
 * (tests/kernels/test_envmap.cpp holds them): a world direction d is turned
 * into the map's frame by the inverse of the emitter's to_world (the rows
 * to_local), l = to_local d, then
 *     u = atan2(l.x, -l.z) / 2 pi  (wrapped into [0, 1)),  v = acos(l.y) / pi,
 * so +y is up (v = 0 is the image's top row) and -z is the image's left edge.
 * Columns are texel-centred and periodic in u: column i lies at
 * u = (i + 1/2) / width, and u = 0 blends the last column with the first.
 * Rows are corner-aligned in v: row j lies at v = j / (height - 1), the first
 * row at the zenith, the last at the nadir. Radiance is the bilinear blend of
 * the four texels around (x, y) = (u width - 1/2, v (height - 1)), times the
 * emitter's scale (radiance.xyz). The host pads images narrower than 2 or
 * lower than 3 texels to that size by repeating the last column or row, as
 * Mitsuba does, so every map here has width >= 2, height >= 3.
 *
 * Sampling (ours, not Mitsuba's): the map is width x (height - 1) bilinear
 * patches, patch (i, j) between columns i, i + 1 (modulo the width) and rows
 * j, j + 1. Each is chosen with probability proportional to its mean
 * luminance (the mean of its four corners', which is positive wherever the
 * radiance in the patch is) times its solid angle, then a direction uniformly
 * in the patch's solid angle: phi uniform, cos theta uniform. So the density
 * of a direction is P(patch) / solid angle(patch), finite at the poles, and
 * exactly what the escape's multiple importance sampling weight uses. The
 * tables (the host builds them, src/render/environment_tables.cpp) are
 * cumulative sums at environment_cdf[cdf_first]: first the height - 1 rows'
 * (the marginal), then for each row its width patches' (the conditional),
 * each table ending in 1; after them come each row's two cosines
 * (wp_envmap_row_geometry). A patch's probability is the difference of two
 * neighbouring entries, in both the sampler and the density, so the two agree
 * to the float even for patches far below the entries' rounding.
 */
#ifndef WP_LIGHTS_ENVMAP_H
#define WP_LIGHTS_ENVMAP_H

#include "sampling.h"
#include "wp_shared.h"

/* The bilinear patch a direction falls in, and where in it: columns *i and
 * *i + 1 (modulo the width) with the second's weight *ax, rows *j and *j + 1
 * with the second's weight *ay. */
static inline void wp_envmap_patch(__global const WpEmitter* e, float3 d, int* i, int* j, float* ax,
                                   float* ay) {
    float3 l = (float3)(dot(e->to_local[0].xyz, d), dot(e->to_local[1].xyz, d),
                        dot(e->to_local[2].xyz, d));
    float u = wp_atan2(l.x, -l.z) * (0.5f / WP_PI); /* atan2's, without its library call */
    u -= floor(u); /* [-1/2, 1/2) to [0, 1); a NaN stays a NaN, caught below */
    /* v = acos(l.y) / pi, as an angle from its sine and cosine: wp_atan2 is
     * inline, where PoCL's acos is a call, and the angle stays accurate at the
     * poles, where acos loses digits. */
    float v = wp_atan2(sqrt(l.x * l.x + l.z * l.z), l.y) * (1.0f / WP_PI);
    int w = (int)e->width, h = (int)e->height;
    float x = u * (float)w - 0.5f; /* [-1/2, w - 1/2]: left of column 0 wraps to w - 1 */
    float x_floor = floor(x);
    int x0 = (int)clamp(x_floor, -1.0f, (float)(w - 1));
    *ax = clamp(x - x_floor, 0.0f, 1.0f);
    *i = x0 < 0 ? w - 1 : x0;
    float y = clamp(v, 0.0f, 1.0f) * (float)(h - 1);
    float y_floor = fmin(floor(y), (float)(h - 2)); /* the nadir belongs to the last patch */
    *j = (int)y_floor;
    *ay = clamp(y - y_floor, 0.0f, 1.0f);
}

/* Texel (x, y) of the map, linear RGB. */
static inline float3 wp_envmap_texel(__global const wp_uint* texels, __global const WpEmitter* e,
                                     int x, int y) {
    __global const wp_uint* p =
        texels + e->texels_first + 3u * ((wp_uint)y * e->width + (wp_uint)x);
    return (float3)(as_float(p[0]), as_float(p[1]), as_float(p[2]));
}

/* The radiance in patch (i, j) at the weights (ax, ay) (wp_envmap_patch). */
static inline float3 wp_envmap_patch_radiance(__global const wp_uint* texels,
                                              __global const WpEmitter* e, int i, int j, float ax,
                                              float ay) {
    int i1 = i + 1 == (int)e->width ? 0 : i + 1;
    float3 top =
        (1.0f - ax) * wp_envmap_texel(texels, e, i, j) + ax * wp_envmap_texel(texels, e, i1, j);
    float3 bottom = (1.0f - ax) * wp_envmap_texel(texels, e, i, j + 1) +
                    ax * wp_envmap_texel(texels, e, i1, j + 1);
    return ((1.0f - ay) * top + ay * bottom) * e->radiance.xyz;
}

/* The radiance arriving along -d, that is seen looking in direction d (unit). */
static inline float3 wp_envmap_radiance(__global const wp_uint* texels, __global const WpEmitter* e,
                                        float3 d) {
    int i, j;
    float ax, ay;
    wp_envmap_patch(e, d, &i, &j, &ax, &ay);
    return wp_envmap_patch_radiance(texels, e, i, j, ax, ay);
}

/* Row j's geometry, from the host's table after the sampling tables
 * (src/render/environment_tables.cpp, in double precision): .x is
 * cos(theta_j) and .y cos(theta_j) - cos(theta_{j+1}) for the row boundaries
 * theta_j = pi j / rows, the difference as 2 sin(mid) sin(half width) (the
 * plain difference of two cosines near 1 loses every digit at the poles of a
 * large map). Read, not computed: two polynomials, their divisions and a
 * call were 8 % of the showcase's shade (docs/performance.md, "Shade, cut
 * further"). */
static inline float2 wp_envmap_row_geometry(__global const float* environment_cdf,
                                            __global const WpEmitter* e, wp_uint j) {
    wp_uint rows = e->height - 1u;
    __global const float* row = environment_cdf + e->cdf_first + rows + rows * e->width + 2u * j;
    return (float2)(row[0], row[1]);
}

/* The probability of patch (i, j) (the product of two table differences). */
static inline float wp_envmap_patch_probability(__global const float* environment_cdf,
                                                __global const WpEmitter* e, int i, int j) {
    __global const float* marginal = environment_cdf + e->cdf_first;
    __global const float* row = marginal + (e->height - 1u) + (wp_uint)j * e->width;
    float p_row = marginal[j] - (j > 0 ? marginal[j - 1] : 0.0f);
    float p_column = row[i] - (i > 0 ? row[i - 1] : 0.0f);
    return p_row * p_column;
}

/* The solid-angle density of any direction in patch (i, j) (uniform within it). */
static inline float wp_envmap_patch_pdf(__global const float* environment_cdf,
                                        __global const WpEmitter* e, int i, int j) {
    float solid_angle =
        (2.0f * WP_PI / (float)e->width) * wp_envmap_row_geometry(environment_cdf, e, (wp_uint)j).y;
    return wp_envmap_patch_probability(environment_cdf, e, i, j) / solid_angle;
}

/* The solid-angle density with which wp_envmap_sample picks direction d. */
static inline float wp_envmap_pdf(__global const float* environment_cdf,
                                  __global const WpEmitter* e, float3 d) {
    int i, j;
    float ax, ay;
    wp_envmap_patch(e, d, &i, &j, &ax, &ay);
    return wp_envmap_patch_pdf(environment_cdf, e, i, j);
}

/* The first of n cumulative entries that exceeds u (n - 1 if none does:
 * rounding may leave u at or above the last, 1). A binary search narrows it
 * to at most WP_ENVMAP_SEARCH_SPAN entries, which are then counted: since
 * the entries never decrease, the answer is low plus how many of
 * [low, high) are at most u, a loop without a branch on the data that the
 * compiler vectorises (the binary search's last, unpredictable steps were
 * most of its 8 % of the showcase's shade, docs/performance.md). */
#define WP_ENVMAP_SEARCH_SPAN 32u
static inline wp_uint wp_envmap_search(__global const float* cdf, wp_uint n, float u) {
    wp_uint low = 0u, high = n - 1u;
    while (high - low > WP_ENVMAP_SEARCH_SPAN) {
        wp_uint mid = (low + high) / 2u;
        if (cdf[mid] > u)
            high = mid;
        else
            low = mid + 1u;
    }
    wp_uint at_most_u = 0u;
    for (wp_uint k = low; k < high; ++k)
        at_most_u += cdf[k] <= u ? 1u : 0u;
    return low + at_most_u;
}

/* Picks a direction by the tables from the numbers (u, v) in [0, 1): *d the
 * unit world direction, *pdf its solid-angle density (wp_envmap_pdf's), and
 * *radiance the map's radiance along it (wp_envmap_radiance's), blended in
 * the patch the numbers chose at the place they chose: the column weight is
 * the sample's own s, and no atan2 of *d is needed (it was about 9 % of
 * the showcase's shade). Up to rounding it is the lookup of *d; a direction
 * within rounding of a patch's edge may read the neighbour's side of the
 * same (continuous) blend. */
static inline void wp_envmap_sample(__global const wp_uint* texels,
                                    __global const float* environment_cdf,
                                    __global const WpEmitter* e, float u, float v, float3* d,
                                    float* pdf, float3* radiance) {
    wp_uint w = e->width, rows = e->height - 1u;
    __global const float* marginal = environment_cdf + e->cdf_first;
    wp_uint j = wp_envmap_search(marginal, rows, v);
    __global const float* row = marginal + rows + j * w;
    wp_uint i = wp_envmap_search(row, w, u);
    /* Where in the patch: the numbers' remainders within their bins. */
    float row_low = j > 0u ? marginal[j - 1u] : 0.0f, column_low = i > 0u ? row[i - 1u] : 0.0f;
    float s = clamp((u - column_low) / (row[i] - column_low), 0.0f, 1.0f);
    float t = clamp((v - row_low) / (marginal[j] - row_low), 0.0f, 1.0f);
    float2 geometry = wp_envmap_row_geometry(environment_cdf, e, j);
    float span = geometry.y;
    float cos_theta = geometry.x - t * span;
    cos_theta = clamp(cos_theta, -1.0f, 1.0f);
    float sin_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta));
    /* phi / 2 pi, in [0, 1 + 1 / 2w]: a turn past 1 is the same angle. */
    float sin_phi, cos_phi;
    wp_sincos_2pi(((float)i + 0.5f + s) / (float)w, &sin_phi, &cos_phi);
    float3 l = (float3)(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta);
    *d = normalize(e->to_local[0].xyz * l.x + e->to_local[1].xyz * l.y + e->to_local[2].xyz * l.z);
    float p_row = marginal[j] - row_low, p_column = row[i] - column_low;
    *pdf = p_row * p_column / ((2.0f * WP_PI / (float)w) * span);
    /* The row weight is theta's place in the row, (theta - theta_j) rows / pi:
     * the radiance is bilinear in (phi, theta), the sample uniform in cos theta. */
    float y = wp_atan2(sin_theta, cos_theta) * (1.0f / WP_PI) * (float)rows;
    *radiance =
        wp_envmap_patch_radiance(texels, e, (int)i, (int)j, s, clamp(y - (float)j, 0.0f, 1.0f));
}

#endif /* WP_LIGHTS_ENVMAP_H */
