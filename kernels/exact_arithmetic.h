/* Error-free transformations: a sum, difference or product split exactly into
 * its rounded value and its rounding error. The sphere test uses them to keep
 * digits that plain float arithmetic would cancel away.
 *
 * a - b == s + *err exactly (Knuth's TwoSum, valid for any rounding-to-nearest
 * floats as long as nothing is contracted, hence FP_CONTRACT OFF in
 * wp_shared.h), and a * b == p + *err exactly (the FMA gives the product's
 * rounding error).
 */
#ifndef WP_EXACT_ARITHMETIC_H
#define WP_EXACT_ARITHMETIC_H

#include "wp_shared.h"

static inline float3 wp_two_diff3(float3 a, float3 b, float3* err) {
    float3 s = a - b;
    float3 bb = s - a;
    *err = (a - (s - bb)) - (b + bb);
    return s;
}

static inline float wp_two_sum(float a, float b, float* err) {
    float s = a + b;
    float bb = s - a;
    *err = (a - (s - bb)) + (b - bb);
    return s;
}

static inline float wp_two_product(float a, float b, float* err) {
    float p = a * b;
    *err = fma(a, b, -p);
    return p;
}

#endif /* WP_EXACT_ARITHMETIC_H */
