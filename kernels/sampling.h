/* Warping uniform random numbers to the distributions the integrator needs. */
#ifndef WP_SAMPLING_H
#define WP_SAMPLING_H

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

/* Cosine-weighted direction on the hemisphere around unit n: pdf cos(theta)/pi.
 * With it the Lambertian estimate's cos/pdf cancels to pi, so the throughput
 * just takes the reflectance. */
static inline float3 wp_sample_cosine_hemisphere(float3 n, float u1, float u2) {
    float r = sqrt(u1);
    float phi = 2.0f * WP_PI * u2;
    float z = sqrt(fmax(0.0f, 1.0f - u1));
    float3 t, b;
    wp_make_basis(n, &t, &b);
    return normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + n * z);
}

/* A uniformly distributed point of the triangle (p0, p1, p2). */
static inline float3 wp_sample_triangle(float3 p0, float3 p1, float3 p2, float u1, float u2) {
    float su = sqrt(u1);
    float b0 = 1.0f - su;
    float b1 = u2 * su;
    return b0 * p0 + b1 * p1 + (1.0f - b0 - b1) * p2;
}

#endif /* WP_SAMPLING_H */
