#include "scene/texture.hpp"
#include "scene/luminance.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace wp {

const char* texture_kind_name(TextureKind kind) {
    switch (static_cast<wp_uint>(kind)) {
#define WP_TEXTURE_NAME_CASE(KIND, Name, name, value)                                              \
    case value:                                                                                    \
        return #name;
        WP_TEXTURES(WP_TEXTURE_NAME_CASE)
#undef WP_TEXTURE_NAME_CASE
    default:
        return nullptr;
    }
}

std::optional<TextureKind> texture_kind_from_name(std::string_view name) {
#define WP_TEXTURE_FROM_NAME(KIND, Name, name_, value)                                             \
    if (name == #name_)                                                                            \
        return TextureKind::Name;
    WP_TEXTURES(WP_TEXTURE_FROM_NAME)
#undef WP_TEXTURE_FROM_NAME
    return std::nullopt;
}

std::string texture_kind_names() {
    std::string out;
#define WP_TEXTURE_LIST_NAME(KIND, Name, name, value) out += out.empty() ? #name : ", " #name;
    WP_TEXTURES(WP_TEXTURE_LIST_NAME)
#undef WP_TEXTURE_LIST_NAME
    return out;
}

std::optional<TextureWrap> texture_wrap_from_name(std::string_view name) {
    if (name == "repeat")
        return TextureWrap::Repeat;
    if (name == "mirror")
        return TextureWrap::Mirror;
    if (name == "clamp")
        return TextureWrap::Clamp;
    return std::nullopt;
}

std::optional<TextureFilter> texture_filter_from_name(std::string_view name) {
    if (name == "bilinear")
        return TextureFilter::Bilinear;
    if (name == "nearest")
        return TextureFilter::Nearest;
    return std::nullopt;
}

const char* texture_wrap_name(TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::Repeat:
        return "repeat";
    case TextureWrap::Mirror:
        return "mirror";
    case TextureWrap::Clamp:
        return "clamp";
    }
    return "repeat";
}

const char* texture_filter_name(TextureFilter filter) {
    return filter == TextureFilter::Nearest ? "nearest" : "bilinear";
}

namespace {

// The kernels' wrap of a texel index (kernels/textures/bitmap.h).
long long wrap_index(long long i, long long n, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::Clamp:
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    case TextureWrap::Mirror: {
        long long m = i % (2 * n);
        m = m < 0 ? m + 2 * n : m;
        return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat:
        break;
    }
    const long long m = i % n;
    return m < 0 ? m + n : m;
}

glm::dvec3 texel(const TextureImage& image, long long x, long long y) {
    return linear_texel(image, static_cast<std::size_t>(x), static_cast<std::size_t>(y));
}

} // namespace

glm::dvec3 Texture::eval(double u, double v) const {
    const double mu = glm::dot(to_u, glm::dvec3(u, v, 1.0));
    const double mv = glm::dot(to_v, glm::dvec3(u, v, 1.0));
    if (kind == TextureKind::Checkerboard)
        return ((mu - std::floor(mu) < 0.5) == (mv - std::floor(mv) < 0.5)) ? color0 : color1;
    const TextureImage& img = *image;
    const long long w = img.width, h = img.height;
    const double wd = img.width, hd = img.height;
    if (filter == TextureFilter::Nearest)
        return texel(img, wrap_index(static_cast<long long>(std::floor(mu * wd)), w, wrap),
                     wrap_index(static_cast<long long>(std::floor(mv * hd)), h, wrap));
    const double x = mu * wd - 0.5, y = mv * hd - 0.5;
    const double xf = std::floor(x), yf = std::floor(y);
    const double ax = x - xf, ay = y - yf;
    const auto x0 = static_cast<long long>(xf), y0 = static_cast<long long>(yf);
    const long long xa = wrap_index(x0, w, wrap), xb = wrap_index(x0 + 1, w, wrap);
    const long long ya = wrap_index(y0, h, wrap), yb = wrap_index(y0 + 1, h, wrap);
    const glm::dvec3 top = (1.0 - ax) * texel(img, xa, ya) + ax * texel(img, xb, ya);
    const glm::dvec3 bottom = (1.0 - ax) * texel(img, xa, yb) + ax * texel(img, xb, yb);
    return (1.0 - ay) * top + ay * bottom;
}

double Texture::eval_float(double u, double v) const {
    glm::dvec3 c;
    if (kind == TextureKind::Checkerboard) {
        Texture swapped = *this;
        std::swap(swapped.color0, swapped.color1);
        c = swapped.eval(u, v);
    } else {
        c = eval(u, v);
    }
    return luminance(c);
}

glm::dvec3 Texture::mean() const {
    if (kind == TextureKind::Checkerboard)
        return 0.5 * (color0 + color1); // the squares cover half the plane each
    // Bilinear filtering over a whole repeat preserves the texels' mean
    // (every texel's weights sum to one texel's area); the other wrap modes
    // differ from it only at the edges.
    glm::dvec3 sum{0.0};
    for (std::uint32_t y = 0; y < image->height; ++y)
        for (std::uint32_t x = 0; x < image->width; ++x)
            sum += texel(*image, x, y);
    return sum / (static_cast<double>(image->width) * image->height);
}

} // namespace wp
