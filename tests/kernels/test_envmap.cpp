// The envmap emitter (kernels/lights/envmap.h): the host's double-precision
// reference (render/environment_tables.hpp) against Mitsuba 3.9.1's own
// envmap plugin, values measured with its Python API
// (mi.load_dict({'type': 'envmap', 'bitmap': mi.Bitmap(data), ...}).eval(si)
// with si.wi = -d), so that wavepath's conventions (which way is up, where
// u = 0 lies, texel-centred columns, corner-aligned rows, the padding of
// small images) are Mitsuba's; then the device against that reference, and
// the device's sampling against its density by a chi-square test.
#include "render/device_scene.hpp"
#include "render/environment_tables.hpp"
#include "support/chi_square.hpp"
#include "support/float_image.hpp"
#include "support/kernel_test_util.hpp"
#include "support/scene_builder.hpp"

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

using namespace wp;
using namespace wp::test;

namespace {

const char* const kEnvmapSource = R"CL(
#include "lights/envmap.h"

__kernel void evaluate(__global const WpEmitter* emitter, __global const uint* texels,
                       __global const float* cdf, uint count, __global const float4* directions,
                       __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float3 d = directions[i].xyz;
    out[i] = (float4)(wp_envmap_radiance(texels, emitter, d), wp_envmap_pdf(cdf, emitter, d));
}

__kernel void search(__global const float* cdf, __global const uint* sizes,
                     __global const float* numbers, uint count, __global uint* out) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    out[i] = wp_envmap_search(cdf + 256u * i, sizes[i], numbers[i]);
}

__kernel void sample(__global const WpEmitter* emitter, __global const uint* texels,
                     __global const float* cdf, uint count, __global const float2* numbers,
                     __global float4* out, __global float4* radiance_out) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float3 d, radiance;
    float pdf;
    wp_envmap_sample(texels, cdf, emitter, numbers[i].x, numbers[i].y, &d, &pdf, &radiance);
    out[i] = (float4)(d, pdf);
    radiance_out[i] = (float4)(radiance, 0.0f);
}
)CL";

constexpr double kPi = 3.14159265358979323846;

// The image of the Mitsuba measurements: texel (i, j) is (i + 1, 10 (j + 1), 1).
std::shared_ptr<const TextureImage> counting_image(std::uint32_t w, std::uint32_t h) {
    std::vector<glm::dvec3> texels;
    for (std::uint32_t j = 0; j < h; ++j)
        for (std::uint32_t i = 0; i < w; ++i)
            texels.push_back({i + 1.0, 10.0 * (j + 1), 1.0});
    return float_image(w, h, texels);
}

// The map-frame direction of map coordinates (u, v), Mitsuba's formula.
glm::dvec3 direction_of(double u, double v) {
    const double phi = 2.0 * kPi * u, theta = kPi * v;
    return {std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta)};
}

void check_close(const glm::dvec3& got, const glm::dvec3& expected, double tolerance) {
    INFO("wavepath " << got.x << " " << got.y << " " << got.z << ", Mitsuba " << expected.x << " "
                     << expected.y << " " << expected.z);
    for (int c = 0; c < 3; ++c)
        CHECK(std::abs(got[c] - expected[c]) <= tolerance * std::max(1.0, std::abs(expected[c])));
}

// A scene holding only an envmap emitter (and a triangle to be a scene),
// flattened as a render flattens it.
DeviceScene flatten_envmap(std::shared_ptr<const TextureImage> image, const glm::dmat3& to_world,
                           double scale) {
    Scene scene;
    const std::uint32_t white = add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    add_quad(scene, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, white);
    scene.camera = make_camera({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    Emitter e;
    e.kind = EmitterKind::Envmap;
    e.value = glm::dvec3(scale);
    e.to_world = to_world;
    e.image = std::move(image);
    scene.emitters.push_back(e);
    return flatten_scene(scene);
}

// A rotation by `degrees` about `axis`.
glm::dmat3 rotation(double degrees, glm::dvec3 axis) {
    return glm::dmat3(glm::rotate(glm::dmat4(1.0), degrees * kPi / 180.0, glm::normalize(axis)));
}

} // namespace

TEST_CASE("envmap reference: Mitsuba 3.9.1's lookups", "[emitters][envmap]") {
    const EnvironmentTables map = build_environment_tables(*counting_image(4, 3));
    // Along the equator (v = 1/2, row 1): columns are texel-centred and
    // periodic, u = 0 halfway between the last column and the first.
    const struct {
        double u;
        double red;
    } along_u[] = {{0.0, 2.5},   {0.0625, 1.75}, {0.125, 1.0}, {0.25, 1.5},
                   {0.375, 2.0}, {0.5, 2.5},     {0.875, 4.0}, {0.95, 3.1}};
    for (const auto& m : along_u) {
        INFO("u " << m.u);
        check_close(map.radiance(direction_of(m.u, 0.5)), {m.red, 20.0, 1.0}, 1e-5);
    }
    // Down column 0 (u = 1/8): rows corner-aligned, the first at the zenith.
    const struct {
        double v;
        double green;
    } along_v[] = {
        {0.001, 10.02}, {1.0 / 6.0, 13.3333}, {0.25, 15.0}, {0.75, 25.0}, {0.999, 29.98}};
    for (const auto& m : along_v) {
        INFO("v " << m.v);
        check_close(map.radiance(direction_of(0.125, m.v)), {1.0, m.green, 1.0}, 1e-4);
    }
    // Images below 2 x 3 are padded by repeating their last column and row:
    // a 1 x 2 map is 10 at the zenith and 20 from the horizon down; 1 x 1 is
    // constant.
    const EnvironmentTables tall = build_environment_tables(*counting_image(1, 2));
    check_close(tall.radiance({0, 1, 0}), {1, 10, 1}, 1e-6);
    check_close(tall.radiance({0, 0, -1}), {1, 20, 1}, 1e-6);
    check_close(tall.radiance({0, -1, 0}), {1, 20, 1}, 1e-6);
    const EnvironmentTables wide = build_environment_tables(*counting_image(3, 2));
    check_close(wide.radiance({1, 0, 0}), {1.25, 20, 1}, 1e-6);
    check_close(wide.radiance({0, 0, -1}), {2, 20, 1}, 1e-6);
    const EnvironmentTables one = build_environment_tables(*counting_image(1, 1));
    for (const glm::dvec3 d : {glm::dvec3(0, 1, 0), glm::dvec3(0.6, 0, 0.8), glm::dvec3(0, -1, 0)})
        check_close(one.radiance(d), {1, 10, 1}, 1e-6);
}

TEST_CASE("envmap on the device: Mitsuba 3.9.1's to_world and scale", "[kernels][envmap]") {
    // to_world rotates 90 degrees about +y, scale 2 (measured: looking
    // along -z Mitsuba gives (3, 40, 2), along +x and -x (5, 40, 2), along
    // +z (7, 40, 2)).
    const DeviceScene flat = flatten_envmap(counting_image(4, 3), rotation(90.0, {0, 1, 0}), 2.0);
    REQUIRE(flat.emitters.size() == 1);
    const std::vector<cl_float4> directions = {
        {{0, 0, -1, 0}}, {{1, 0, 0, 0}}, {{-1, 0, 0, 0}}, {{0, 0, 1, 0}}};
    const glm::dvec3 expected[] = {{3, 40, 2}, {5, 40, 2}, {5, 40, 2}, {7, 40, 2}};
    cl::Kernel kernel(program(kEnvmapSource, "envmap_test.cl"), "evaluate");
    const cl::Buffer emitter = upload(flat.emitters), texels = upload(flat.texels),
                     cdf = upload(flat.environment_cdf), in = upload(directions),
                     out = upload(std::vector<cl_float4>(directions.size()));
    set_args(kernel, emitter, texels, cdf, static_cast<cl_uint>(directions.size()), in, out);
    launch(kernel, directions.size());
    const std::vector<cl_float4> got = download<cl_float4>(out, directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) {
        INFO("direction " << i);
        check_close({got[i].s[0], got[i].s[1], got[i].s[2]}, expected[i], 1e-5);
    }
}

TEST_CASE("envmap on the device matches the double-precision reference", "[kernels][envmap]") {
    std::mt19937 rng(20261205);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // A random 13 x 7 map with a black band (zero-probability patches) and
    // one bright texel, under a rotation about a tilted axis.
    const std::uint32_t w = 13, h = 7;
    std::vector<glm::dvec3> texels;
    for (std::uint32_t j = 0; j < h; ++j)
        for (std::uint32_t i = 0; i < w; ++i)
            texels.push_back(j == 4 ? glm::dvec3(0.0)
                                    : glm::dvec3(unit(rng), unit(rng), unit(rng)) * 3.0);
    texels[2 * w + 5] = glm::dvec3(400.0, 300.0, 200.0);
    const auto image = float_image(w, h, texels);
    const glm::dmat3 to_world = rotation(37.0, {0.3, 1.0, -0.2});
    const DeviceScene flat = flatten_envmap(image, to_world, 1.5);
    const EnvironmentTables map = build_environment_tables(*image);
    const glm::dmat3 to_local = glm::transpose(to_world);

    std::vector<cl_float4> directions;
    for (int n = 0; n < 20000; ++n) {
        const double z = 2.0 * unit(rng) - 1.0, phi = 2.0 * kPi * unit(rng);
        const double r = std::sqrt(1.0 - z * z);
        directions.push_back({{static_cast<float>(r * std::cos(phi)),
                               static_cast<float>(r * std::sin(phi)), static_cast<float>(z), 0}});
    }
    // The seam (u = 0), in the map's frame. (At the poles u is undefined:
    // the first and last rows vary along u, so rounding picks the value
    // there, in Mitsuba as here; the stability test below has them.)
    for (const glm::dvec3 l : {glm::dvec3(0, 0, -1), glm::dvec3(0, 0.6, -0.8)}) {
        const glm::dvec3 d = to_world * l;
        directions.push_back(
            {{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z), 0}});
    }
    cl::Kernel kernel(program(kEnvmapSource, "envmap_test.cl"), "evaluate");
    const cl::Buffer emitter = upload(flat.emitters), texels_buffer = upload(flat.texels),
                     cdf = upload(flat.environment_cdf), in = upload(directions),
                     out = upload(std::vector<cl_float4>(directions.size()));
    set_args(kernel, emitter, texels_buffer, cdf, static_cast<cl_uint>(directions.size()), in, out);
    launch(kernel, directions.size());
    const std::vector<cl_float4> got = download<cl_float4>(out, directions.size());
    std::size_t compared = 0;
    for (std::size_t n = 0; n < directions.size(); ++n) {
        const glm::dvec3 d(directions[n].s[0], directions[n].s[1], directions[n].s[2]);
        const glm::dvec3 local = to_local * glm::normalize(d);
        // A direction within float rounding of a patch's edge may fall in
        // either patch on the device: its density is left out there (the
        // radiance is continuous and compared everywhere).
        std::uint32_t i, j;
        double ax, ay;
        environment_patch(map.width, map.height, local, &i, &j, &ax, &ay);
        const bool on_edge = std::min(ax, 1.0 - ax) < 1e-4 || std::min(ay, 1.0 - ay) < 1e-4;
        const glm::dvec3 radiance = 1.5 * map.radiance(local);
        INFO("direction " << n << " (" << d.x << ", " << d.y << ", " << d.z << ")");
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(got[n].s[c] - radiance[c]) <= 1e-4 * std::max(1.0, radiance[c]));
        if (!on_edge) {
            const double pdf = map.pdf(local);
            CHECK(std::abs(got[n].s[3] - pdf) <= 1e-4 * std::max(1.0, pdf));
            ++compared;
        }
    }
    CHECK(compared > directions.size() * 99 / 100);
}

TEST_CASE("envmap search: the first cumulative entry past u, as a binary search finds it",
          "[kernels][envmap]") {
    // Tables of 1 to 256 entries ending in 1, with runs of equal entries
    // (patches of probability 0), searched for numbers drawn at random, at
    // entries exactly and just beside them; the reference is the plain
    // binary search the kernel's narrowing and counting replaced.
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> tables;
    std::vector<cl_uint> sizes;
    std::vector<float> numbers;
    for (int t = 0; t < 4000; ++t) {
        const cl_uint n = 1u + static_cast<cl_uint>(rng() % 256u);
        std::vector<float> cdf(256, 1.0f);
        float sum = 0.0f;
        std::vector<float> weights(n);
        for (float& w : weights) {
            w = rng() % 4u == 0u ? 0.0f : unit(rng);
            sum += w;
        }
        float running = 0.0f;
        for (cl_uint k = 0; k < n; ++k) {
            running += weights[k];
            cdf[k] = sum > 0.0f ? running / sum : 1.0f;
        }
        cdf[n - 1] = 1.0f;
        const float entry = cdf[rng() % n];
        const float choices[] = {
            unit(rng), entry,         std::nextafter(entry, 0.0f), std::nextafter(entry, 2.0f),
            0.0f,      0x1.fffffep-1f};
        tables.insert(tables.end(), cdf.begin(), cdf.end());
        sizes.push_back(n);
        numbers.push_back(choices[rng() % 6u]);
    }
    const auto count = static_cast<cl_uint>(sizes.size());
    cl::Kernel kernel(program(kEnvmapSource, "envmap_test.cl"), "search");
    const cl::Buffer cdf = upload(tables), sizes_buffer = upload(sizes),
                     numbers_buffer = upload(numbers), out = upload(std::vector<cl_uint>(count));
    set_args(kernel, cdf, sizes_buffer, numbers_buffer, count, out);
    launch(kernel, count);
    const std::vector<cl_uint> got = download<cl_uint>(out, count);
    std::size_t differ = 0;
    for (cl_uint i = 0; i < count; ++i) {
        const float* table = tables.data() + 256u * i;
        cl_uint low = 0, high = sizes[i] - 1u;
        while (low < high) {
            const cl_uint mid = (low + high) / 2u;
            if (table[mid] > numbers[i])
                high = mid;
            else
                low = mid + 1u;
        }
        differ += got[i] != low;
    }
    CHECK(differ == 0);
}

TEST_CASE("envmap sampling on the device follows its density (chi-square)",
          "[kernels][envmap][statistical]") {
    // A 9 x 5 map: a smooth gradient, a black row (never sampled), and a
    // 1-texel sun 500 times brighter, rotated; 400k samples.
    const std::uint32_t w = 9, h = 5;
    std::vector<glm::dvec3> texels;
    for (std::uint32_t j = 0; j < h; ++j)
        for (std::uint32_t i = 0; i < w; ++i)
            texels.push_back(j == 3 ? glm::dvec3(0.0)
                                    : glm::dvec3(0.2 + 0.1 * i, 0.5 + 0.2 * j, 1.0 + 0.05 * i * j));
    texels[1 * w + 6] = glm::dvec3(500.0);
    const auto image = float_image(w, h, texels);
    const glm::dmat3 to_world = rotation(-65.0, {1.0, 0.2, 0.4});
    const DeviceScene flat = flatten_envmap(image, to_world, 1.0);
    const EnvironmentTables map = build_environment_tables(*image);
    const glm::dmat3 to_local = glm::transpose(to_world);

    const std::size_t count = 400000;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<cl_float2> numbers(count);
    for (cl_float2& n : numbers)
        n = {{unit(rng), unit(rng)}};
    cl::Kernel kernel(program(kEnvmapSource, "envmap_test.cl"), "sample");
    const cl::Buffer emitter = upload(flat.emitters), texels_buffer = upload(flat.texels),
                     cdf = upload(flat.environment_cdf), in = upload(numbers),
                     out = upload(std::vector<cl_float4>(count)),
                     radiance_out = upload(std::vector<cl_float4>(count));
    set_args(kernel, emitter, texels_buffer, cdf, static_cast<cl_uint>(count), in, out,
             radiance_out);
    launch(kernel, count);
    const std::vector<cl_float4> got = download<cl_float4>(out, count);
    const std::vector<cl_float4> radiances = download<cl_float4>(radiance_out, count);

    // Bins over the world's sphere of directions, (phi, cos theta) in a 24 x 12
    // grid that does not line up with the map's patches; their expected
    // counts by integrating the reference density over each bin (a 24 x 24
    // midpoint grid a bin: equal solid angles).
    const int bins_phi = 24, bins_z = 12, sub = 24;
    auto bin_of = [&](const glm::dvec3& d) {
        double phi = std::atan2(d.y, d.x);
        phi = phi < 0.0 ? phi + 2.0 * kPi : phi;
        const int a = std::min(bins_phi - 1, static_cast<int>(phi / (2.0 * kPi) * bins_phi));
        const int b = std::min(bins_z - 1, static_cast<int>((d.z + 1.0) / 2.0 * bins_z));
        return b * bins_phi + a;
    };
    std::vector<double> observed(bins_phi * bins_z, 0.0), expected(observed.size(), 0.0);
    std::size_t pdf_checked = 0, pdf_bad = 0, not_unit = 0, radiance_bad = 0;
    for (std::size_t n = 0; n < count; ++n) {
        const cl_float4& s = got[n];
        const glm::dvec3 d(s.s[0], s.s[1], s.s[2]);
        if (std::abs(glm::length(d) - 1.0) > 1e-5)
            ++not_unit;
        observed[static_cast<std::size_t>(bin_of(glm::normalize(d)))] += 1.0;
        // The density the sampler reports is the reference's there.
        std::uint32_t i, j;
        double ax, ay;
        const glm::dvec3 local = to_local * glm::normalize(d);
        environment_patch(map.width, map.height, local, &i, &j, &ax, &ay);
        // The radiance the sample carries (blended in its patch at the
        // sample's own place, not looked up by direction) is the reference's
        // along the direction it made, to float rounding: the direction's own
        // rounding, a few 1e-7 of a texel, moves the blend by that times the
        // patch's brightest corner where a texel is far brighter than its
        // neighbour (the sun here).
        double corner = 0.0;
        for (std::uint32_t x : {i, (i + 1) % map.width})
            for (std::uint32_t y : {j, j + 1}) {
                const glm::dvec3 texel = map.texel(x, y);
                corner = std::max({corner, texel.x, texel.y, texel.z});
            }
        const glm::dvec3 radiance = map.radiance(local);
        for (int c = 0; c < 3; ++c)
            if (!(std::abs(radiances[n].s[c] - radiance[c]) <=
                  1e-4 * std::max(1.0, radiance[c]) + 2e-6 * corner))
                ++radiance_bad;
        if (std::min(ax, 1.0 - ax) > 1e-3 && std::min(ay, 1.0 - ay) > 1e-3) {
            ++pdf_checked;
            const double pdf = map.pdf(local);
            if (!(std::abs(s.s[3] - pdf) <= 1e-3 * pdf))
                ++pdf_bad;
        }
    }
    double total_probability = 0.0;
    const double bin_solid_angle = (2.0 * kPi / bins_phi) * (2.0 / bins_z) / (sub * sub);
    for (int b = 0; b < bins_z; ++b)
        for (int a = 0; a < bins_phi; ++a)
            for (int y = 0; y < sub; ++y)
                for (int x = 0; x < sub; ++x) {
                    const double phi = 2.0 * kPi * (a + (x + 0.5) / sub) / bins_phi;
                    const double z = -1.0 + 2.0 * (b + (y + 0.5) / sub) / bins_z;
                    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                    const glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
                    const double p = map.pdf(to_local * d) * bin_solid_angle;
                    expected[static_cast<std::size_t>(b * bins_phi + a)] += p * count;
                    total_probability += p;
                }
    CHECK(not_unit == 0);
    INFO(radiance_bad << " sampled radiances differ from the reference's along their direction");
    CHECK(radiance_bad == 0);
    INFO(pdf_bad << " of " << pdf_checked << " sampled densities differ from the reference");
    CHECK(pdf_bad == 0);
    CHECK(pdf_checked > count * 9 / 10);
    // The density integrates to one (to the midpoint rule's error at the
    // patches' edges).
    CHECK(total_probability == Approx(1.0).epsilon(2e-3));
    const ChiSquare test = chi_square(observed, expected);
    INFO("chi-square " << test.statistic << " with " << test.dof << " dof, p = " << test.p_value);
    CHECK(test.outside == 0);
    CHECK(test.p_value > 1e-3);
}

TEST_CASE("envmap tables: a black map is never sampled, and its integral is zero", "[envmap]") {
    const EnvironmentTables black =
        build_environment_tables(*float_image(4, 4, std::vector<glm::dvec3>(16, glm::dvec3(0.0))));
    CHECK(black.cdf.empty());
    CHECK(black.integral == 0.0);
    CHECK(black.pdf({0, 1, 0}) == 0.0);
    // A constant map integrates to 4 pi times its value (the patches' solid
    // angles cover the sphere exactly), and samples uniformly: 1 / (4 pi).
    const EnvironmentTables grey =
        build_environment_tables(*float_image(6, 4, std::vector<glm::dvec3>(24, glm::dvec3(0.5))));
    CHECK(grey.integral == Approx(0.5 * 4.0 * kPi).epsilon(1e-12));
    for (const glm::dvec3 d : {glm::dvec3(0, 1, 0), glm::dvec3(0.6, 0, 0.8), glm::dvec3(0, -1, 0)})
        CHECK(grey.pdf(d) == Approx(1.0 / (4.0 * kPi)).epsilon(1e-6));
}

TEST_CASE("envmap on the device stays finite at the poles, the seam and extreme values",
          "[kernels][envmap][stability]") {
    // A 16 x 8 map with a texel of radiance 1e6 in the first row (at the
    // zenith) beside texels of 1e-3, unrotated.
    const std::uint32_t w = 16, h = 8;
    std::vector<glm::dvec3> texels(w * h, glm::dvec3(1e-3));
    texels[3] = glm::dvec3(1e6);
    const DeviceScene flat = flatten_envmap(float_image(w, h, texels), glm::dmat3(1.0), 1.0);
    const float tiny = 1e-30f, next_below_one = std::nextafter(1.0f, 0.0f);
    const std::vector<cl_float4> directions = {
        {{0, 1, 0, 0}},    {{0, -1, 0, 0}},     {{-0.0f, 1, -0.0f, 0}}, {{tiny, 1, 0, 0}},
        {{0, 1, tiny, 0}}, {{-tiny, -1, 0, 0}}, {{tiny, 0, -1, 0}},     {{-tiny, 0, -1, 0}},
        {{0, 0, -1, 0}},   {{0, 0, 1, 0}},      {{1, 0, 0, 0}},         {{0.6f, 0.8f, 0, 0}}};
    cl::Kernel evaluate(program(kEnvmapSource, "envmap_test.cl"), "evaluate");
    const cl::Buffer emitter = upload(flat.emitters), texels_buffer = upload(flat.texels),
                     cdf = upload(flat.environment_cdf), in = upload(directions),
                     out = upload(std::vector<cl_float4>(directions.size()));
    set_args(evaluate, emitter, texels_buffer, cdf, static_cast<cl_uint>(directions.size()), in,
             out);
    launch(evaluate, directions.size());
    const std::vector<cl_float4> got = download<cl_float4>(out, directions.size());
    for (std::size_t n = 0; n < directions.size(); ++n) {
        INFO("direction " << n);
        for (int c = 0; c < 4; ++c) {
            CHECK(std::isfinite(got[n].s[c]));
            CHECK(got[n].s[c] >= 0.0f);
        }
        CHECK(got[n].s[0] <= 1e6f);
    }
    // The numbers at the ends of [0, 1), and the sun's patches.
    std::vector<cl_float2> numbers;
    for (float u : {0.0f, 1e-9f, 0.5f, next_below_one})
        for (float v : {0.0f, 1e-9f, 0.5f, next_below_one})
            numbers.push_back({{u, v}});
    cl::Kernel sample(program(kEnvmapSource, "envmap_test.cl"), "sample");
    const cl::Buffer numbers_buffer = upload(numbers),
                     samples = upload(std::vector<cl_float4>(numbers.size())),
                     sampled_radiance = upload(std::vector<cl_float4>(numbers.size()));
    set_args(sample, emitter, texels_buffer, cdf, static_cast<cl_uint>(numbers.size()),
             numbers_buffer, samples, sampled_radiance);
    launch(sample, numbers.size());
    const std::vector<cl_float4> drawn = download<cl_float4>(samples, numbers.size());
    const std::vector<cl_float4> radiances = download<cl_float4>(sampled_radiance, numbers.size());
    for (std::size_t n = 0; n < numbers.size(); ++n) {
        INFO("numbers (" << numbers[n].s[0] << ", " << numbers[n].s[1] << ")");
        const glm::dvec3 d(drawn[n].s[0], drawn[n].s[1], drawn[n].s[2]);
        CHECK(std::abs(glm::length(d) - 1.0) < 1e-5);
        CHECK(std::isfinite(drawn[n].s[3]));
        CHECK(drawn[n].s[3] > 0.0f);
        for (int c = 0; c < 3; ++c) {
            CHECK(std::isfinite(radiances[n].s[c]));
            CHECK(radiances[n].s[c] >= 0.0f);
        }
    }
}
