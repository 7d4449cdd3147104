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

static inline float wp_two_diff(float a, float b, float* err) {
    float s = a - b;
    float bb = s - a;
    *err = (a - (s - bb)) - (b + bb);
    return s;
}

/* a - b, rounded exactly as a - b is (fma(-1, b, a) = round(a - b)), but
 * as a different instruction: the sphere test computes one axis with it, so
 * that LLVM's SLP vectoriser finds no alike lines to pack (traverse.h). */
static inline float wp_minus(float a, float b) {
    return fma(-1.0f, b, a);
}

/* wp_two_diff with every subtraction done by wp_minus: the same results. */
static inline float wp_two_diff_fma(float a, float b, float* err) {
    float s = wp_minus(a, b);
    float bb = wp_minus(s, a);
    *err = wp_minus(wp_minus(a, wp_minus(s, bb)), b + bb);
    return s;
}

static inline float wp_two_sum(float a, float b, float* err) {
    float s = a + b;
    float bb = s - a;
    *err = (a - (s - bb)) + (b - bb);
    return s;
}

/* wp_two_sum in two other forms for SLP, with the same results: the
 * error's two terms added as x - (-y) (bb - b == -(b - bb) exactly), so
 * that the last operation is an fma, not an addition; or its first term
 * subtracted by wp_minus. */
static inline float wp_two_sum_fma(float a, float b, float* err) {
    float s = a + b;
    float bb = s - a;
    *err = wp_minus(a - (s - bb), bb - b);
    return s;
}

static inline float wp_two_sum_fma_first(float a, float b, float* err) {
    float s = a + b;
    float bb = s - a;
    *err = wp_minus(a, s - bb) + (b - bb);
    return s;
}

static inline float wp_two_product(float a, float b, float* err) {
    float p = a * b;
    *err = fma(a, b, -p);
    return p;
}

#endif /* WP_EXACT_ARITHMETIC_H */
