/* Materials: what a surface emits and how it scatters. */
#ifndef WP_MATERIAL_H
#define WP_MATERIAL_H

#include "wp_shared.h"

static inline int wp_is_black(float3 c) {
    return c.x <= 0.0f && c.y <= 0.0f && c.z <= 0.0f;
}

/* Perfect mirror reflection of d about the unit normal n. */
static inline float3 wp_reflect(float3 d, float3 n) {
    return d - 2.0f * dot(d, n) * n;
}

static inline float wp_max_component(float3 c) {
    return fmax(c.x, fmax(c.y, c.z));
}

#endif /* WP_MATERIAL_H */
