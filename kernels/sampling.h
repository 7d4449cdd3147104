/* Warping uniform random numbers to the distributions the integrator needs. */
#ifndef WP_SAMPLING_H
#define WP_SAMPLING_H

/* First: its FP_CONTRACT OFF must precede this file's arithmetic, whichever
 * header a stage includes first (without it, a stage that included this one
 * first let the compiler fuse the polynomials below into FMAs, and every
 * image with a diffuse bounce changed). */
#include "wp_shared.h"

#define WP_PI 3.14159265358979323846f

/* An orthonormal basis around unit n, without branches on n's direction
 * (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017). */
static inline void wp_make_basis(float3 n, float3* t, float3* b) {
    float sign = copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = (float3)(c, sign + n.y * n.y * a, -n.y);
}

/* sin(2 pi u) and cos(2 pi u) for u in [0, 1), as polynomials: no library
 * call, whose general argument reduction PoCL does not inline (and whose
 * branches stop vectorisation). The reduction is exact: 4u = q + f with q the
 * nearest integer and |f| <= 1/2 (exact for any float u in [0, 1)), so that
 * 2 pi u = (pi / 2) (q + f); sin and cos of (pi / 2) f are Taylor polynomials
 * in f (truncation below 2e-9 on |f| <= 1/2) and the quadrant q swaps and
 * negates them. Within 1.2e-7 of the double-precision values
 * (tests/kernels/test_sampling.cpp), more accurate than sin(2 pi u in float),
 * whose argument alone is rounded by up to 2.4e-7. */
static inline void wp_sincos_2pi(float u, float* sine, float* cosine) {
    float q = rint(4.0f * u);
    float f = 4.0f * u - q;
    float f2 = f * f;
    float s = f * (1.5707963267948966f +
                   f2 * (-0.6459640975062462f +
                         f2 * (0.07969262624616704f +
                               f2 * (-0.004681754135318687f + f2 * 0.00016044118478735982f))));
    float c =
        1.0f + f2 * (-1.2337005501361697f +
                     f2 * (0.2536695079010480f +
                           f2 * (-0.020863480763352960f +
                                 f2 * (0.0009192602748394261f + f2 * -2.5202042373060605e-05f))));
    int k = ((int)q) & 3; /* q in 0 .. 4, and 4 is a full turn */
    float sin_k = (k & 1) ? c : s;
    float cos_k = (k & 1) ? s : c;
    *sine = (k & 2) ? -sin_k : sin_k;
    *cosine = (k == 1 || k == 2) ? -cos_k : cos_k;
}

/* atan2(y, x) without a library call (PoCL's atan2 was 5 % of the
 * showcase's shade, where the envmap turns every escaping ray's direction
 * into map coordinates): the angle's tangent t = |y| / |x| reduced to
 * |t'| <= tan(pi/8) by atan t = pi/4 + atan((t - 1)/(t + 1)) or
 * pi/2 - atan(1/t), then Moshier's polynomial for float (Cephes' atanf),
 * then the quadrant by selects. Within 3.5 ulps of the double-precision
 * atan2 (tests/kernels/test_sampling.cpp), and as atan2 at the axes and the
 * signed zeros: (+-0, +0) give +-0, (+-0, -0) give +-pi; a NaN gives NaN. */
static inline float wp_atan2(float y, float x) {
    float ax = fabs(x), ay = fabs(y);
    float t = ay / ax; /* +inf on the y axis; 0 / 0 at the origin, fixed below */
    int steep = t > 2.414213562373095f, middle = !steep && t > 0.4142135623730950f;
    float base = steep ? 0.5f * WP_PI : middle ? 0.25f * WP_PI : 0.0f;
    float r = steep ? -1.0f / t : middle ? (t - 1.0f) / (t + 1.0f) : t;
    float z = r * r;
    float angle =
        base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
                 3.33329491539e-1f) *
                    z * r +
                r);
    angle = ax == 0.0f && ay == 0.0f ? 0.0f : angle;
    angle = signbit(x) ? WP_PI - angle : angle;
    return copysign(angle, y);
}

/* Cosine-weighted direction on the hemisphere around unit n: pdf cos(theta)/pi.
 * With it the Lambertian estimate's cos/pdf cancels to pi, so the throughput
 * just takes the reflectance. */
static inline float3 wp_sample_cosine_hemisphere(float3 n, float u1, float u2) {
    float r = sqrt(u1);
    float sin_phi, cos_phi; /* phi = 2 pi u2 */
    wp_sincos_2pi(u2, &sin_phi, &cos_phi);
    float z = sqrt(fmax(0.0f, 1.0f - u1));
    float3 t, b;
    wp_make_basis(n, &t, &b);
    return normalize(t * (r * cos_phi) + b * (r * sin_phi) + n * z);
}

/* A direction uniformly distributed on the unit sphere: pdf 1 / (4 pi). The
 * constant emitter's light sample (lights.h): its pdf is the same at every
 * vertex, so a ray that escapes after a BSDF sample weighs itself against it
 * without knowing the surface it left. */
static inline float3 wp_sample_uniform_sphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = sqrt(fmax(0.0f, 1.0f - z * z));
    float sin_phi, cos_phi; /* phi = 2 pi u2 */
    wp_sincos_2pi(u2, &sin_phi, &cos_phi);
    return (float3)(r * cos_phi, r * sin_phi, z);
}

/* A uniform point of the unit disk by Shirley and Chiu's concentric map
 * ("A Low Distortion Map Between Disk and Square", 1997): each square ring
 * [-r, r]^2 minus [-r', r']^2 goes to the annulus between r' and r, so
 * stratified (u1, u2) stay stratified on the disk and neighbouring numbers
 * stay neighbours (the thin lens's aperture, camera.h). pdf 1 / pi. The
 * angle, pi/4 times a ratio in [-1, 1], is one eighth of a turn at most:
 * wp_sincos_2pi of its magnitude, the sign put back on the sine. */
static inline float2 wp_sample_concentric_disk(float u1, float u2) {
    float a = 2.0f * u1 - 1.0f;
    float b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return (float2)(0.0f, 0.0f);
    int wide = fabs(a) > fabs(b);
    float r = wide ? a : b;
    float ratio = wide ? b / a : a / b;
    float sine, cosine;
    wp_sincos_2pi(0.125f * fabs(ratio), &sine, &cosine);
    sine = copysign(sine, ratio);
    /* Where |b| >= |a| the angle is pi/2 - (pi/4) a/b: cosine and sine swap. */
    return wide ? (float2)(r * cosine, r * sine) : (float2)(r * sine, r * cosine);
}

/* The direction (theta, phi) around unit n, theta from n: the report's
 * parametrisation (x = sin theta cos phi, y = sin theta sin phi, z = cos theta). */
static inline float3 wp_direction_from_angles(float3 n, float theta, float phi) {
    float sin_theta = sin(theta);
    float3 t, b;
    wp_make_basis(n, &t, &b);
    return normalize(t * (sin_theta * cos(phi)) + b * (sin_theta * sin(phi)) + n * cos(theta));
}

/* The angle between unit vectors, accurate near 0 and pi (unlike acos). */
static inline float wp_angle_between(float3 a, float3 b) {
    if (dot(a, b) < 0.0f)
        return WP_PI - 2.0f * asin(fmin(1.0f, 0.5f * length(a + b)));
    return 2.0f * asin(fmin(1.0f, 0.5f * length(b - a)));
}

/* Solid angle subtended at the origin by the triangle (r0, r1, r2), given
 * relative to the point (Van Oosterom and Strackee 1983). The triple product
 * comes from the triangle's edges, so it stays accurate for small, distant
 * triangles; the vectors need not be unit. */
static inline float wp_spherical_triangle_area(float3 r0, float3 r1, float3 r2) {
    float l0 = length(r0), l1 = length(r1), l2 = length(r2);
    float triple = fabs(dot(r0, cross(r1 - r0, r2 - r0)));
    float denominator = l0 * l1 * l2 + dot(r0, r1) * l2 + dot(r0, r2) * l1 + dot(r1, r2) * l0;
    return 2.0f * atan2(triple, denominator);
}

/* A direction uniformly distributed in the solid angle of the spherical
 * triangle of unit vectors (a, b, c), whose area is `area` (Arvo, "Stratified
 * sampling of spherical triangles", SIGGRAPH 1995; in the form of pbrt-v4's
 * SampleSphericalTriangle). u1 picks the sub-triangle (a, b, c') of area
 * u1 * area, u2 the point on the arc from b to c'. */
static inline float3 wp_sample_spherical_triangle(float3 a, float3 b, float3 c, float area,
                                                  float u1, float u2) {
    float3 n_ab = normalize(cross(a, b));
    float3 n_bc = normalize(cross(b, c));
    float3 n_ca = normalize(cross(c, a));
    float alpha = wp_angle_between(n_ab, -n_ca); /* the triangle's angle at a */
    float cos_alpha = cos(alpha), sin_alpha = sin(alpha);
    /* phi = (pi + u1 * area) - alpha, where pi + u1 * area is the angle sum of
     * the sub-triangle; its sine and cosine without adding pi in float. */
    float alpha_minus = alpha - u1 * area;
    float sin_phi = sin(alpha_minus);
    float cos_phi = -cos(alpha_minus);
    float k1 = cos_phi + cos_alpha;
    float k2 = sin_phi - sin_alpha * dot(a, b);
    float cos_bp = (k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) /
                   ((k2 * sin_phi + k1 * cos_phi) * sin_alpha);
    cos_bp = clamp(cos_bp, -1.0f, 1.0f);
    float sin_bp = sqrt(fmax(0.0f, 1.0f - cos_bp * cos_bp));
    float3 c_perp = normalize(c - dot(c, a) * a);
    float3 c_prime = cos_bp * a + sin_bp * c_perp; /* on the arc from a to c */
    float cos_theta = 1.0f - u2 * (1.0f - dot(c_prime, b));
    float sin_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta));
    float3 towards = normalize(c_prime - dot(c_prime, b) * b);
    return normalize(cos_theta * b + sin_theta * towards);
}

/* A uniformly distributed point of the triangle (p0, p1, p2). */
static inline float3 wp_sample_triangle(float3 p0, float3 p1, float3 p2, float u1, float u2) {
    float su = sqrt(u1);
    float b0 = 1.0f - su;
    float b1 = u2 * su;
    return b0 * p0 + b1 * p1 + (1.0f - b0 - b1) * p2;
}

#endif /* WP_SAMPLING_H */
