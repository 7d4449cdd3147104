/* Estimator switches: which Monte Carlo estimator the kernels compile.
 *
 * The host passes them as -D options (IntegratorOptions::diffuse_sampling and
 * ::light_sampling; see src/render/wavefront.cpp), always both, so what a
 * render uses never depends on the defaults below. Left undefined, they give
 * the original estimator, which the stage tests in tests/kernels model on the host.
 * Every combination is unbiased and converges to the same image; they differ
 * in variance and cost (docs/convergence.md measures them on the hexroom).
 * Next-event estimation on/off is WP_USE_NEE, in scene_features.h.
 *
 * WP_DIFFUSE_SAMPLING: the next direction at a Lambertian surface.
 *   WP_DIFFUSE_COSINE (0): cosine-weighted directions (pdf cos(theta)/pi), so
 *     the throughput takes the reflectance; then throughput roulette: survive
 *     with probability min(1, max(throughput)), survivors divided by it.
 *   WP_DIFFUSE_REPORT (1): the student report's estimator (seed report, eqs.
 *     2.2, 2.9 and 2.10), made unbiased:
 *       - theta' = u * pi/2 with u uniform in [0, 1), phi uniform in [0, 2pi);
 *       - the report's roulette: terminate when theta' > sigma * pi/2 (eq.
 *         2.9), with sigma = min(1, max(reflectance)): probability 1 - sigma;
 *       - a survivor does NOT continue at theta' (the report does: that never
 *         samples theta > sigma * pi/2, so it loses that part of the
 *         hemisphere and is biased dark). Given survival theta' is uniform in
 *         [0, sigma * pi/2], so theta = theta' / sigma is uniform in [0, pi/2]
 *         again and independent of the roulette: that is the direction;
 *       - (theta, phi) uniform in the rectangle has solid-angle pdf
 *         1 / (pi^2 sin theta), so the unbiased weight is
 *         f cos / pdf = (rho/pi) cos theta pi^2 sin theta = pi rho cos sin
 *         (eq. 2.2), divided by the survival probability sigma (eq. 2.10 with
 *         1 - alpha = sigma). At most pi/2 per bounce: bounded, but the
 *         throughput can grow above 1.
 *     Mirrors keep their exact reflection and take the same albedo roulette
 *     (survive with probability sigma, no angle). No throughput roulette.
 *
 * WP_LIGHT_SAMPLING: how next-event estimation picks a point on a light
 * (a triangle is always picked with probability proportional to its area).
 *   WP_LIGHT_AREA (0): uniform by area on the triangle; the estimate carries
 *     cos_light / d^2, unbounded for points close to a light.
 *   WP_LIGHT_SOLID_ANGLE (1): uniform in the solid angle the triangle subtends
 *     (Arvo 1995, spherical triangles): weight Le cos_surface Omega / p_pick,
 *     bounded. Triangles subtending less than WP_MIN_SPHERICAL_AREA or more
 *     than WP_MAX_SPHERICAL_AREA steradians fall back to area sampling (float
 *     precision); the choice depends on the geometry only, so it stays
 *     unbiased.
 */
#ifndef WP_ESTIMATOR_H
#define WP_ESTIMATOR_H

#define WP_DIFFUSE_COSINE 0
#define WP_DIFFUSE_REPORT 1
#ifndef WP_DIFFUSE_SAMPLING
#define WP_DIFFUSE_SAMPLING WP_DIFFUSE_COSINE
#endif

#define WP_LIGHT_AREA 0
#define WP_LIGHT_SOLID_ANGLE 1
#ifndef WP_LIGHT_SAMPLING
#define WP_LIGHT_SAMPLING WP_LIGHT_AREA
#endif

/* WP_ROULETTE_DEPTH: the first bounce (1: the first vertex) at which the
 * throughput roulette of WP_DIFFUSE_COSINE may end a path; before it every
 * path goes on with survival probability 1 (IntegratorOptions::roulette_depth,
 * --roulette-depth; docs/convergence.md measures it). The report's albedo
 * roulette is part of its direction sampling and always runs. */
#ifndef WP_ROULETTE_DEPTH
#define WP_ROULETTE_DEPTH 1
#endif

/* WP_PATH_LENGTH: what frame.max_depth ends (IntegratorOptions::depth_rule).
 *   0: wavepath's safety cap: a path bounces at most frame.max_depth times;
 *     its last vertex still samples a light, and a path cut is counted.
 *   1: Mitsuba 3's max_depth M (a Mitsuba file's, docs/mitsuba-import.md):
 *     paths of at most M edges, the camera ray included; frame.max_depth is
 *     M - 1, the depth of the last vertex, which adds its emission and ends
 *     the path (no light sample there, no bounce), and a light sample by way
 *     of a mirror (two edges) is made only two vertices before it. */
#ifndef WP_PATH_LENGTH
#define WP_PATH_LENGTH 0
#endif

/* WP_ROULETTE_RULE: the survival probability of WP_DIFFUSE_COSINE's
 * throughput roulette (IntegratorOptions::roulette_rule, --roulette).
 *   WP_ROULETTE_THROUGHPUT (0): min(1, max(throughput)).
 *   WP_ROULETTE_MITSUBA (1): Mitsuba 3's `path` integrator's,
 *     min(0.95, max(throughput) eta^2), eta^2 the product of the squared
 *     relative indices of refraction the path crossed (throughput.w, 1 when
 *     generated). A refraction into glass divides the radiance a path carries
 *     by eta^2 (bsdf/dielectric.h); this rule does not count that against
 *     the path's chance to go on, and the cap ends even bright paths now and
 *     then. Only this rule compiles the eta^2 bookkeeping (shade.cl).
 *   WP_ROULETTE_SQRT (2): Blender Cycles', min(1, sqrt(max(throughput))).
 *     A path whose throughput has fallen to t survives with sqrt(t) > t and
 *     carries sqrt(t) on: roulette ends it later, and its survivors' weights
 *     stay nearer 1.
 *   WP_ROULETTE_RELATIVE (3): min(1, max(throughput) / max(throughput after
 *     the first bounce)), carried in throughput.w. A pixel's value scales
 *     with its first surface's reflectance as its paths' throughputs do, so
 *     relative to the pixel a path has lost nothing at its first bounce: the
 *     roulette weighs what later bounces take (a green wall's first bounce
 *     keeps 0.45 of the throughput, and under the throughput rule ended 55 %
 *     of its paths there, whatever its pixel's indirect light). */
#define WP_ROULETTE_THROUGHPUT 0
#define WP_ROULETTE_MITSUBA 1
#define WP_ROULETTE_SQRT 2
#define WP_ROULETTE_RELATIVE 3
#ifndef WP_ROULETTE_RULE
#define WP_ROULETTE_RULE WP_ROULETTE_THROUGHPUT
#endif

/* WP_MIS_STRATEGY: how a light sample and a BSDF sample that can find the
 * same light are weighed (lights.h, wp_mis_light_sample and wp_mis_bsdf_hit;
 * IntegratorOptions::mis, --mis).
 *   WP_MIS_POWER (0): the power heuristic.
 *   WP_MIS_LIGHT_ONLY (1): the light sample alone (weight 1) wherever it can
 *     reach; a BSDF sample's hit on such a light counts 0. For measuring what
 *     multiple importance sampling buys (docs/lights-and-camera.md). */
#define WP_MIS_POWER 0
#define WP_MIS_LIGHT_ONLY 1
#ifndef WP_MIS_STRATEGY
#define WP_MIS_STRATEGY WP_MIS_POWER
#endif

#define WP_MIN_SPHERICAL_AREA 1e-3f
#define WP_MAX_SPHERICAL_AREA 6.2f

#endif /* WP_ESTIMATOR_H */
