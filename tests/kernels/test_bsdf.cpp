// The BSDFs of kernels/bsdf/ on the device, against host references in double
// precision: eval and pdf, reciprocity, the chi-square goodness of fit of
// sample() against pdf() over the sphere of directions (as Mitsuba's and
// pbrt's test suites do it), and the white furnace. One test program, built
// once, serves every case.
#include "rng.h"
#include "scene/material.hpp"
#include "support/chi_square.hpp"
#include "support/kernel_test_util.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

using namespace wp::test;

namespace {

const char* const kBsdfSource = R"CL(
#include "bsdf.h"
#include "rng.h"

/* n.xyz the shading normal on the ray's side; n.w 0 when the ray came from
 * the front side, 1 from the back (inside a solid). */
WpShadingPoint shading_point(float4 n) {
    WpShadingPoint p;
    p.n = n.xyz;
    p.front_face = n.w == 0.0f;
#if WP_HAS_ANISOTROPY /* the frame the host reference takes (make_basis below) */
    float3 b;
    wp_make_basis(p.n, &p.tangent, &b);
#endif
    return p;
}

/* eval_pi (rgb) and pdf (w) of count direction pairs. */
__kernel void bsdf_eval(__global const WpMaterial* material, float4 n, uint count,
                        __global const float4* wo, __global const float4* wi,
                        __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpMaterial m = *material;
    WpShadingPoint p = shading_point(n);
    float3 f = wp_bsdf_eval_pi(&m, wo[i].xyz, wi[i].xyz, &p);
    out[i] = (float4)(f, wp_bsdf_pdf(&m, wo[i].xyz, wi[i].xyz, &p));
}

/* count samples for one incident direction: direction and pdf (w), weight and
 * flags (w). */
__kernel void bsdf_sample(__global const WpMaterial* material, float4 n, float4 wo, uint seed,
                          uint count, __global float4* direction, __global float4* weight) {
    uint i = get_global_id(0);
    if (i >= count) return;
    WpMaterial m = *material;
    float u1 = wp_random(seed, i, 0u, 0u, WP_DIM_BSDF_U);
    float u2 = wp_random(seed, i, 0u, 0u, WP_DIM_BSDF_V);
    float u_lobe = wp_random(seed, i, 0u, 0u, WP_DIM_BSDF_LOBE);
    WpBsdfSample s;
    WpShadingPoint p = shading_point(n);
    wp_bsdf_sample(&m, wo.xyz, &p, u1, u2, u_lobe, &s);
    direction[i] = (float4)(s.direction, s.pdf);
    weight[i] = (float4)(s.weight, (float)s.flags);
}
)CL";

// Independent numbers: the chi-square test assumes independent samples.
const cl::Program& bsdf_program() {
    return program(kBsdfSource, "bsdf_test.cl", "-D WP_SAMPLER=0");
}

constexpr double kPi = 3.14159265358979323846;

// ---- the host reference, in double precision ---------------------------------

struct Rough {
    bool ggx = true;
    double alpha_u = 0.2, alpha_v = 0.2;
};

// Mitsuba's microfacet.h, as kernels/bsdf/microfacet.h implements it.
double ref_d(const Rough& r, const D3& m) {
    if (!(m.z > 0.0))
        return 0.0;
    const double x = m.x / r.alpha_u, y = m.y / r.alpha_v, z2 = m.z * m.z;
    const double area = kPi * r.alpha_u * r.alpha_v;
    if (r.ggx) {
        const double s = x * x + y * y + z2;
        return 1.0 / (area * s * s);
    }
    return std::exp(-(x * x + y * y) / z2) / (area * z2 * z2);
}

double ref_g1(const Rough& r, const D3& v, const D3& m) {
    if (!(glm::dot(v, m) * v.z > 0.0))
        return 0.0;
    const double xy = r.alpha_u * r.alpha_u * v.x * v.x + r.alpha_v * r.alpha_v * v.y * v.y;
    if (xy == 0.0)
        return 1.0;
    const double t2 = xy / (v.z * v.z);
    if (r.ggx)
        return 2.0 / (1.0 + std::sqrt(1.0 + t2));
    const double a = 1.0 / std::sqrt(t2);
    if (a >= 1.6)
        return 1.0;
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// The conductor's Fresnel reflectance for complex index eta + i k: the
// textbook form |r_s|^2, |r_p|^2 of complex amplitudes, independent of the
// kernels' real-arithmetic rearrangement.
double ref_fresnel(double cos_i, double eta, double k) {
    using C = std::complex<double>;
    const C n(eta, k);
    const double sin2 = 1.0 - cos_i * cos_i;
    const C cos_t = std::sqrt(C(1.0) - sin2 / (n * n));
    const C rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    const C rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

struct Conductor {
    Rough rough;
    D3 eta{0.0}, k{1.0};
    bool fresnel = true;
    D3 specular{1.0};
};

D3 ref_f(const Conductor& c, double cos_i) {
    if (!c.fresnel)
        return c.specular;
    return c.specular * D3(ref_fresnel(cos_i, c.eta.x, c.k.x), ref_fresnel(cos_i, c.eta.y, c.k.y),
                           ref_fresnel(cos_i, c.eta.z, c.k.z));
}

// pi f(v, l) and the density of l, local frame, v towards the viewer.
D3 ref_eval_pi(const Conductor& c, const D3& v, const D3& l) {
    if (!(v.z > 0.0 && l.z > 0.0))
        return D3(0.0);
    const D3 h = glm::normalize(v + l);
    const double g = ref_g1(c.rough, v, h) * ref_g1(c.rough, l, h);
    return ref_f(c, glm::dot(v, h)) * (kPi * ref_d(c.rough, h) * g / (4.0 * v.z * l.z));
}

double ref_pdf(const Conductor& c, const D3& v, const D3& l) {
    if (!(v.z > 0.0 && l.z > 0.0))
        return 0.0;
    const D3 h = glm::normalize(v + l);
    const double vh = glm::dot(v, h);
    if (!(vh > 0.0))
        return 0.0;
    return ref_d(c.rough, h) * ref_g1(c.rough, v, h) * vh / v.z / (4.0 * vh);
}

WpMaterial device_material(const Conductor& c, wp_uint kind = WP_MATERIAL_ROUGHCONDUCTOR) {
    WpMaterial m{};
    m.kind = kind;
    m.reflectance = to_float4(c.specular);
    m.eta = to_float4(c.eta);
    m.k = to_float4(c.k);
    m.fresnel = c.fresnel ? 1u : 0u;
    m.distribution = c.rough.ggx ? WP_MICROFACET_GGX : WP_MICROFACET_BECKMANN;
    m.alpha_u = static_cast<float>(c.rough.alpha_u);
    m.alpha_v = static_cast<float>(c.rough.alpha_v);
    return m;
}

// The kernels' frame around n (kernels/sampling.h, wp_make_basis), in double.
void make_basis(const D3& n, D3& t, D3& b) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = D3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = D3(c, sign + n.y * n.y * a, -n.y);
}

D3 to_world(const D3& local, const D3& n) {
    D3 t, b;
    make_basis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

D3 direction(double cos_theta, double phi) {
    const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return D3(s * std::cos(phi), s * std::sin(phi), cos_theta);
}

std::string describe(const Conductor& c) {
    std::ostringstream s;
    s << (c.rough.ggx ? "ggx" : "beckmann") << " alpha " << c.rough.alpha_u << "/"
      << c.rough.alpha_v << (c.fresnel ? "" : " (no Fresnel)") << " eta " << c.eta.x << ","
      << c.eta.y << "," << c.eta.z << " k " << c.k.x << "," << c.k.y << "," << c.k.z;
    return s.str();
}

// ---- the device side ----------------------------------------------------------

std::vector<cl_float4> run_eval(const WpMaterial& m, const D3& n, const std::vector<cl_float4>& wo,
                                const std::vector<cl_float4>& wi) {
    cl::Kernel kernel(bsdf_program(), "bsdf_eval");
    cl::Buffer material = upload(std::vector<WpMaterial>{m});
    // Named: a buffer must outlive the launch that reads it.
    cl::Buffer wo_buffer = upload(wo), wi_buffer = upload(wi);
    cl::Buffer out = upload(std::vector<cl_float4>(wo.size()));
    set_args(kernel, material, to_float4(n), static_cast<cl_uint>(wo.size()), wo_buffer, wi_buffer,
             out);
    launch(kernel, wo.size());
    return download<cl_float4>(out, wo.size());
}

struct Samples {
    std::vector<cl_float4> direction; // xyz, pdf in w
    std::vector<cl_float4> weight;    // rgb, flags in w
};

// `count` samples for the ray direction wo at shading normal n (on the ray's
// side), which arrived from the primitive's back side when `from_back`.
Samples run_sample(const WpMaterial& m, const D3& n, const D3& wo, cl_uint seed, std::size_t count,
                   bool from_back = false) {
    cl::Kernel kernel(bsdf_program(), "bsdf_sample");
    cl::Buffer material = upload(std::vector<WpMaterial>{m});
    cl::Buffer direction = upload(std::vector<cl_float4>(count));
    cl::Buffer weight = upload(std::vector<cl_float4>(count));
    cl_float4 normal = to_float4(n);
    normal.s[3] = from_back ? 1.0f : 0.0f;
    set_args(kernel, material, normal, to_float4(wo), seed, static_cast<cl_uint>(count), direction,
             weight);
    launch(kernel, count);
    return {download<cl_float4>(direction, count), download<cl_float4>(weight, count)};
}

// ---- statistics ------------------------------------------------------------------

// The histogram of sampled directions (local frame) and the expected counts
// from the reference pdf, integrated over each bin by Simpson's rule in
// (cos theta, phi), over the whole sphere.
constexpr int kCosBins = 32, kPhiBins = 32;

template <typename Pdf> std::vector<double> expected_counts_of(Pdf pdf, std::size_t samples) {
    // Simpson intervals per bin and axis (even). The two bins at the poles get
    // many more along cos theta: a lobe of angular width w there is only w^2/2
    // wide in cos theta (a narrow refracted lobe at normal incidence).
    constexpr int kSteps = 16, kPoleSteps = 1024;
    std::vector<double> out(kCosBins * kPhiBins);
    const double dc = 2.0 / kCosBins, dp = 2.0 * kPi / kPhiBins;
    for (int i = 0; i < kCosBins; ++i) {
        const int cos_steps = (i == 0 || i == kCosBins - 1) ? kPoleSteps : kSteps;
        for (int j = 0; j < kPhiBins; ++j) {
            double sum = 0.0;
            for (int a = 0; a <= cos_steps; ++a) {
                const double wa = (a == 0 || a == cos_steps) ? 1.0 : (a % 2 ? 4.0 : 2.0);
                const double cos_theta = -1.0 + dc * (i + double(a) / cos_steps);
                for (int b = 0; b <= kSteps; ++b) {
                    const double wb = (b == 0 || b == kSteps) ? 1.0 : (b % 2 ? 4.0 : 2.0);
                    const double phi = dp * (j + double(b) / kSteps);
                    sum += wa * wb * pdf(direction(cos_theta, phi));
                }
            }
            out[i * kPhiBins + j] =
                sum * (dc / cos_steps / 3.0) * (dp / kSteps / 3.0) * double(samples);
        }
    }
    return out;
}

std::vector<double> expected_counts(const Conductor& c, const D3& v, std::size_t samples) {
    return expected_counts_of([&](const D3& l) { return ref_pdf(c, v, l); }, samples);
}

std::vector<double> observed_counts(const Samples& s) {
    std::vector<double> out(kCosBins * kPhiBins);
    for (std::size_t i = 0; i < s.direction.size(); ++i) {
        if (s.weight[i].s[3] == 0.0f || (cl_uint(s.weight[i].s[3]) & WP_BSDF_DELTA))
            continue; // no direction, or one that no density describes
        const D3 d = glm::normalize(from_float4(s.direction[i]));
        const int ci = std::clamp(int((d.z + 1.0) * 0.5 * kCosBins), 0, kCosBins - 1);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0.0)
            phi += 2.0 * kPi;
        const int pj = std::clamp(int(phi / (2.0 * kPi) * kPhiBins), 0, kPhiBins - 1);
        out[ci * kPhiBins + pj] += 1.0;
    }
    return out;
}

const D3 kUp(0.0, 0.0, 1.0);

std::vector<Conductor> chi_square_materials() {
    std::vector<Conductor> out;
    for (bool ggx : {true, false})
        for (auto [au, av] : {std::pair{0.2, 0.2}, std::pair{0.6, 0.6}, std::pair{0.15, 0.5}}) {
            Conductor c;
            c.rough = Rough{ggx, au, av};
            c.eta = D3(0.2004376970, 0.9240334304, 1.1022119527); // Cu
            c.k = D3(3.9129485033, 2.4528477015, 2.1421879552);
            out.push_back(c);
        }
    return out;
}

} // namespace

TEST_CASE("roughconductor: eval and pdf match the double-precision reference", "[cl][bsdf]") {
    const D3 normals[] = {kUp, glm::normalize(D3(0.3, -0.5, 0.8))};
    std::vector<Conductor> materials = chi_square_materials();
    Conductor lossless;
    lossless.rough = Rough{true, 0.05, 0.05};
    lossless.fresnel = false;
    materials.push_back(lossless);
    Conductor gold;
    gold.rough = Rough{false, 0.4, 0.1};
    gold.eta = D3(0.1431189557, 0.3749570432, 1.4424785571);
    gold.k = D3(3.9831604247, 2.3857207478, 1.6032152899);
    gold.specular = D3(0.9, 0.8, 0.7);
    materials.push_back(gold);

    // Direction pairs on a grid over both hemispheres (those below carry 0).
    std::vector<D3> v_local, l_local;
    for (double cv : {1.0, 0.9, 0.6, 0.3, 0.05, -0.4})
        for (double pv : {0.0, 1.1})
            for (double cl : {0.95, 0.7, 0.4, 0.1, -0.2})
                for (double pl : {0.0, 0.9, 2.5, 3.14, 4.4}) {
                    v_local.push_back(direction(cv, pv));
                    l_local.push_back(direction(cl, pl));
                }
    for (const D3& n : normals)
        for (const Conductor& c : materials) {
            INFO(describe(c) << ", normal " << n.x << " " << n.y << " " << n.z);
            std::vector<cl_float4> wo, wi;
            std::vector<D3> v_exact, l_exact; // the float directions, as the device has them
            for (std::size_t i = 0; i < v_local.size(); ++i) {
                wo.push_back(to_float4(-to_world(v_local[i], n)));
                wi.push_back(to_float4(to_world(l_local[i], n)));
            }
            const std::vector<cl_float4> got = run_eval(device_material(c), n, wo, wi);
            D3 t, b;
            make_basis(from_float4(to_float4(n)), t, b);
            const D3 nf = from_float4(to_float4(n));
            std::size_t nonzero = 0;
            for (std::size_t i = 0; i < got.size(); ++i) {
                const D3 vw = -from_float4(wo[i]), lw = from_float4(wi[i]);
                const D3 v(glm::dot(vw, t), glm::dot(vw, b), glm::dot(vw, nf));
                const D3 l(glm::dot(lw, t), glm::dot(lw, b), glm::dot(lw, nf));
                const D3 f = ref_eval_pi(c, v, l);
                const double pdf = ref_pdf(c, v, l);
                INFO("v " << v.x << " " << v.y << " " << v.z << ", l " << l.x << " " << l.y << " "
                          << l.z);
                // Relative 1e-3 of the value: float arithmetic on D's steep
                // exponent and powers; an absolute floor for near-zero lobes.
                for (int ch = 0; ch < 3; ++ch)
                    CHECK(std::fabs(got[i].s[ch] - f[ch]) <= 1e-3 * f[ch] + 1e-6);
                CHECK(std::fabs(got[i].s[3] - pdf) <= 1e-3 * pdf + 1e-6);
                nonzero += pdf > 1e-3 ? 1 : 0;
            }
            CHECK(nonzero > got.size() / 10); // the grid meets the lobes
        }
}

TEST_CASE("roughconductor: eval is reciprocal", "[cl][bsdf]") {
    for (const Conductor& c : chi_square_materials()) {
        INFO(describe(c));
        std::vector<cl_float4> a, b;
        for (double cv : {0.95, 0.6, 0.2})
            for (double cl : {0.9, 0.5, 0.15})
                for (double p : {0.0, 0.7, 2.0, 3.0, 5.5}) {
                    a.push_back(to_float4(-direction(cv, 0.3)));
                    b.push_back(to_float4(direction(cl, p)));
                }
        std::vector<cl_float4> b_in, a_out; // the same pairs, the other way round
        for (std::size_t i = 0; i < a.size(); ++i) {
            b_in.push_back(to_float4(-from_float4(b[i])));
            a_out.push_back(to_float4(-from_float4(a[i])));
        }
        const auto forward = run_eval(device_material(c), kUp, a, b);
        const auto backward = run_eval(device_material(c), kUp, b_in, a_out);
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int ch = 0; ch < 3; ++ch)
                CHECK(std::fabs(forward[i].s[ch] - backward[i].s[ch]) <=
                      1e-4 * std::fabs(forward[i].s[ch]) + 1e-7);
    }
}

TEST_CASE("roughconductor: sample() follows pdf() (chi-square)", "[cl][bsdf][statistical]") {
    // 2^18 samples per case: a pdf off by 2 % over a tenth of the sphere
    // (bins of expectation ~2600) shows as a chi-square excess of ~1 per such
    // bin, about 100 bins, far past the 1 % level with 500 degrees of freedom.
    constexpr std::size_t kSamples = 1u << 18;
    const double incident_degrees[] = {0.0, 40.0, 75.0};
    const std::vector<Conductor> materials = chi_square_materials();
    const double significance = 0.01 / double(materials.size() * std::size(incident_degrees));
    cl_uint seed = 11;
    double lowest_p = 1.0;
    for (const Conductor& c : materials)
        for (double degrees : incident_degrees) {
            const double theta = degrees * kPi / 180.0;
            const D3 v = D3(std::sin(theta) * std::cos(0.4), std::sin(theta) * std::sin(0.4),
                            std::cos(theta));
            const D3 v_float = glm::normalize(from_float4(to_float4(v)));
            const Samples s = run_sample(device_material(c), kUp, -v, seed++, kSamples);
            const ChiSquare result =
                chi_square(observed_counts(s), expected_counts(c, v_float, kSamples));
            INFO(describe(c) << ", incidence " << degrees << " degrees: chi-square "
                             << result.statistic << ", " << result.dof << " dof, p "
                             << result.p_value);
            CHECK(result.outside == 0);
            CHECK(result.p_value > significance);
            lowest_p = std::min(lowest_p, result.p_value);
        }
    INFO("lowest p-value " << lowest_p);
    CHECK(lowest_p > significance);
}

TEST_CASE("roughconductor: sample weights are eval cos / pdf, pdf is pdf()", "[cl][bsdf]") {
    for (const Conductor& c : chi_square_materials()) {
        INFO(describe(c));
        const D3 v = glm::normalize(from_float4(to_float4(glm::normalize(D3(0.4, 0.1, 0.8)))));
        const Samples s = run_sample(device_material(c), kUp, -v, 3, 4096);
        std::size_t valid = 0;
        for (std::size_t i = 0; i < s.direction.size(); ++i) {
            if (s.weight[i].s[3] == 0.0f)
                continue;
            ++valid;
            const D3 l = from_float4(s.direction[i]);
            const double pdf = ref_pdf(c, v, l);
            const D3 expected = ref_eval_pi(c, v, l) / kPi * l.z / pdf;
            INFO("l " << l.x << " " << l.y << " " << l.z);
            CHECK(std::fabs(s.direction[i].s[3] - pdf) <= 2e-3 * pdf + 1e-6);
            for (int ch = 0; ch < 3; ++ch)
                CHECK(std::fabs(s.weight[i].s[ch] - expected[ch]) <= 2e-3 * expected[ch] + 1e-6);
            CHECK(cl_uint(s.weight[i].s[3]) == (WP_BSDF_REFLECTION | WP_BSDF_GLOSSY));
        }
        CHECK(valid > 2000); // the rest leave below the horizon (up to a quarter at alpha 0.6)
    }
}

TEST_CASE("roughconductor: white furnace", "[cl][bsdf][statistical]") {
    // The directional albedo is the mean weight over samples. It may never
    // exceed 1; for a lossless conductor (no Fresnel term, or eta 0 and k 1
    // through the Fresnel formula) of small roughness it is 1 within noise
    // and the single-scattering loss (G1 < 1, below 1e-3 at alpha 0.01).
    constexpr std::size_t kSamples = 1u << 16;
    cl_uint seed = 101;
    for (bool ggx : {true, false})
        for (double alpha : {0.01, 0.3, 1.0})
            for (int lossless = 0; lossless < 3; ++lossless)
                for (double degrees : {0.0, 30.0, 60.0, 85.0}) {
                    Conductor c;
                    c.rough = Rough{ggx, alpha, alpha};
                    if (lossless == 0)
                        c.fresnel = false;
                    else if (lossless == 2) { // Al, which absorbs
                        c.eta = D3(1.6574599595, 0.8803689579, 0.5212287346);
                        c.k = D3(9.2238691996, 6.2695232477, 4.8370012281);
                    }
                    const double theta = degrees * kPi / 180.0;
                    const D3 v(std::sin(theta), 0.0, std::cos(theta));
                    const Samples s = run_sample(device_material(c), kUp, -v, seed++, kSamples);
                    std::array<double, 3> sum{}, sum_squares{};
                    for (const cl_float4& w : s.weight)
                        for (int ch = 0; ch < 3; ++ch) {
                            sum[ch] += w.s[ch];
                            sum_squares[ch] += double(w.s[ch]) * w.s[ch];
                        }
                    for (int ch = 0; ch < 3; ++ch) {
                        const double mean = sum[ch] / kSamples;
                        const double sigma = std::sqrt(
                            std::max(0.0, sum_squares[ch] / kSamples - mean * mean) / kSamples);
                        INFO(describe(c) << ", incidence " << degrees << ": albedo[" << ch << "] "
                                         << mean << " +- " << sigma);
                        CHECK(mean <= 1.0 + 5.0 * sigma + 1e-6);
                        if (lossless < 2 && alpha <= 0.01 && degrees <= 60.0)
                            CHECK(std::fabs(mean - 1.0) <= 5.0 * sigma + 1e-3);
                    }
                }
}

TEST_CASE("conductor: a delta reflection with the Fresnel reflectance", "[cl][bsdf]") {
    Conductor gold;
    gold.eta = D3(0.1431189557, 0.3749570432, 1.4424785571);
    gold.k = D3(3.9831604247, 2.3857207478, 1.6032152899);
    gold.specular = D3(1.0, 0.5, 0.25);
    const WpMaterial m = device_material(gold, WP_MATERIAL_CONDUCTOR);
    for (double degrees : {0.0, 45.0, 80.0, 89.0}) {
        const double theta = degrees * kPi / 180.0;
        const D3 v(std::sin(theta), 0.0, std::cos(theta));
        const Samples s = run_sample(m, kUp, -v, 1, 1);
        const D3 d = from_float4(s.direction[0]);
        const D3 f = ref_f(gold, std::cos(theta));
        INFO("incidence " << degrees);
        CHECK(std::fabs(d.x + v.x) < 1e-6);
        CHECK(std::fabs(d.z - v.z) < 1e-6);
        CHECK(s.direction[0].s[3] == 0.0f);
        CHECK(cl_uint(s.weight[0].s[3]) == (WP_BSDF_REFLECTION | WP_BSDF_DELTA));
        for (int ch = 0; ch < 3; ++ch)
            CHECK(std::fabs(s.weight[0].s[ch] - f[ch]) <= 1e-5 + 1e-4 * f[ch]);
    }
    // eval and pdf: no direction meets a delta BSDF.
    const auto got =
        run_eval(m, kUp, {to_float4(-direction(0.8, 0.0))}, {to_float4(direction(0.8, kPi))});
    CHECK(got[0].s[0] == 0.0f);
    CHECK(got[0].s[3] == 0.0f);
}

// ---- dielectrics --------------------------------------------------------------

// The reflectance of a dielectric interface, unpolarised, for incidence angle
// theta_i where eta = n_far / n_near, by Fresnel's sine and tangent laws
// (Hecht, "Optics", eq. 4.42-4.43): another form than the kernels' amplitude
// ratios of cosines. 1 beyond the critical angle.
double ref_fresnel_dielectric(double theta_i, double eta) {
    if (theta_i == 0.0)
        return ((eta - 1.0) / (eta + 1.0)) * ((eta - 1.0) / (eta + 1.0));
    const double sin_t = std::sin(theta_i) / eta;
    if (sin_t >= 1.0)
        return 1.0;
    const double theta_t = std::asin(sin_t);
    const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return 0.5 * (rs * rs + rp * rp);
}

WpMaterial dielectric_material(wp_uint kind, double eta, const D3& reflectance,
                               const D3& transmittance) {
    WpMaterial m{};
    m.kind = kind;
    m.eta = to_float4(D3(eta));
    m.reflectance = to_float4(reflectance);
    m.transmittance = to_float4(transmittance);
    return m;
}

// Counts a dielectric's samples: the share that reflect within 5 sigma of
// `reflect_probability` (exactly all or none when it is 1 or 0), each
// reflection the mirror direction with weight `reflectance`, each
// transmission `transmitted` (unit, up to float rounding) with weight
// `transmittance` x `factor`.
void check_lobes(const Samples& s, const D3& wo, const D3& n, double reflect_probability,
                 const D3& transmitted, const D3& reflectance, const D3& transmittance,
                 double factor) {
    const std::size_t count = s.direction.size();
    std::size_t reflected = 0, wrong_direction = 0, wrong_weight = 0, wrong_flags = 0;
    const D3 mirror = wo - 2.0 * glm::dot(wo, n) * n;
    for (std::size_t i = 0; i < count; ++i) {
        const auto flags = static_cast<cl_uint>(s.weight[i].s[3]);
        const bool reflection = flags == (WP_BSDF_REFLECTION | WP_BSDF_DELTA);
        if (!reflection && flags != (WP_BSDF_TRANSMISSION | WP_BSDF_DELTA)) {
            ++wrong_flags;
            continue;
        }
        reflected += reflection ? 1 : 0;
        const D3 expected = reflection ? mirror : transmitted;
        if (glm::length(from_float4(s.direction[i]) - expected) > 2e-6)
            ++wrong_direction;
        for (int c = 0; c < 3; ++c) {
            const double w = reflection ? reflectance[c] : transmittance[c] * factor;
            if (std::fabs(s.weight[i].s[c] - w) > 1e-6 * std::max(1.0, w))
                ++wrong_weight;
        }
        if (s.direction[i].s[3] != 0.0f) // a delta BSDF's density is 0
            ++wrong_flags;
    }
    CHECK(wrong_flags == 0);
    CHECK(wrong_direction == 0);
    CHECK(wrong_weight == 0);
    const double share = static_cast<double>(reflected) / static_cast<double>(count);
    INFO("reflected " << share << ", Fresnel " << reflect_probability);
    if (reflect_probability == 0.0 || reflect_probability == 1.0)
        CHECK(share == reflect_probability);
    else
        CHECK(std::fabs(share - reflect_probability) <=
              5.0 * std::sqrt(reflect_probability * (1.0 - reflect_probability) /
                              static_cast<double>(count)));
}

TEST_CASE("dielectric: reflects with the Fresnel probability, refracts by Snell's law, and "
          "carries radiance across the interface",
          "[cl][bsdf][statistical]") {
    // BK7, water and diamond against air, entered from outside (the front)
    // and left from inside (the back, where total internal reflection sets
    // in beyond the critical angle); a tilted normal too.
    constexpr std::size_t kCount = 20000;
    const D3 reflectance(1.0, 0.5, 0.25), transmittance(0.9, 0.8, 0.7);
    cl_uint seed = 300;
    for (double ior : {1.5046, 1.3330, 2.419})
        for (bool from_back : {false, true})
            for (const D3& n : {kUp, glm::normalize(D3(0.2, 0.4, -0.9))})
                for (double degrees : {0.0, 20.0, 40.0, 60.0, 80.0, 89.0}) {
                    const double theta = degrees * kPi / 180.0;
                    const D3 v = to_world(D3(std::sin(theta), 0.0, std::cos(theta)), n);
                    const double eta = from_back ? 1.0 / ior : ior; // n_far / n_near
                    const double r = ref_fresnel_dielectric(theta, eta);
                    // Snell: the tangential part over eta, the rest below the surface.
                    const D3 tangential = (-v + std::cos(theta) * n) / eta;
                    const double sin2_t = glm::dot(tangential, tangential);
                    const D3 refracted = tangential - std::sqrt(std::max(0.0, 1.0 - sin2_t)) * n;
                    const WpMaterial m = dielectric_material(WP_MATERIAL_DIELECTRIC, ior,
                                                             reflectance, transmittance);
                    INFO("ior " << ior << (from_back ? " from inside" : " from outside")
                                << ", normal " << n.z << ", incidence " << degrees);
                    check_lobes(run_sample(m, n, -v, seed++, kCount, from_back), -v, n, r,
                                refracted, reflectance, transmittance, 1.0 / (eta * eta));
                }
}

TEST_CASE("dielectric: an index of 1 is no interface", "[cl][bsdf]") {
    // Every sample passes straight on with the transmittance: no reflection,
    // no bending, no solid-angle factor, even at grazing incidence.
    const D3 transmittance(0.9, 0.8, 0.7);
    for (bool from_back : {false, true})
        for (double degrees : {0.0, 45.0, 89.9}) {
            const double theta = degrees * kPi / 180.0;
            const D3 v(std::sin(theta), 0.0, std::cos(theta));
            const WpMaterial m =
                dielectric_material(WP_MATERIAL_DIELECTRIC, 1.0, D3(1.0), transmittance);
            INFO((from_back ? "from inside" : "from outside") << ", incidence " << degrees);
            check_lobes(run_sample(m, kUp, -v, 7, 2000, from_back), -v, kUp, 0.0, -v, D3(1.0),
                        transmittance, 1.0);
        }
}

TEST_CASE("thindielectric: reflects 2R / (1 + R) and passes the rest straight through",
          "[cl][bsdf][statistical]") {
    // The pane's two interfaces and every internal bounce between them; the
    // same from both sides, and no bending.
    constexpr std::size_t kCount = 20000;
    const D3 reflectance(1.0, 0.5, 0.25), transmittance(0.9, 0.8, 0.7);
    cl_uint seed = 500;
    for (double ior : {1.5046, 1.7, 4.0})
        for (bool from_back : {false, true})
            for (double degrees : {0.0, 45.0, 75.0, 89.0}) {
                const double theta = degrees * kPi / 180.0;
                const D3 v(std::sin(theta), 0.0, std::cos(theta));
                const double r = ref_fresnel_dielectric(theta, ior);
                const WpMaterial m = dielectric_material(WP_MATERIAL_THINDIELECTRIC, ior,
                                                         reflectance, transmittance);
                INFO("ior " << ior << (from_back ? " from the back" : " from the front")
                            << ", incidence " << degrees);
                check_lobes(run_sample(m, kUp, -v, seed++, kCount, from_back), -v, kUp,
                            2.0 * r / (1.0 + r), -v, reflectance, transmittance, 1.0);
            }
}

// ---- plastic ---------------------------------------------------------------------

struct Plastic {
    double eta = 1.49;
    D3 diffuse{0.5};
    D3 specular{1.0};
    double fdr_int = 0.6;
    double specular_weight = 0.5;
    bool nonlinear = false;
};

WpMaterial device_material(const Plastic& p) {
    WpMaterial m{};
    m.kind = WP_MATERIAL_PLASTIC;
    m.eta = to_float4(D3(p.eta));
    m.reflectance = to_float4(p.diffuse);
    m.specular = to_float4(p.specular);
    m.fdr_int = static_cast<float>(p.fdr_int);
    m.specular_weight = static_cast<float>(p.specular_weight);
    m.nonlinear = p.nonlinear ? 1u : 0u;
    return m;
}

// The coating's reflectance, by Fresnel's laws in double precision.
double ref_plastic_fresnel(const Plastic& p, double cos_theta) {
    return ref_fresnel_dielectric(std::acos(std::clamp(cos_theta, 0.0, 1.0)), p.eta);
}

double ref_plastic_specular_probability(const Plastic& p, double f_i) {
    const double s = f_i * p.specular_weight, d = (1.0 - f_i) * (1.0 - p.specular_weight);
    return s / (s + d);
}

// pi f of the base through the coating (kernels/bsdf/plastic.h's formula).
D3 ref_plastic_eval_pi(const Plastic& p, const D3& v, const D3& l) {
    if (!(v.z > 0.0 && l.z > 0.0))
        return D3(0.0);
    const D3 base =
        p.nonlinear ? p.diffuse / (D3(1.0) - p.diffuse * p.fdr_int) : p.diffuse / (1.0 - p.fdr_int);
    return base * ((1.0 - ref_plastic_fresnel(p, v.z)) * (1.0 - ref_plastic_fresnel(p, l.z)) /
                   (p.eta * p.eta));
}

double ref_plastic_pdf(const Plastic& p, const D3& v, const D3& l) {
    if (!(v.z > 0.0 && l.z > 0.0))
        return 0.0;
    return (1.0 - ref_plastic_specular_probability(p, ref_plastic_fresnel(p, v.z))) * l.z / kPi;
}

std::vector<Plastic> plastics() {
    Plastic polypropylene; // Mitsuba's defaults
    Plastic saturated;
    saturated.eta = 1.9;
    saturated.diffuse = D3(0.9, 0.4, 0.1);
    saturated.specular = D3(0.8, 0.9, 1.0);
    saturated.fdr_int = 0.75;
    saturated.specular_weight = 0.6;
    saturated.nonlinear = true;
    return {polypropylene, saturated};
}

TEST_CASE("plastic: eval and pdf match the double-precision reference", "[cl][bsdf]") {
    for (const Plastic& p : plastics())
        for (double degrees : {0.0, 30.0, 60.0, 85.0}) {
            const double theta = degrees * kPi / 180.0;
            const D3 v(std::sin(theta), 0.0, std::cos(theta));
            std::vector<cl_float4> wo, wi;
            for (double c : {-0.5, 0.01, 0.2, 0.5, 0.8, 0.99})
                for (double phi : {0.0, 1.0, 2.5}) {
                    wo.push_back(to_float4(-v));
                    wi.push_back(to_float4(direction(c, phi)));
                }
            const std::vector<cl_float4> got = run_eval(device_material(p), kUp, wo, wi);
            for (std::size_t i = 0; i < wo.size(); ++i) {
                const D3 vf = -from_float4(wo[i]), lf = from_float4(wi[i]);
                const D3 f = ref_plastic_eval_pi(p, vf, lf);
                const double pdf = ref_plastic_pdf(p, vf, lf);
                INFO("eta " << p.eta << ", incidence " << degrees << ", out cos " << lf.z);
                for (int ch = 0; ch < 3; ++ch)
                    CHECK(std::fabs(got[i].s[ch] - f[ch]) <= 1e-4 * f[ch] + 1e-6);
                CHECK(std::fabs(got[i].s[3] - pdf) <= 1e-4 * pdf + 1e-6);
            }
        }
}

TEST_CASE("plastic: the coating's share, the base's directions (chi-square) and every weight",
          "[cl][bsdf][statistical]") {
    constexpr std::size_t kSamples = 1u << 18;
    const double incident_degrees[] = {0.0, 50.0, 80.0};
    const double significance = 0.01 / double(plastics().size() * std::size(incident_degrees));
    cl_uint seed = 700;
    for (const Plastic& p : plastics())
        for (double degrees : incident_degrees) {
            const double theta = degrees * kPi / 180.0;
            const D3 v = glm::normalize(
                from_float4(to_float4(D3(std::sin(theta) * std::cos(0.4),
                                         std::sin(theta) * std::sin(0.4), std::cos(theta)))));
            const Samples s = run_sample(device_material(p), kUp, -v, seed++, kSamples);
            const double f_i = ref_plastic_fresnel(p, v.z);
            const double p_specular = ref_plastic_specular_probability(p, f_i);
            INFO("eta " << p.eta << ", incidence " << degrees << ": coating probability "
                        << p_specular);
            // The base's directions against its density (p_diffuse cos / pi).
            const ChiSquare result =
                chi_square(observed_counts(s),
                           expected_counts_of([&](const D3& l) { return ref_plastic_pdf(p, v, l); },
                                              kSamples));
            INFO("chi-square " << result.statistic << ", " << result.dof << " dof, p "
                               << result.p_value);
            CHECK(result.outside == 0);
            CHECK(result.p_value > significance);
            std::size_t specular = 0, wrong = 0;
            for (std::size_t i = 0; i < kSamples; ++i) {
                const auto flags = cl_uint(s.weight[i].s[3]);
                const D3 l = from_float4(s.direction[i]);
                D3 expected;
                if (flags == (WP_BSDF_REFLECTION | WP_BSDF_DELTA)) {
                    ++specular;
                    expected = p.specular * (f_i / p_specular);
                    wrong += glm::length(l - D3(-v.x, -v.y, v.z)) > 2e-6 ? 1 : 0;
                } else if (flags == (WP_BSDF_REFLECTION | WP_BSDF_DIFFUSE)) {
                    const double pdf = ref_plastic_pdf(p, v, l);
                    expected = ref_plastic_eval_pi(p, v, l) / kPi * l.z / pdf;
                    wrong += std::fabs(s.direction[i].s[3] - pdf) > 1e-4 * pdf + 1e-6 ? 1 : 0;
                } else {
                    ++wrong; // the base's cosine sampling never leaves the hemisphere
                    continue;
                }
                for (int ch = 0; ch < 3; ++ch)
                    wrong +=
                        std::fabs(s.weight[i].s[ch] - expected[ch]) > 2e-4 * expected[ch] + 1e-6
                            ? 1
                            : 0;
            }
            CHECK(wrong == 0);
            const double share = double(specular) / double(kSamples);
            CHECK(std::fabs(share - p_specular) <=
                  5.0 * std::sqrt(p_specular * (1.0 - p_specular) / double(kSamples)));
        }
}

TEST_CASE("plastic: the directional albedo is the coating's plus the base's integral",
          "[cl][bsdf][statistical]") {
    // The mean sample weight against F(cos_i) specular + the integral of
    // f cos over the hemisphere by quadrature (Simpson in cos theta; f does
    // not depend on phi). A white base under a clear coating loses nothing:
    // its albedo is 1 up to the diffuse Fresnel fits' error (about 0.1 %).
    constexpr std::size_t kSamples = 1u << 16;
    std::vector<Plastic> cases = plastics();
    Plastic white;
    white.diffuse = D3(1.0);
    white.fdr_int = 0.5908; // Mitsuba's fit (Egan and Hilgeman) at 1 / 1.49
    cases.push_back(white);
    cl_uint seed = 900;
    for (const Plastic& p : cases)
        for (double degrees : {0.0, 45.0, 75.0, 89.0}) {
            const double theta = degrees * kPi / 180.0;
            const D3 v(std::sin(theta), 0.0, std::cos(theta));
            const Samples s = run_sample(device_material(p), kUp, -v, seed++, kSamples);
            constexpr int kSteps = 2000;
            D3 integral(0.0);
            for (int a = 0; a <= kSteps; ++a) {
                const double w = (a == 0 || a == kSteps) ? 1.0 : (a % 2 ? 4.0 : 2.0);
                const double c = double(a) / kSteps;
                integral += w * ref_plastic_eval_pi(p, v, direction(c, 0.0)) / kPi * c;
            }
            integral *= 2.0 * kPi / (3.0 * kSteps);
            const D3 albedo = p.specular * ref_plastic_fresnel(p, v.z) + integral;
            for (int ch = 0; ch < 3; ++ch) {
                double sum = 0.0, sum_squares = 0.0;
                for (const cl_float4& w : s.weight) {
                    sum += w.s[ch];
                    sum_squares += double(w.s[ch]) * w.s[ch];
                }
                const double mean = sum / kSamples;
                const double sigma =
                    std::sqrt(std::max(0.0, sum_squares / kSamples - mean * mean) / kSamples);
                INFO("eta " << p.eta << ", incidence " << degrees << ", channel " << ch
                            << ": albedo " << mean << " +- " << sigma << ", quadrature "
                            << albedo[ch]);
                CHECK(std::fabs(mean - albedo[ch]) <= 5.0 * sigma + 1e-4);
                if (p.diffuse == D3(1.0) && p.specular == D3(1.0))
                    CHECK(std::fabs(mean - 1.0) <= 5.0 * sigma + 5e-3);
            }
        }
}

// ---- rough dielectric ---------------------------------------------------------------

struct RoughGlass {
    Rough rough;
    double ior = 1.5046;
    bool from_back = false; // the ray arrives from inside: eta = 1 / ior
    D3 reflectance{1.0}, transmittance{1.0};
    double eta() const { return from_back ? 1.0 / ior : ior; }
};

WpMaterial device_material(const RoughGlass& g) {
    WpMaterial m =
        dielectric_material(WP_MATERIAL_ROUGHDIELECTRIC, g.ior, g.reflectance, g.transmittance);
    m.distribution = g.rough.ggx ? WP_MICROFACET_GGX : WP_MICROFACET_BECKMANN;
    m.alpha_u = static_cast<float>(g.rough.alpha_u);
    m.alpha_v = static_cast<float>(g.rough.alpha_v);
    return m;
}

// pi f (radiance) and the density of l, local frame, v towards the viewer
// (v.z > 0), after Walter et al. 2007 in double precision: the half vector
// h_r = v + l or h_t = -(v + eta l), the Jacobians 1 / (4 |l.h|) and
// eta^2 |l.h| / (v.h + eta l.h)^2, the densities of the visible normals, and
// the side picked by the microfacet's Fresnel reflectance F(v.h) (Mitsuba
// 3's sampler).
struct RoughEval {
    D3 f_pi{0.0};
    double pdf = 0.0;
};

RoughEval ref_rough_glass(const RoughGlass& g, const D3& v, const D3& l) {
    RoughEval out;
    if (!(v.z > 0.0) || l.z == 0.0)
        return out;
    const bool reflect = l.z > 0.0;
    const double eta = g.eta();
    D3 h = glm::normalize(reflect ? v + l : -(v + eta * l));
    if (h.z < 0.0)
        h = -h;
    const double vh = glm::dot(v, h), lh = glm::dot(l, h);
    if (!(vh > 0.0) || !(reflect ? lh > 0.0 : lh < 0.0))
        return out;
    const double fresnel = ref_fresnel_dielectric(std::acos(std::min(1.0, vh)), eta);
    const double d = ref_d(g.rough, h);
    const double gg = ref_g1(g.rough, v, h) * ref_g1(g.rough, l, h);
    const double visible = d * ref_g1(g.rough, v, h) * vh / v.z;
    if (reflect) {
        out.f_pi = g.reflectance * (kPi * fresnel * d * gg / (4.0 * v.z * l.z));
        out.pdf = fresnel * visible / (4.0 * vh);
    } else {
        const double den = vh + eta * lh;
        out.f_pi = g.transmittance * (kPi * (1.0 - fresnel) * d * gg * vh * std::fabs(lh) /
                                      (v.z * std::fabs(l.z) * den * den));
        out.pdf = (1.0 - fresnel) * visible * eta * eta * std::fabs(lh) / (den * den);
    }
    return out;
}

std::vector<RoughGlass> rough_glasses() {
    std::vector<RoughGlass> out;
    for (bool ggx : {true, false})
        for (bool from_back : {false, true})
            for (double alpha : {0.1, 0.5}) {
                RoughGlass g;
                g.rough = Rough{ggx, alpha, alpha};
                g.from_back = from_back;
                out.push_back(g);
            }
    RoughGlass anisotropic;
    anisotropic.rough = Rough{true, 0.2, 0.5};
    anisotropic.ior = 2.419;
    anisotropic.reflectance = D3(1.0, 0.8, 0.6);
    anisotropic.transmittance = D3(0.5, 0.7, 0.9);
    out.push_back(anisotropic);
    return out;
}

std::string describe(const RoughGlass& g) {
    std::ostringstream s;
    s << (g.rough.ggx ? "ggx" : "beckmann") << " alpha " << g.rough.alpha_u << "/"
      << g.rough.alpha_v << " ior " << g.ior << (g.from_back ? " from inside" : " from outside");
    return s.str();
}

cl_float4 normal_arg(const RoughGlass& g) {
    cl_float4 n = to_float4(kUp);
    n.s[3] = g.from_back ? 1.0f : 0.0f;
    return n;
}

TEST_CASE("roughdielectric: eval and pdf match the double-precision reference", "[cl][bsdf]") {
    for (const RoughGlass& g : rough_glasses())
        for (double degrees : {0.0, 35.0, 70.0}) {
            const double theta = degrees * kPi / 180.0;
            const D3 v(std::sin(theta) * std::cos(0.3), std::sin(theta) * std::sin(0.3),
                       std::cos(theta));
            std::vector<cl_float4> wo, wi;
            for (double c : {-0.95, -0.6, -0.2, -0.02, 0.02, 0.3, 0.7, 0.99})
                for (double phi : {0.1, 2.0, 3.5}) {
                    wo.push_back(to_float4(-v));
                    wi.push_back(to_float4(direction(c, phi)));
                }
            cl::Kernel kernel(bsdf_program(), "bsdf_eval");
            cl::Buffer material = upload(std::vector<WpMaterial>{device_material(g)});
            cl::Buffer wo_buffer = upload(wo), wi_buffer = upload(wi);
            cl::Buffer out = upload(std::vector<cl_float4>(wo.size()));
            set_args(kernel, material, normal_arg(g), static_cast<cl_uint>(wo.size()), wo_buffer,
                     wi_buffer, out);
            launch(kernel, wo.size());
            const std::vector<cl_float4> got = download<cl_float4>(out, wo.size());
            for (std::size_t i = 0; i < wo.size(); ++i) {
                const RoughEval want = ref_rough_glass(g, -from_float4(wo[i]), from_float4(wi[i]));
                INFO(describe(g) << ", incidence " << degrees << ", out " << wi[i].s[0] << " "
                                 << wi[i].s[1] << " " << wi[i].s[2]);
                for (int ch = 0; ch < 3; ++ch)
                    CHECK(std::fabs(got[i].s[ch] - want.f_pi[ch]) <= 2e-3 * want.f_pi[ch] + 1e-5);
                CHECK(std::fabs(got[i].s[3] - want.pdf) <= 2e-3 * want.pdf + 1e-5);
            }
        }
}

Samples run_sample(const RoughGlass& g, const D3& wo, cl_uint seed, std::size_t count) {
    return run_sample(device_material(g), kUp, wo, seed, count, g.from_back);
}

TEST_CASE("roughdielectric: sample() follows pdf() over the sphere (chi-square), and every "
          "weight is eval cos / pdf",
          "[cl][bsdf][statistical]") {
    constexpr std::size_t kSamples = 1u << 18;
    const double incident_degrees[] = {0.0, 45.0, 75.0};
    const std::vector<RoughGlass> glasses = rough_glasses();
    const double significance = 0.01 / double(glasses.size() * std::size(incident_degrees));
    cl_uint seed = 1100;
    for (const RoughGlass& g : glasses)
        for (double degrees : incident_degrees) {
            const double theta = degrees * kPi / 180.0;
            const D3 v = glm::normalize(
                from_float4(to_float4(D3(std::sin(theta) * std::cos(0.4),
                                         std::sin(theta) * std::sin(0.4), std::cos(theta)))));
            const Samples s = run_sample(g, -v, seed++, kSamples);
            const ChiSquare result = chi_square(
                observed_counts(s),
                expected_counts_of([&](const D3& l) { return ref_rough_glass(g, v, l).pdf; },
                                   kSamples));
            INFO(describe(g) << ", incidence " << degrees << ": chi-square " << result.statistic
                             << ", " << result.dof << " dof, p " << result.p_value);
            CHECK(result.outside == 0);
            CHECK(result.p_value > significance);
            std::size_t wrong = 0, checked = 0;
            for (std::size_t i = 0; i < kSamples; i += 16) {
                const auto flags = cl_uint(s.weight[i].s[3]);
                if (flags == 0u)
                    continue;
                const D3 l = from_float4(s.direction[i]);
                const RoughEval want = ref_rough_glass(g, v, l);
                const bool transmitted = flags == (WP_BSDF_TRANSMISSION | WP_BSDF_GLOSSY);
                wrong += transmitted == (l.z < 0.0) ? 0 : 1;
                wrong += std::fabs(s.direction[i].s[3] - want.pdf) > 2e-3 * want.pdf + 1e-5;
                for (int ch = 0; ch < 3; ++ch) {
                    const double w = want.f_pi[ch] / kPi * std::fabs(l.z) / want.pdf;
                    wrong += std::fabs(s.weight[i].s[ch] - w) > 2e-3 * w + 1e-5 ? 1 : 0;
                }
                ++checked;
            }
            INFO(wrong << " wrong of " << checked << " samples checked");
            CHECK(wrong == 0);
            CHECK(checked > kSamples / 32);
            // The side picked by the microfacet's F(v.h) leaves only l's
            // masking in a weight: at most the tint, times (1 / eta)^2 through
            // the interface (and Beckmann's rational G1, Walter's fit, rises to
            // 1.00006). Picked by the interface's F(v.z) within [0.05, 0.95]
            // a weight reached 20 times that.
            double heaviest = 0.0;
            for (std::size_t i = 0; i < kSamples; ++i) {
                const auto flags = cl_uint(s.weight[i].s[3]);
                if (flags == 0u)
                    continue;
                const bool transmitted = flags == (WP_BSDF_TRANSMISSION | WP_BSDF_GLOSSY);
                const D3 tint = transmitted ? g.transmittance / (g.eta() * g.eta()) : g.reflectance;
                for (int ch = 0; ch < 3; ++ch)
                    heaviest = std::max(heaviest, s.weight[i].s[ch] / tint[ch]);
            }
            INFO("the heaviest weight is " << heaviest << " of its bound");
            CHECK(heaviest <= 1.0001);
        }
}

TEST_CASE("roughdielectric: white furnace", "[cl][bsdf][statistical]") {
    // What a lossless rough interface lets through or reflects, counted as
    // energy (transmitted weights times eta^2, undoing the radiance factor):
    // at most 1, and 1 within 1 % for a nearly smooth one away from grazing
    // (the single-scattering model loses energy with roughness, as
    // roughconductor's furnace shows).
    constexpr std::size_t kSamples = 1u << 16;
    cl_uint seed = 1300;
    for (const RoughGlass& base : rough_glasses())
        for (double alpha : {0.01, base.rough.alpha_u})
            for (double degrees : {0.0, 40.0, 80.0}) {
                RoughGlass g = base;
                g.rough.alpha_u = g.rough.alpha_v = alpha;
                g.reflectance = g.transmittance = D3(1.0);
                const double theta = degrees * kPi / 180.0;
                const D3 v(std::sin(theta), 0.0, std::cos(theta));
                const Samples s = run_sample(g, -v, seed++, kSamples);
                double sum = 0.0, sum_squares = 0.0;
                for (std::size_t i = 0; i < kSamples; ++i) {
                    const bool transmitted = s.direction[i].s[2] < 0.0f;
                    const double w = s.weight[i].s[0] * (transmitted ? g.eta() * g.eta() : 1.0);
                    sum += w;
                    sum_squares += w * w;
                }
                const double mean = sum / kSamples;
                const double sigma =
                    std::sqrt(std::max(0.0, sum_squares / kSamples - mean * mean) / kSamples);
                INFO(describe(g) << ", incidence " << degrees << ": albedo " << mean << " +- "
                                 << sigma);
                CHECK(mean <= 1.0 + 5.0 * sigma + 1e-4);
                if (alpha <= 0.01 && degrees <= 40.0)
                    CHECK(std::fabs(mean - 1.0) <= 5.0 * sigma + 1e-2);
            }
}

// ---- rough plastic ------------------------------------------------------------------

namespace {

struct RoughPlastic {
    Rough rough{true, 0.1, 0.1};
    double ior = 1.49 / 1.000277; // Mitsuba's defaults: polypropylene in air
    D3 diffuse{0.5};
    D3 specular{1.0};
    bool nonlinear = false;
    // The coating's integrals, as the host computes them for the device.
    wp::RoughCoating coating() const {
        return wp::rough_coating(rough.ggx ? wp::MicrofacetDistribution::Ggx
                                           : wp::MicrofacetDistribution::Beckmann,
                                 rough.alpha_u, ior);
    }
    double specular_weight() const {
        const double s = (specular.x + specular.y + specular.z) / 3.0;
        const double d = (diffuse.x + diffuse.y + diffuse.z) / 3.0;
        return s / (s + d);
    }
};

std::string describe(const RoughPlastic& p) {
    std::ostringstream s;
    s << (p.rough.ggx ? "ggx" : "beckmann") << " alpha " << p.rough.alpha_u << " eta " << p.ior
      << (p.nonlinear ? " nonlinear" : "") << " diffuse " << p.diffuse.x << "," << p.diffuse.y
      << "," << p.diffuse.z;
    return s.str();
}

WpMaterial device_material(const RoughPlastic& p, const wp::RoughCoating& c) {
    WpMaterial m{};
    m.kind = WP_MATERIAL_ROUGHPLASTIC;
    m.eta = to_float4(D3(p.ior));
    m.reflectance = to_float4(p.diffuse);
    m.specular = to_float4(p.specular);
    m.distribution = p.rough.ggx ? WP_MICROFACET_GGX : WP_MICROFACET_BECKMANN;
    m.alpha_u = m.alpha_v = static_cast<float>(p.rough.alpha_u);
    m.fdr_int = static_cast<float>(c.internal_reflectance);
    m.specular_weight = static_cast<float>(p.specular_weight());
    m.nonlinear = p.nonlinear ? 1u : 0u;
    for (int i = 0; i < WP_ROUGH_TRANSMITTANCE_RES; ++i)
        m.rough_transmittance[i] = static_cast<float>(c.transmittance[static_cast<std::size_t>(i)]);
    return m;
}

// Mitsuba's lerp_gather of the table, in double.
double ref_transmittance(const wp::RoughCoating& c, double mu) {
    const double x = std::clamp(mu, 0.0, 1.0) * (WP_ROUGH_TRANSMITTANCE_RES - 1);
    const int i = std::min(int(x), WP_ROUGH_TRANSMITTANCE_RES - 2);
    const double t0 = c.transmittance[static_cast<std::size_t>(i)];
    const double t1 = c.transmittance[static_cast<std::size_t>(i) + 1];
    return t0 + (t1 - t0) * (x - i);
}

// pi f and the density of l, local frame (Mitsuba's roughplastic eval and
// pdf in double precision; the formulas of kernels/bsdf/roughplastic.h).
RoughEval ref_rough_plastic(const RoughPlastic& p, const wp::RoughCoating& c, const D3& v,
                            const D3& l) {
    RoughEval out;
    if (!(v.z > 0.0 && l.z > 0.0))
        return out;
    const D3 h = glm::normalize(v + l);
    const double vh = glm::dot(v, h);
    const double fresnel = ref_fresnel_dielectric(std::acos(std::min(1.0, vh)), p.ior);
    const double d = ref_d(p.rough, h);
    const double g = ref_g1(p.rough, v, h) * ref_g1(p.rough, l, h);
    const double t_i = ref_transmittance(c, v.z), t_o = ref_transmittance(c, l.z);
    const double r = c.internal_reflectance;
    const D3 base = p.nonlinear ? p.diffuse / (D3(1.0) - p.diffuse * r) : p.diffuse / (1.0 - r);
    out.f_pi = p.specular * (kPi * fresnel * d * g / (4.0 * v.z * l.z)) +
               base * (t_i * t_o / (p.ior * p.ior));
    const double w = p.specular_weight();
    const double s = (1.0 - t_i) * w, dd = t_i * (1.0 - w);
    const double p_specular = s / (s + dd);
    out.pdf = p_specular * d * ref_g1(p.rough, v, h) / v.z / 4.0 + (1.0 - p_specular) * l.z / kPi;
    return out;
}

std::vector<RoughPlastic> rough_plastics() {
    RoughPlastic defaults; // Mitsuba's defaults but GGX
    RoughPlastic beckmann;
    beckmann.rough = Rough{false, 0.3, 0.3};
    beckmann.ior = 1.7;
    beckmann.diffuse = D3(0.9, 0.4, 0.1);
    beckmann.specular = D3(0.8, 0.9, 1.0);
    beckmann.nonlinear = true;
    RoughPlastic rough;
    rough.rough = Rough{true, 0.6, 0.6};
    rough.ior = 1.33;
    rough.diffuse = D3(0.1, 0.2, 0.7);
    return {defaults, beckmann, rough};
}

D3 incident(double degrees) {
    const double theta = degrees * kPi / 180.0;
    return glm::normalize(from_float4(to_float4(
        D3(std::sin(theta) * std::cos(0.4), std::sin(theta) * std::sin(0.4), std::cos(theta)))));
}

} // namespace

TEST_CASE("roughplastic: eval and pdf match the double-precision reference", "[cl][bsdf]") {
    const D3 normals[] = {kUp, glm::normalize(D3(0.3, -0.5, 0.8))};
    std::vector<D3> v_local, l_local;
    for (double cv : {1.0, 0.9, 0.6, 0.3, 0.05, -0.4})
        for (double pv : {0.0, 1.1})
            for (double cl : {0.95, 0.7, 0.4, 0.1, -0.2})
                for (double pl : {0.0, 0.9, 2.5, 3.14, 4.4}) {
                    v_local.push_back(direction(cv, pv));
                    l_local.push_back(direction(cl, pl));
                }
    for (const D3& n : normals)
        for (const RoughPlastic& p : rough_plastics()) {
            INFO(describe(p) << ", normal " << n.x << " " << n.y << " " << n.z);
            const wp::RoughCoating c = p.coating();
            std::vector<cl_float4> wo, wi;
            for (std::size_t i = 0; i < v_local.size(); ++i) {
                wo.push_back(to_float4(-to_world(v_local[i], n)));
                wi.push_back(to_float4(to_world(l_local[i], n)));
            }
            const std::vector<cl_float4> got = run_eval(device_material(p, c), n, wo, wi);
            D3 t, b;
            const D3 nf = from_float4(to_float4(n));
            make_basis(nf, t, b);
            std::size_t nonzero = 0;
            for (std::size_t i = 0; i < got.size(); ++i) {
                const D3 vw = -from_float4(wo[i]), lw = from_float4(wi[i]);
                const D3 v(glm::dot(vw, t), glm::dot(vw, b), glm::dot(vw, nf));
                const D3 l(glm::dot(lw, t), glm::dot(lw, b), glm::dot(lw, nf));
                const RoughEval r = ref_rough_plastic(p, c, v, l);
                INFO("v " << v.x << " " << v.y << " " << v.z << ", l " << l.x << " " << l.y << " "
                          << l.z);
                for (int ch = 0; ch < 3; ++ch)
                    CHECK(std::fabs(got[i].s[ch] - r.f_pi[ch]) <= 1e-3 * r.f_pi[ch] + 1e-6);
                CHECK(std::fabs(got[i].s[3] - r.pdf) <= 1e-3 * r.pdf + 1e-6);
                nonzero += r.pdf > 1e-3 ? 1 : 0;
            }
            CHECK(nonzero > got.size() / 3); // the base is seen from the whole hemisphere
        }
}

TEST_CASE("roughplastic: eval is reciprocal", "[cl][bsdf]") {
    // T(cos_i) T(cos_o) and the coating's F(v.h) D G / (cos_i cos_o) are
    // symmetric in the two directions; the sampling weight is not (eval only).
    for (const RoughPlastic& p : rough_plastics()) {
        INFO(describe(p));
        const WpMaterial m = device_material(p, p.coating());
        std::vector<cl_float4> a, b, b_in, a_out;
        for (double cv : {0.95, 0.6, 0.2})
            for (double cl : {0.9, 0.5, 0.15})
                for (double phi : {0.0, 0.7, 2.0, 3.0, 5.5}) {
                    a.push_back(to_float4(-direction(cv, 0.3)));
                    b.push_back(to_float4(direction(cl, phi)));
                    b_in.push_back(to_float4(-direction(cl, phi)));
                    a_out.push_back(to_float4(direction(cv, 0.3)));
                }
        const auto forward = run_eval(m, kUp, a, b);
        const auto backward = run_eval(m, kUp, b_in, a_out);
        for (std::size_t i = 0; i < a.size(); ++i)
            for (int ch = 0; ch < 3; ++ch)
                CHECK(std::fabs(forward[i].s[ch] - backward[i].s[ch]) <=
                      1e-4 * std::fabs(forward[i].s[ch]) + 1e-7);
    }
}

TEST_CASE("roughplastic: sample() follows pdf() (chi-square), its weights are eval cos / pdf",
          "[cl][bsdf][statistical]") {
    constexpr std::size_t kSamples = 1u << 18;
    const double incident_degrees[] = {0.0, 40.0, 75.0};
    const std::vector<RoughPlastic> materials = rough_plastics();
    const double significance = 0.01 / double(materials.size() * std::size(incident_degrees));
    cl_uint seed = 1300;
    double lowest_p = 1.0;
    for (const RoughPlastic& p : materials) {
        const wp::RoughCoating c = p.coating();
        for (double degrees : incident_degrees) {
            const D3 v = incident(degrees);
            const Samples s = run_sample(device_material(p, c), kUp, -v, seed++, kSamples);
            const ChiSquare result = chi_square(
                observed_counts(s),
                expected_counts_of([&](const D3& l) { return ref_rough_plastic(p, c, v, l).pdf; },
                                   kSamples));
            INFO(describe(p) << ", incidence " << degrees << " degrees: chi-square "
                             << result.statistic << ", " << result.dof << " dof, p "
                             << result.p_value);
            CHECK(result.outside == 0);
            CHECK(result.p_value > significance);
            lowest_p = std::min(lowest_p, result.p_value);
            std::size_t valid = 0, wrong = 0, glossy = 0;
            for (std::size_t i = 0; i < kSamples; ++i) {
                const auto flags = cl_uint(s.weight[i].s[3]);
                if (flags == 0u)
                    continue; // reflected below the horizon by a microfacet
                ++valid;
                glossy += flags == (WP_BSDF_REFLECTION | WP_BSDF_GLOSSY) ? 1 : 0;
                wrong += flags == (WP_BSDF_REFLECTION | WP_BSDF_GLOSSY) ||
                                 flags == (WP_BSDF_REFLECTION | WP_BSDF_DIFFUSE)
                             ? 0
                             : 1;
                const D3 l = from_float4(s.direction[i]);
                const RoughEval r = ref_rough_plastic(p, c, v, l);
                wrong += std::fabs(s.direction[i].s[3] - r.pdf) > 2e-3 * r.pdf + 1e-6 ? 1 : 0;
                for (int ch = 0; ch < 3; ++ch) {
                    const double expected = r.f_pi[ch] / kPi * l.z / r.pdf;
                    wrong += std::fabs(s.weight[i].s[ch] - expected) > 2e-3 * expected + 1e-6;
                }
            }
            CHECK(wrong == 0);
            CHECK(valid > kSamples * 3 / 4);
            CHECK(glossy > 0);
        }
    }
    INFO("lowest p-value " << lowest_p);
    CHECK(lowest_p > significance);
}

TEST_CASE("roughplastic: white furnace (the albedo is the integral of f cos, at most 1, and "
          "Mitsuba's)",
          "[cl][bsdf][statistical]") {
    // The mean sample weight against the directional albedo by quadrature of
    // the reference's f cos over the hemisphere (Simpson in cos theta and
    // phi), and never above 1. A white base under a clear coating does not
    // keep all the light in this model (the coating's multiple scattering
    // is dropped, and R_int is Mitsuba's coarse estimate): its albedo is
    // Mitsuba 3.9.1's own, measured as the mean of its sample() weights
    // (400000 samples each, scalar_rgb: `python3 tools/mitsuba_roughplastic.py albedo`).
    constexpr std::size_t kSamples = 1u << 16;
    struct Case {
        RoughPlastic p;
        double mitsuba[3], mitsuba_error[3]; // at 0, 45 and 75 degrees; 0: none
    };
    std::vector<Case> cases;
    for (const RoughPlastic& p : rough_plastics())
        cases.push_back({p, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}});
    RoughPlastic white;
    white.diffuse = D3(1.0);
    cases.push_back({white, {0.91015, 0.90921, 0.89542}, {0.00012, 0.00012, 0.00023}});
    RoughPlastic white_beckmann = white;
    white_beckmann.rough = Rough{false, 0.2, 0.2};
    white_beckmann.nonlinear = true;
    cases.push_back({white_beckmann, {0.93109, 0.93146, 0.90036}, {0.00011, 0.00011, 0.00027}});
    cl_uint seed = 1500;
    for (const Case& k : cases) {
        const RoughPlastic& p = k.p;
        const wp::RoughCoating c = p.coating();
        const double incidences[] = {0.0, 45.0, 75.0};
        for (int a_index = 0; a_index < 3; ++a_index) {
            const double degrees = incidences[a_index];
            const D3 v = incident(degrees);
            const Samples s = run_sample(device_material(p, c), kUp, -v, seed++, kSamples);
            constexpr int kCos = 1200, kPhi = 600;
            D3 albedo(0.0);
            for (int a = 0; a <= kCos; ++a) {
                const double wa = (a == 0 || a == kCos) ? 1.0 : (a % 2 ? 4.0 : 2.0);
                const double ct = double(a) / kCos;
                for (int b = 0; b <= kPhi; ++b) {
                    const double wb = (b == 0 || b == kPhi) ? 1.0 : (b % 2 ? 4.0 : 2.0);
                    const D3 l = direction(ct, 2.0 * kPi * b / kPhi);
                    albedo += wa * wb * ref_rough_plastic(p, c, v, l).f_pi / kPi * ct;
                }
            }
            albedo *= (1.0 / (3.0 * kCos)) * (2.0 * kPi / (3.0 * kPhi));
            for (int ch = 0; ch < 3; ++ch) {
                double sum = 0.0, sum_squares = 0.0;
                for (const cl_float4& w : s.weight) {
                    sum += w.s[ch];
                    sum_squares += double(w.s[ch]) * w.s[ch];
                }
                const double mean = sum / kSamples;
                const double sigma =
                    std::sqrt(std::max(0.0, sum_squares / kSamples - mean * mean) / kSamples);
                INFO(describe(p) << ", incidence " << degrees << ", channel " << ch << ": albedo "
                                 << mean << " +- " << sigma << ", quadrature " << albedo[ch]
                                 << ", Mitsuba " << k.mitsuba[a_index] << " +- "
                                 << k.mitsuba_error[a_index]);
                CHECK(std::fabs(mean - albedo[ch]) <= 5.0 * sigma + 1e-3 * albedo[ch]);
                CHECK(mean <= 1.0 + 5.0 * sigma);
                if (k.mitsuba[a_index] > 0.0)
                    CHECK(std::fabs(mean - k.mitsuba[a_index]) <=
                          5.0 * std::hypot(sigma, k.mitsuba_error[a_index]));
            }
        }
    }
}
