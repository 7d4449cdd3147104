// Mitsuba 3's sensors, film and sampler as wavepath's camera (sensor.hpp).
#include "scene/mitsuba/sensor.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "scene/camera.hpp"
#include "scene/json_reader.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/validate.hpp"

namespace wp::mitsuba {
namespace {

using json::number_text;

void read_filter(const Object& rfilter, Camera& camera) {
    Parameters p(rfilter);
    const std::optional<FilterKind> kind = filter_kind_from_name(rfilter.type);
    if (rfilter.tag != "rfilter" || !kind)
        p.fail("unsupported reconstruction filter (wavepath has " + filter_kind_names() + ")");
    camera.filter = *kind;
    const char* size = *kind == FilterKind::Tent       ? "radius"
                       : *kind == FilterKind::Gaussian ? "stddev"
                                                       : nullptr;
    if (size) {
        if (const std::optional<double> x = p.number(size)) {
            if (!(*x > 0.0 && *x <= scene_limits::max_filter_size))
                p.fail(size, "must be positive and at most " +
                                 number_text(scene_limits::max_filter_size) + " pixels, got " +
                                 number_text(*x));
            (*kind == FilterKind::Tent ? camera.filter_radius : camera.filter_stddev) = *x;
        }
    }
    p.finish();
}

int pixels(Parameters& p, const char* name, long long fallback) {
    const long long n = p.integer(name).value_or(fallback);
    if (n < 1 || n > scene_limits::max_resolution)
        p.fail(name, "must be 1 to 16384 pixels, got " + std::to_string(n));
    return static_cast<int>(n);
}

void read_film(const Object& film, Camera& camera) {
    Parameters p(film);
    if (film.tag != "film" || film.type != "hdrfilm")
        p.fail("unsupported film (wavepath has hdrfilm)");
    camera.width = pixels(p, "width", 768); // Mitsuba's defaults
    camera.height = pixels(p, "height", 576);
    // What is stored, not what is rendered: wavepath writes its own outputs.
    for (const char* name : {"pixel_format", "component_format", "file_format"})
        p.ignore(name);
    // Mitsuba's hdrfilm filters with a Gaussian unless told otherwise.
    camera.filter = FilterKind::Gaussian;
    for (const auto& child : film.children)
        read_filter(*child, camera);
    p.finish();
}

// Any of Mitsuba's samplers: all of them converge to the same image.
// wavepath takes its sample count from the command line (--spp), so the
// file's sample_count is read and left.
void read_sampler(const Object& sampler) {
    Parameters p(sampler);
    for (const char* name : {"sample_count", "seed", "jitter", "scramble_seed"})
        p.ignore(name);
    static const char* const kTypes[] = {"independent", "stratified", "multijitter", "orthogonal",
                                         "ldsampler"};
    if (std::find(std::begin(kTypes), std::end(kTypes), sampler.type) == std::end(kTypes))
        p.fail("unsupported sampler (wavepath reads independent, stratified, multijitter, "
               "orthogonal and ldsampler, and takes the sample count from --spp)");
    p.finish();
}

// Mitsuba's focal_length, "50mm": the field of view of a 36 x 24 mm film's
// diagonal (Mitsuba's parse_fov).
double focal_length_fov(Parameters& p, const std::string& text) {
    std::string number = text;
    if (number.size() > 2 && number.ends_with("mm"))
        number.resize(number.size() - 2);
    double mm = 0.0;
    try {
        std::size_t used = 0;
        mm = std::stod(number, &used);
        if (used != number.size())
            mm = 0.0;
    } catch (const std::exception&) {
        mm = 0.0;
    }
    if (!(mm > 0.0))
        p.fail("focal_length",
               "expected a length such as '50mm', got '" + json::shorten(text, 40) + "'");
    return 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / M_PI;
}

} // namespace

Camera read_sensor(const Object& sensor, std::vector<std::string>& warnings) {
    (void)warnings;
    Parameters p(sensor);
    const bool lens = sensor.type == "thinlens";
    if (sensor.type != "perspective" && !lens)
        p.fail("unsupported sensor (wavepath has perspective and thinlens)");
    Camera c;
    c.width = 768;
    c.height = 576;
    c.filter = FilterKind::Gaussian;
    for (const auto& child : sensor.children) {
        if (child->tag == "film")
            read_film(*child, c);
        else if (child->tag == "sampler")
            read_sampler(*child);
        else
            fail_at(child->where, child->element(),
                    "wavepath does not support a <" + child->tag + "> inside " + sensor.element() +
                        " (it reads a film and a sampler)");
    }

    // The field of view, along fov_axis (Mitsuba's default x).
    const std::optional<double> fov = p.number("fov");
    const std::optional<std::string> focal_length = p.string("focal_length");
    const std::optional<std::string> axis_name = p.string("fov_axis");
    if (fov && focal_length)
        p.fail("focal_length", "give either fov or focal_length, not both");
    double degrees = fov.value_or(0.0);
    FovAxis axis = FovAxis::X;
    if (!fov) {
        degrees = focal_length_fov(p, focal_length.value_or("50mm"));
        axis = FovAxis::Diagonal;
    }
    if (axis_name) {
        const std::optional<FovAxis> a = fov_axis_from_name(*axis_name);
        if (!a)
            p.fail("fov_axis", "unknown fov_axis '" + json::shorten(*axis_name, 40) +
                                   "' (expected " + fov_axis_names() + ")");
        axis = *a;
    }
    if (!(degrees > 0.0 && degrees < 180.0))
        p.fail(fov ? "fov" : "focal_length",
               "the field of view must be in (0, 180) degrees, got " + number_text(degrees));
    c.vertical_fov_degrees = vertical_fov_degrees(degrees, axis, c.width, c.height);

    // wavepath has no clipping planes: everything in front of the eye is seen.
    p.ignore("near_clip");
    p.ignore("far_clip");
    if (lens) {
        // As Mitsuba 3.9.1 (measured with mi.load_dict): aperture_radius is
        // required, focus_distance defaults to 10000.
        const std::optional<double> aperture = p.number("aperture_radius");
        if (!aperture)
            p.fail("a thinlens sensor needs aperture_radius (the lens radius in scene units)");
        c.aperture_radius = *aperture;
        if (!(c.aperture_radius >= 0.0) || c.aperture_radius > scene_limits::max_coordinate)
            p.fail("aperture_radius",
                   "must be in [0, 1e30], got " + number_text(c.aperture_radius));
        c.focus_distance = p.number("focus_distance").value_or(10000.0);
        if (!(c.focus_distance > 0.0) || c.focus_distance > scene_limits::max_coordinate)
            p.fail("focus_distance", "must be in (0, 1e30], got " + number_text(c.focus_distance));
    } else {
        p.ignore("focus_distance"); // Mitsuba's perspective sensor reads it for nothing too
    }

    // The frame: +z forward, +y up, +x to the image's left.
    const wp::Transform to_world = p.transform("to_world").value_or(wp::Transform());
    const glm::dvec3 left = to_world.apply_to_vector({1.0, 0.0, 0.0});
    const glm::dvec3 up = to_world.apply_to_vector({0.0, 1.0, 0.0});
    const glm::dvec3 forward = to_world.apply_to_vector({0.0, 0.0, 1.0});
    const double scale = glm::length(forward);
    const double tolerance = 1e-6 * scale * scale;
    const bool similar = std::abs(glm::dot(left, left) - scale * scale) <= tolerance &&
                         std::abs(glm::dot(up, up) - scale * scale) <= tolerance &&
                         std::abs(glm::dot(left, up)) <= tolerance &&
                         std::abs(glm::dot(left, forward)) <= tolerance &&
                         std::abs(glm::dot(up, forward)) <= tolerance;
    if (!similar)
        p.fail("to_world", "the camera's to_world must be a rotation, a uniform scale and a "
                           "translation (a lookat); this one shears or scales unevenly");
    if (glm::dot(glm::cross(left, up), forward) < 0.0)
        p.fail("to_world", "the camera's to_world mirrors the image (a negative scale), which "
                           "wavepath's camera cannot; remove the mirroring scale");
    c.eye = to_world.apply_to_point(glm::dvec3(0.0));
    c.look_at = c.eye + forward / scale;
    c.up = up / scale;
    p.finish();
    return c;
}

} // namespace wp::mitsuba
