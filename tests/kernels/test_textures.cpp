// kernels/textures/ on the device against the host's double-precision
// reference (scene/texture.hpp, Texture::eval), and that reference against
// Mitsuba 3.9.1's own bitmap and checkerboard plugins: values measured with
// its Python API (mi.load_dict({'type': 'bitmap', 'data': ...}).eval(si) at
// the texture coordinates below), so wavepath's conventions (which row is
// v = 0, where texel centres lie, how each wrap mode folds an index) are
// Mitsuba's.
#include "render/device_scene.hpp"
#include "scene/texture.hpp"
#include "support/kernel_test_util.hpp"
#include "support/vectorizer_remarks.hpp" // test_device_is_pocl

#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace wp;
using namespace wp::test;

namespace {

const char* const kTextureSource = R"CL(
#include "textures/texture.h"

__kernel void lookups(__global const WpTexture* textures, __global const uint* texels, uint count,
                      __global const uint* which, __global const float2* uv,
                      __global float4* out) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    out[i] = (float4)(wp_texture_lookup(textures, texels, which[i], uv[i], 0), 0.0f);
}
)CL";

// A 2x2 float image, row 0 black and red, row 1 green and blue: the image of
// the Mitsuba measurements.
std::shared_ptr<const TextureImage> two_by_two() {
    auto image = std::make_shared<TextureImage>();
    image->width = image->height = 2;
    image->encoding = TexelEncoding::Float32;
    for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f})
        image->texels.push_back(std::bit_cast<std::uint32_t>(x));
    return image;
}

Texture bitmap(std::shared_ptr<const TextureImage> image, TextureFilter filter, TextureWrap wrap) {
    Texture t;
    t.kind = TextureKind::Bitmap;
    t.image = std::move(image);
    t.filter = filter;
    t.wrap = wrap;
    return t;
}

struct Measured {
    double u, v;
    glm::dvec3 rgb;
};

void check_measured(const Texture& t, const std::vector<Measured>& cases) {
    for (const Measured& m : cases) {
        const glm::dvec3 got = t.eval(m.u, m.v);
        INFO("uv (" << m.u << ", " << m.v << "): wavepath " << got.x << " " << got.y << " " << got.z
                    << ", Mitsuba " << m.rgb.x << " " << m.rgb.y << " " << m.rgb.z);
        // Mitsuba printed its float32 results to 6 digits.
        CHECK(std::abs(got.x - m.rgb.x) < 1e-6);
        CHECK(std::abs(got.y - m.rgb.y) < 1e-6);
        CHECK(std::abs(got.z - m.rgb.z) < 1e-6);
    }
}

} // namespace

TEST_CASE("texture reference: Mitsuba 3's bitmap filtering and wrap modes", "[textures]") {
    using F = TextureFilter;
    using W = TextureWrap;
    check_measured(bitmap(two_by_two(), F::Bilinear, W::Repeat), {{0.25, 0.25, {0, 0, 0}},
                                                                  {0.75, 0.25, {1, 0, 0}},
                                                                  {0.25, 0.75, {0, 1, 0}},
                                                                  {0.5, 0.5, {0.25, 0.25, 0.25}},
                                                                  {0.1, 0.9, {0.09, 0.49, 0.21}},
                                                                  {-0.1, 0.3, {0.63, 0.03, 0.07}},
                                                                  {1.2, 0.3, {0.09, 0.09, 0.01}},
                                                                  {-0.6, 1.7, {0.03, 0.63, 0.27}}});
    check_measured(bitmap(two_by_two(), F::Bilinear, W::Mirror), {{0.1, 0.9, {0, 1, 0}},
                                                                  {-0.1, 0.3, {0, 0.1, 0}},
                                                                  {1.2, 0.3, {0.9, 0, 0.1}},
                                                                  {-0.6, 1.7, {0.63, 0.03, 0.07}}});
    check_measured(bitmap(two_by_two(), F::Bilinear, W::Clamp), {{0.1, 0.9, {0, 1, 0}},
                                                                 {-0.1, 0.3, {0, 0.1, 0}},
                                                                 {1.2, 0.3, {0.9, 0, 0.1}},
                                                                 {-0.6, 1.7, {0, 1, 0}}});
    check_measured(bitmap(two_by_two(), F::Nearest, W::Repeat), {{0.1, 0.9, {0, 1, 0}},
                                                                 {-0.1, 0.3, {1, 0, 0}},
                                                                 {1.2, 0.3, {0, 0, 0}},
                                                                 {-0.6, 1.7, {0, 1, 0}}});
    check_measured(bitmap(two_by_two(), F::Nearest, W::Mirror), {{0.1, 0.9, {0, 1, 0}},
                                                                 {-0.1, 0.3, {0, 0, 0}},
                                                                 {1.2, 0.3, {1, 0, 0}},
                                                                 {-0.6, 1.7, {1, 0, 0}}});
    check_measured(bitmap(two_by_two(), F::Nearest, W::Clamp), {{0.1, 0.9, {0, 1, 0}},
                                                                {-0.1, 0.3, {0, 0, 0}},
                                                                {1.2, 0.3, {1, 0, 0}},
                                                                {-0.6, 1.7, {0, 1, 0}}});
    // to_uv = scale(2, 3) after translate(0.1, 0.2): (0.3, 0.4) -> (0.8, 1.8).
    Texture moved = bitmap(two_by_two(), F::Bilinear, W::Repeat);
    moved.to_u = {2.0, 0.0, 0.2};
    moved.to_v = {0.0, 3.0, 0.6};
    check_measured(moved, {{0.3, 0.4, {0.09, 0.09, 0.81}}});
}

TEST_CASE("texture reference: Mitsuba 3's checkerboard", "[textures]") {
    Texture t; // Mitsuba's defaults: color0 0.4, color1 0.2
    check_measured(t, {{0.25, 0.25, glm::dvec3(0.4)},
                       {0.75, 0.25, glm::dvec3(0.2)},
                       {0.3, 0.7, glm::dvec3(0.2)},
                       {0.7, 0.7, glm::dvec3(0.4)},
                       {1.25, 0.25, glm::dvec3(0.4)},
                       {-0.25, 0.25, glm::dvec3(0.2)}});
}

TEST_CASE("texture reference: float lookups as Mitsuba 3's eval_1", "[textures]") {
    // A bitmap's: the luminance of its colour (Mitsuba's eval_1 at the same
    // points as above).
    const Texture grid = bitmap(two_by_two(), TextureFilter::Bilinear, TextureWrap::Repeat);
    CHECK(grid.eval_float(0.1, 0.9) == Approx(0.38472).margin(1e-5));
    CHECK(grid.eval_float(-0.1, 0.3) == Approx(0.16049).margin(1e-5));
    CHECK(grid.eval_float(1.2, 0.3) == Approx(0.08423).margin(1e-5));
    // A checkerboard's: its colours swapped (to_uv scale (4, 2), color0 0.05,
    // color1 0.4; eval and eval_1 measured at each point).
    Texture checker;
    checker.color0 = glm::dvec3(0.05);
    checker.color1 = glm::dvec3(0.4);
    checker.to_u = {4.0, 0.0, 0.0};
    checker.to_v = {0.0, 2.0, 0.0};
    const struct {
        double u, v, eval, eval_1;
    } measured[] = {{0.1, 0.1, 0.05, 0.4},
                    {0.2, 0.1, 0.4, 0.05},
                    {0.1, 0.3, 0.4, 0.05},
                    {0.3, 0.3, 0.4, 0.05},
                    {0.05, 0.6, 0.05, 0.4}};
    for (const auto& m : measured) {
        INFO("uv (" << m.u << ", " << m.v << ")");
        CHECK(checker.eval(m.u, m.v).x == Approx(m.eval));
        CHECK(checker.eval_float(m.u, m.v) == Approx(m.eval_1));
    }
}

TEST_CASE("textures on the device match the double-precision reference", "[kernels][textures]") {
    std::mt19937 rng(20261205);
    std::uniform_int_distribution<std::uint32_t> byte(0, 255);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto image = [&](std::uint32_t w, std::uint32_t h, TexelEncoding encoding) {
        auto img = std::make_shared<TextureImage>();
        img->width = w;
        img->height = h;
        img->encoding = encoding;
        for (std::uint32_t i = 0; i < w * h; ++i) {
            if (encoding == TexelEncoding::Float32)
                for (int c = 0; c < 3; ++c)
                    img->texels.push_back(std::bit_cast<std::uint32_t>(4.0f * unit(rng)));
            else
                img->texels.push_back(byte(rng) | byte(rng) << 8 | byte(rng) << 16);
        }
        return std::shared_ptr<const TextureImage>(img);
    };
    // Every encoding, filter and wrap mode, odd sizes, a 1x1 image, and a
    // checkerboard, each under its own affine to_uv.
    Scene scene;
    const std::shared_ptr<const TextureImage> images[] = {
        image(5, 3, TexelEncoding::Srgb8), image(4, 7, TexelEncoding::Linear8),
        image(7, 4, TexelEncoding::Float32), image(1, 1, TexelEncoding::Srgb8)};
    for (const auto& img : images)
        for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Nearest})
            for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Mirror, TextureWrap::Clamp})
                scene.textures.push_back(bitmap(img, filter, wrap));
    Texture checker;
    checker.color0 = {0.9, 0.5, 0.1};
    checker.color1 = {0.05, 0.2, 0.7};
    scene.textures.push_back(checker);
    std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
    for (Texture& t : scene.textures) {
        t.to_u = {coefficient(rng), coefficient(rng), coefficient(rng)};
        t.to_v = {coefficient(rng), coefficient(rng), coefficient(rng)};
    }
    DeviceScene flat;
    flatten_textures(scene, flat);
    // The kernels see float32 coefficients; the reference uses the same.
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        scene.textures[i].to_u = {flat.textures[i].to_u.s[0], flat.textures[i].to_u.s[1],
                                  flat.textures[i].to_u.s[2]};
        scene.textures[i].to_v = {flat.textures[i].to_v.s[0], flat.textures[i].to_v.s[1],
                                  flat.textures[i].to_v.s[2]};
    }

    const std::size_t per_texture = 2048;
    std::vector<cl_uint> which;
    std::vector<cl_float2> uvs;
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
    for (std::size_t t = 0; t < scene.textures.size(); ++t)
        for (std::size_t i = 0; i < per_texture; ++i) {
            which.push_back(static_cast<cl_uint>(t));
            uvs.push_back({{coordinate(rng), coordinate(rng)}});
        }
    cl::Kernel kernel(program(kTextureSource, "texture_test.cl"), "lookups");
    cl::Buffer out = upload(std::vector<cl_float4>(which.size()));
    // The buffers live until the kernel has run.
    const cl::Buffer textures = upload(flat.textures), texels = upload(flat.texels);
    const cl::Buffer which_buffer = upload(which), uv_buffer = upload(uvs);
    set_args(kernel, textures, texels, static_cast<cl_uint>(which.size()), which_buffer, uv_buffer,
             out);
    launch(kernel, which.size());
    const std::vector<cl_float4> got = download<cl_float4>(out, which.size());

    std::size_t compared = 0, skipped = 0;
    for (std::size_t i = 0; i < which.size(); ++i) {
        const Texture& t = scene.textures[which[i]];
        const double u = uvs[i].s[0], v = uvs[i].s[1];
        // Where a lookup jumps (a nearest texel's edge, a checker square's),
        // float32 and double may land on different sides: such points are
        // left out, the rest must agree to float32 rounding.
        const double mu = glm::dot(t.to_u, glm::dvec3(u, v, 1.0));
        const double mv = glm::dot(t.to_v, glm::dvec3(u, v, 1.0));
        auto near_step = [](double x, double period) {
            const double f = x / period - std::floor(x / period);
            return f < 1e-4 || f > 1.0 - 1e-4;
        };
        const bool jumps =
            t.kind == TextureKind::Checkerboard
                ? near_step(mu, 0.5) || near_step(mv, 0.5)
                : t.filter == TextureFilter::Nearest &&
                      (near_step(mu * t.image->width, 1.0) || near_step(mv * t.image->height, 1.0));
        if (jumps) {
            ++skipped;
            continue;
        }
        const glm::dvec3 expected = t.eval(u, v);
        for (int c = 0; c < 3; ++c) {
            INFO("texture " << which[i] << " at (" << u << ", " << v << ") channel " << c);
            CHECK(std::abs(got[i].s[c] - expected[c]) <= 2e-5 * std::max(1.0, expected[c]));
        }
        ++compared;
    }
    INFO(compared << " lookups compared, " << skipped << " at a step left out");
    CHECK(compared > which.size() * 99 / 100);
}

// The 8-bit sRGB decode is a table (kernels/textures/srgb8.h): each entry
// must be the float the curve's formula gives on the device, so that the
// table renders as the formula did (bit-identical on PoCL, whose values the
// table holds), and the curve itself to float rounding, from the double-precision
// reference of the host's decoding (IEC 61966-2-1).
TEST_CASE("textures: the 8-bit sRGB table holds the curve's float values", "[kernels][textures]") {
    const char* const source = R"CL(
#include "textures/bitmap.h"
__kernel void srgb8(__global float2* out) {
    uint k = get_global_id(0);
    if (k < 256u)
        out[k] = (float2)(wp_srgb8_to_linear[k], wp_srgb_to_linear((float)k * (1.0f / 255.0f)));
}
)CL";
    cl::Kernel kernel(program(source, "srgb8_test.cl"), "srgb8");
    cl::Buffer out = upload(std::vector<cl_float2>(256));
    set_args(kernel, out);
    launch(kernel, 256);
    const std::vector<cl_float2> got = download<cl_float2>(out, 256);
    for (int k = 0; k < 256; ++k) {
        const float table = got[k].s[0], formula = got[k].s[1];
        const double c = static_cast<double>(static_cast<float>(k) * (1.0f / 255.0f));
        const double curve = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        const float rounded = static_cast<float>(curve);
        const double ulp = std::nextafter(rounded, 2.0f) - rounded;
        INFO("code " << k << ": table " << table << ", formula on the device " << formula
                     << ", double curve " << curve);
        // Bit for bit on PoCL, whose pow made the table; another device's pow
        // may round otherwise, within the few ulps OpenCL allows it.
        if (test_device_is_pocl())
            CHECK(table == formula);
        else
            CHECK(std::abs(static_cast<double>(table) - formula) <= 16.0 * ulp);
        CHECK(std::abs(table - curve) <= 5.0 * ulp);
    }
    CHECK(got[0].s[0] == 0.0f);
    CHECK(got[255].s[0] == 1.0f);
}

TEST_CASE("textures on the device stay finite and in range at extreme coordinates",
          "[kernels][textures][stability]") {
    Scene scene;
    auto image = std::make_shared<TextureImage>();
    image->width = 3;
    image->height = 2;
    image->encoding = TexelEncoding::Linear8;
    image->texels = {0x000000u, 0xffffffu, 0x808080u, 0x102030u, 0xf0e0d0u, 0x7f7f7fu};
    for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Nearest})
        for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Mirror, TextureWrap::Clamp})
            scene.textures.push_back(bitmap(image, filter, wrap));
    DeviceScene flat;
    flatten_textures(scene, flat);
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float extremes[] = {0.0f, 1e-30f, -1e-30f, 1e7f, -1e7f, 1e30f, -1e30f, inf, -inf, nan};
    std::vector<cl_uint> which;
    std::vector<cl_float2> uvs;
    for (std::size_t t = 0; t < scene.textures.size(); ++t)
        for (float u : extremes)
            for (float v : extremes) {
                which.push_back(static_cast<cl_uint>(t));
                uvs.push_back({{u, v}});
            }
    cl::Kernel kernel(program(kTextureSource, "texture_test.cl"), "lookups");
    cl::Buffer out = upload(std::vector<cl_float4>(which.size()));
    // The buffers live until the kernel has run.
    const cl::Buffer textures = upload(flat.textures), texels = upload(flat.texels);
    const cl::Buffer which_buffer = upload(which), uv_buffer = upload(uvs);
    set_args(kernel, textures, texels, static_cast<cl_uint>(which.size()), which_buffer, uv_buffer,
             out);
    launch(kernel, which.size());
    const std::vector<cl_float4> got = download<cl_float4>(out, which.size());
    for (std::size_t i = 0; i < got.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            INFO("texture " << which[i] << " at (" << uvs[i].s[0] << ", " << uvs[i].s[1] << ")");
            // A blend of texels, which lie in [0, 1].
            CHECK(std::isfinite(got[i].s[c]));
            CHECK(got[i].s[c] >= 0.0f);
            CHECK(got[i].s[c] <= 1.0f + 1e-6f);
        }
}
