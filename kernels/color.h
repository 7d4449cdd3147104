/* RGB helpers. */
#ifndef WP_COLOR_H
#define WP_COLOR_H

#include "wp_shared.h"

static inline int wp_is_black(float3 c) {
    return c.x <= 0.0f && c.y <= 0.0f && c.z <= 0.0f;
}

static inline float wp_max_component(float3 c) {
    return fmax(c.x, fmax(c.y, c.z));
}

#endif /* WP_COLOR_H */
