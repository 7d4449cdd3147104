/* Path types: which part of the estimate a contribution belongs to, for
 * measuring where the error is (`--path-types`, docs/convergence.md).
 *
 * A path's vertices after the camera are diffuse (D) or mirror (S) bounces.
 * Light reaches it either as emission at the vertex a ray hits or by
 * next-event estimation at a diffuse vertex; the bounces before that event
 * (for next-event estimation: including the diffuse vertex itself) are its
 * history, and the history picks exactly one type:
 *   camera    none: an emitter seen directly
 *   direct    D: next-event estimation at the first vertex, and an emitter
 *             hit after one diffuse bounce (weighed against it by multiple
 *             importance sampling, or in full without it)
 *   indirect  D D..., no mirror anywhere
 *   mirror    S ...: the first vertex is a mirror (the light or the lit room
 *             seen in a mirror)
 *   caustic   D ... S ...: light that came by way of a mirror after a diffuse
 *             bounce
 * Every history is one of these five, so the parts sum to the full estimate.
 *
 * Compiled in only with WP_PATH_TYPES: the history class is then kept in
 * bits of path_flags (WP_PATH_HISTORY_BITS, which hold the type the history
 * so far gives), and contributions of types outside the render's set
 * (WpFrame.path_types, a sum of 1u << type) are not added. The set is the
 * frame's, not a build option, so that one program serves every set (a
 * breakdown renders each type in turn). Random numbers depend on (seed,
 * pixel, sample, depth, dimension) alone, so leaving a contribution out
 * changes nothing else: with the same seed the parts' images sum to the full
 * image. Without WP_PATH_TYPES the tests below are the constant 1 and nothing
 * is tracked.
 */
#ifndef WP_PATH_TYPE_H
#define WP_PATH_TYPE_H

#include "wp_shared.h"

#ifndef WP_PATH_TYPES
#define WP_PATH_TYPES 0
#endif

#if WP_PATH_TYPES

static inline wp_uint wp_path_history(wp_uint flags) {
    return (flags & WP_PATH_HISTORY_BITS) >> WP_PATH_HISTORY_SHIFT;
}

/* The history class after one more bounce, specular (a mirror) or diffuse. */
static inline wp_uint wp_path_history_after(wp_uint history, int specular) {
    if (history == WP_PATH_TYPE_CAMERA)
        return specular ? WP_PATH_TYPE_MIRROR : WP_PATH_TYPE_DIRECT;
    if (history == WP_PATH_TYPE_DIRECT || history == WP_PATH_TYPE_INDIRECT)
        return specular ? WP_PATH_TYPE_CAUSTIC : WP_PATH_TYPE_INDIRECT;
    return history; /* mirror and caustic stay what they are */
}

static inline int wp_path_type_selected(wp_uint types, wp_uint type) {
    return (types >> type) & 1u;
}

/* Whether emission found at this vertex counts, and whether next-event
 * estimation at this (diffuse) vertex does, for a render that adds the path
 * types `types` (WpFrame.path_types). */
#define WP_PATH_EMISSION_SELECTED(types, flags) wp_path_type_selected(types, wp_path_history(flags))
#define WP_PATH_NEXT_EVENT_SELECTED(types, flags)                                                  \
    wp_path_type_selected(types, wp_path_history_after(wp_path_history(flags), 0))

/* `flags` with the history extended by the bounce just sampled. */
static inline wp_uint wp_path_flags_after(wp_uint flags, int specular) {
    wp_uint history = wp_path_history_after(wp_path_history(flags), specular);
    return (flags & ~WP_PATH_HISTORY_BITS) | (history << WP_PATH_HISTORY_SHIFT);
}

#else

#define WP_PATH_EMISSION_SELECTED(types, flags) 1
#define WP_PATH_NEXT_EVENT_SELECTED(types, flags) 1

#endif /* WP_PATH_TYPES */

#endif /* WP_PATH_TYPE_H */
