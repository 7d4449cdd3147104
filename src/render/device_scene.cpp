#include "render/device_scene.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render/environment_tables.hpp"
#include "render/float_range.hpp"
#include "render/planar_mirrors.hpp"
#include "render/shadow_occluders.hpp"
#include "render/wide_bvh.hpp"
#include "scene/instancing.hpp"
#include "scene/material.hpp"
#include "scene/scene_box.hpp"

namespace wp {

wp_float4 to_float4(const glm::dvec3& v, double w) {
    wp_float4 r;
    r.s[0] = static_cast<float>(v.x);
    r.s[1] = static_cast<float>(v.y);
    r.s[2] = static_cast<float>(v.z);
    r.s[3] = static_cast<float>(w);
    return r;
}

namespace {

std::string flag(const char* name, bool on) {
    return std::string("-D ") + name + (on ? "=1" : "=0");
}

// Appends `word` to a space-separated list.
// Whether a primitive of the scene has an anisotropic microfacet material:
// alpha_u != alpha_v, or roughnesses from two different textures (the
// kernels' test, after the textures, is kernels/bsdf/frame.h's). Its BSDF
// then needs the surface's tangent dp/du (WP_HAS_ANISOTROPY), and its
// triangles their texture coordinates, which dp/du comes from.
bool has_anisotropy(const Scene& scene) {
    auto anisotropic = [&](std::uint32_t material) {
        const Material& m = scene.materials[material];
        if (m.kind != MaterialKind::RoughConductor && m.kind != MaterialKind::RoughDielectric)
            return false;
        if (m.alpha_u_texture != m.alpha_v_texture)
            return true;
        return m.alpha_u_texture == 0 && m.alpha_u != m.alpha_v;
    };
    // No anisotropic material, no pass over a big mesh's triangles.
    bool any = false;
    for (std::uint32_t m = 0; m < scene.materials.size(); ++m)
        any = any || anisotropic(m);
    if (!any)
        return false;
    bool found = false;
    for_each_defined_triangle(scene,
                              [&](const Triangle& t) { found = found || anisotropic(t.material); });
    return found || std::any_of(scene.spheres.begin(), scene.spheres.end(),
                                [&](const Sphere& s) { return anisotropic(s.material); });
}

void append_word(std::string& list, const std::string& word) {
    if (!list.empty())
        list += ' ';
    list += word;
}

// A box grown by a few float ulps of its magnitude. The triangle and sphere
// tests round, and may report a hit a few ulps outside the exact primitive
// (a ray through a shared edge must hit one of the two triangles, whichever
// side the rounding favours); the float bounds of a sphere rounded from
// double may also lose half an ulp. 2^-21 of the magnitude is 8 ulps.
Bounds3f widened(const Bounds3f& b) {
    const float magnitude =
        std::max({std::fabs(b.lower.x), std::fabs(b.lower.y), std::fabs(b.lower.z),
                  std::fabs(b.upper.x), std::fabs(b.upper.y), std::fabs(b.upper.z)});
    const float slack = magnitude * 0x1p-21f + 1e-30f;
    Bounds3f out;
    out.lower = b.lower - glm::vec3(slack);
    out.upper = b.upper + glm::vec3(slack);
    return out;
}

// The builder's tree with primitive numbers in leaf order (DeviceScene's
// triangles, spheres and instances are permuted so that each leaf's are
// contiguous), so that a leaf names a range of primitive numbers and needs no
// index array. A leaf that holds two kinds (triangles, spheres, instances),
// whose numbers cannot form one range, becomes an inner node over a leaf of
// the first kind and the rest: a leaf, or with three kinds another such node.
class BinaryWriter {
  public:
    BinaryWriter(const Bvh& bvh, const std::vector<Bounds3f>& boxes,
                 const std::vector<wp_uint>& new_number, wp_uint triangle_count,
                 wp_uint plain_count, std::vector<BinaryNode>& out)
        : bvh_(bvh), boxes_(boxes), new_number_(new_number), triangle_count_(triangle_count),
          plain_count_(plain_count), out_(out) {}

    // 0 a triangle, 1 a sphere, 2 an instance (by the builder's numbers).
    int kind(std::uint32_t p) const { return p < triangle_count_ ? 0 : p < plain_count_ ? 1 : 2; }

    void write(std::uint32_t index) {
        const BvhNode& node = bvh_.nodes[index];
        if (!node.is_leaf()) {
            const std::size_t at = push(node.bounds, 0, 0);
            write(index + 1);
            out_[at].offset = static_cast<wp_uint>(out_.size());
            write(node.second_child);
            return;
        }
        // build_hierarchy sorted a leaf's primitives by kind.
        const std::uint32_t* first = &bvh_.primitives[node.first_primitive];
        write_runs(node.bounds, first, first + node.primitive_count);
    }

  private:
    // A leaf of [first, last), split at its kinds' boundaries.
    void write_runs(const Bounds3f& bounds, const std::uint32_t* first, const std::uint32_t* last) {
        const std::uint32_t* run_end = first;
        while (run_end != last && kind(*run_end) == kind(*first))
            ++run_end;
        const auto run = static_cast<std::uint32_t>(run_end - first);
        if (run_end == last) {
            push(bounds, new_number_[*first], run);
            return;
        }
        const std::size_t at = push(bounds, 0, 0);
        push(bounds_of(first, run), new_number_[first[0]], run);
        out_[at].offset = static_cast<wp_uint>(out_.size());
        write_runs(bounds_of(run_end, static_cast<std::uint32_t>(last - run_end)), run_end, last);
    }

    std::size_t push(const Bounds3f& b, wp_uint offset, wp_uint count) {
        out_.push_back({b, offset, count});
        return out_.size() - 1;
    }

    Bounds3f bounds_of(const std::uint32_t* first, std::uint32_t count) const {
        if (boxes_.empty())
            throw std::logic_error("BVH leaf mixes primitive kinds, but no boxes were given");
        Bounds3f b;
        for (std::uint32_t k = 0; k < count; ++k)
            b.extend(boxes_[first[k]]);
        return b;
    }

    const Bvh& bvh_;
    const std::vector<Bounds3f>& boxes_;
    const std::vector<wp_uint>& new_number_;
    wp_uint triangle_count_;
    wp_uint plain_count_; // triangles and spheres; instances after them
    std::vector<BinaryNode>& out_;
};

// The build options of every hierarchy: the top level's and the groups'.
BvhBuildOptions hierarchy_options(std::uint32_t split_levels) {
    BvhBuildOptions options;
    options.max_depth = WP_BVH_MAX_DEPTH - split_levels; // mixed leaves' splits add levels
    // A wide node tests its boxes at once: SAH weighs its visit as two
    // triangle tests, which makes fewer, fuller leaves (docs/performance.md:
    // measured smaller and no slower than the default 1).
    options.traversal_cost = 2.0;
    options.max_leaf_size = 8;
    return options;
}

// The binary tree of `bvh` as eight-wide nodes appended to `nodes`; throws if
// the collapse broke its promise to keep every path within the traversal
// stack (wide_bvh.cpp). `boxes` are the builder's, needed only where a leaf
// mixes kinds: empty for a hierarchy of one kind.
void write_wide(const Bvh& bvh, const std::vector<Bounds3f>& boxes,
                const std::vector<wp_uint>& new_number, wp_uint triangle_count, wp_uint plain_count,
                DeviceArray<WpBvhNode>& nodes) {
    std::vector<BinaryNode> binary;
    binary.reserve(bvh.nodes.size());
    BinaryWriter(bvh, boxes, new_number, triangle_count, plain_count, binary).write(0);
    nodes.reserve(nodes.size() + bvh.nodes.size() / 7 + 1);
    if (write_wide_nodes(binary, nodes) > WP_BVH_STACK_SIZE)
        throw std::logic_error("BVH too deep for the traversal stack");
}

// The hierarchy over every primitive, with the primitives put in its leaf
// order and every primitive number (the lights') renumbered to match. Each
// instance's first_primitive holds its group's triangle count on entry and
// its hits' first number on return (they follow the instances' new order).
void build_hierarchy(DeviceScene& scene) {
    const auto triangle_count = static_cast<wp_uint>(scene.triangles.size());
    const auto plain_count = triangle_count + static_cast<wp_uint>(scene.spheres.size());
    // Only leaves that mix kinds need the boxes after the build (BinaryWriter);
    // a scene of one kind moves them into the builder, which frees them early.
    const int kinds = static_cast<int>(!scene.triangles.empty()) +
                      static_cast<int>(!scene.spheres.empty()) +
                      static_cast<int>(!scene.instances.empty());
    const bool mixed = kinds > 1;
    std::vector<Bounds3f> boxes = primitive_boxes(scene);
    const BvhBuildOptions options = hierarchy_options(scene.instances.empty() ? 1 : 2);
    Bvh bvh = mixed ? build_bvh(boxes, options) : build_bvh(std::move(boxes), options);
    if (!mixed)
        boxes.clear();
    auto kind = [&](std::uint32_t p) { return p < triangle_count ? 0 : p < plain_count ? 1 : 2; };
    // Within each leaf, triangles, then spheres, then instances (BinaryWriter
    // splits mixed leaves there). A scene of one kind is in order already.
    for (const BvhNode& node : bvh.nodes)
        if (mixed && node.is_leaf())
            std::stable_sort(bvh.primitives.begin() + node.first_primitive,
                             bvh.primitives.begin() + node.first_primitive + node.primitive_count,
                             [&](std::uint32_t a, std::uint32_t b) { return kind(a) < kind(b); });

    std::vector<wp_uint> new_number(bvh.primitives.size());
    DeviceArray<WpTriangle> triangles;
    DeviceArray<WpSphere> spheres;
    DeviceArray<WpInstance> instances;
    std::vector<Bounds3f> instance_boxes;
    triangles.reserve(scene.triangles.size());
    spheres.reserve(scene.spheres.size());
    instances.reserve(scene.instances.size());
    for (std::uint32_t p : bvh.primitives)
        if (p < triangle_count) {
            new_number[p] = static_cast<wp_uint>(triangles.size());
            triangles.push_back(scene.triangles[p]);
        } else if (p < plain_count) {
            new_number[p] = triangle_count + static_cast<wp_uint>(spheres.size());
            spheres.push_back(scene.spheres[p - triangle_count]);
        } else {
            new_number[p] = plain_count + static_cast<wp_uint>(instances.size());
            instances.push_back(scene.instances[p - plain_count]);
            instance_boxes.push_back(scene.instance_boxes[p - plain_count]);
        }
    scene.triangles = std::move(triangles);
    scene.spheres = std::move(spheres);
    scene.instances = std::move(instances);
    scene.instance_boxes = std::move(instance_boxes);
    wp_uint next = 0; // validate_scene keeps the numbers within 32 bits
    for (WpInstance& m : scene.instances) {
        const wp_uint count = m.first_primitive;
        m.first_primitive = next;
        next += count;
    }
    scene.instanced_triangles = next;
    for (WpLight& light : scene.lights)
        light.triangle = new_number[light.triangle];
    for (WpEmitter& e : scene.emitters)
        if (e.kind == WP_EMITTER_SPHERE)
            e.sphere = new_number[triangle_count + e.sphere] - triangle_count;

    write_wide(bvh, boxes, new_number, triangle_count, plain_count, scene.bvh_nodes);
    scene.bvh_stats = bvh.stats;
}

// A triangle's float record: material, vertex normals and texture
// coordinates (appended to out's tables), vertices mapped by `point`.
template <typename Point>
WpTriangle flatten_triangle(const Triangle& t, bool uvs, Point&& point, DeviceScene& out) {
    WpTriangle w{};
    w.v0 = to_float4(point(t.v[0]));
    w.v1 = to_float4(point(t.v[1]));
    w.v2 = to_float4(point(t.v[2]));
    wp_set_triangle_material(&w, t.material);
    if (t.has_normals) {
        WpShadingNormals n{};
        n.n0 = to_float4(t.normals[0]);
        n.n1 = to_float4(t.normals[1]);
        n.n2 = to_float4(t.normals[2]);
        out.triangle_normals.push_back(n);
        wp_set_triangle_normals(&w, static_cast<wp_uint>(out.triangle_normals.size())); // k + 1
    }
    if (uvs && t.has_uvs) {
        WpTriangleUvs c{};
        for (int k = 0; k < 3; ++k) {
            c.u.s[k] = static_cast<float>(t.uvs[k].x);
            c.v.s[k] = static_cast<float>(t.uvs[k].y);
        }
        out.triangle_uvs.push_back(c);
        wp_set_triangle_uvs(&w, static_cast<wp_uint>(out.triangle_uvs.size())); // k + 1
    }
    return w;
}

// The shape groups (their triangles in object space, in each group's
// hierarchy's leaf order, and the hierarchies) and the instances (their maps
// into the float frame and their boxes there). A group is built once however
// many instances place it; instances of a group that lost every triangle
// (zero-area ones are skipped) place nothing and are left out.
//
// An instance's box is its group's box mapped to the world, widened for the
// rounding of the ray's map into object space: the kernel finds hits along
// the rounded object-space ray, a few ulps of the ray's coordinates times the
// map's condition number from the exact one. The slack is 2^-16 of the
// frame's largest coordinate (the ray origins lie within it), which covers
// condition numbers up to about 2^7 with room; a box a little too large only
// costs a few extra visits.
void flatten_instances(const Scene& scene, const FloatFrame& frame, bool uvs, DeviceScene& out) {
    struct GroupRecord {
        wp_uint root = 0, first = 0, count = 0;
        Bounds3f box;
    };
    std::vector<GroupRecord> groups;
    for (const ShapeGroup& group : scene.shape_groups) {
        GroupRecord g;
        g.first = static_cast<wp_uint>(out.group_triangles.size());
        g.count = static_cast<wp_uint>(group.triangles.size());
        std::vector<WpTriangle> triangles;
        triangles.reserve(group.triangles.size());
        for (const Triangle& t : group.triangles)
            triangles.push_back(flatten_triangle(
                t, uvs, [](const glm::dvec3& p) { return p; }, out));
        if (triangles.empty()) {
            groups.push_back(g);
            continue;
        }
        std::vector<Bounds3f> boxes;
        boxes.reserve(triangles.size());
        for (const WpTriangle& t : triangles) {
            Bounds3f b;
            for (const wp_float4* v : {&t.v0, &t.v1, &t.v2})
                b.extend(glm::vec3(v->s[0], v->s[1], v->s[2]));
            boxes.push_back(widened(b));
            g.box.extend(boxes.back());
        }
        const Bvh bvh = build_bvh(std::move(boxes), hierarchy_options(1));
        std::vector<wp_uint> new_number(triangles.size());
        for (std::uint32_t p : bvh.primitives) {
            new_number[p] = static_cast<wp_uint>(out.group_triangles.size());
            out.group_triangles.push_back(triangles[p]);
        }
        g.root = static_cast<wp_uint>(out.group_bvh_nodes.size());
        write_wide(bvh, {}, new_number, g.count, g.count, out.group_bvh_nodes); // triangles only
        groups.push_back(g);
    }

    // The frame's largest coordinate: the scene's box mapped (render/float_range.hpp).
    const SceneBox world = scene_box(scene);
    const double magnitude =
        std::max(glm::length(frame.point(world.lower)), glm::length(frame.point(world.upper)));
    const double slack = magnitude * 0x1p-16;
    for (const Instance& instance : scene.instances) {
        const GroupRecord& g = groups[instance.group];
        if (g.count == 0)
            continue;
        // p -> frame.scale (to_world p - origin): the frame after the instance's map.
        glm::dmat4 to_frame = instance.to_world;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r)
                to_frame[c][r] *= frame.scale;
        for (int r = 0; r < 3; ++r)
            to_frame[3][r] -= frame.scale * frame.origin[r];
        const glm::dmat4 to_object = glm::inverse(to_frame);
        WpInstance m{};
        for (int r = 0; r < 3; ++r) {
            m.to_world[r] = to_float4(glm::dvec3(to_frame[0][r], to_frame[1][r], to_frame[2][r]),
                                      to_frame[3][r]);
            m.to_object[r] = to_float4(
                glm::dvec3(to_object[0][r], to_object[1][r], to_object[2][r]), to_object[3][r]);
        }
        m.root = g.root;
        m.first_triangle = g.first;
        m.first_primitive = g.count; // the hits' numbers follow the hierarchy (build_hierarchy)
        m.mirrored = glm::determinant(glm::dmat3(to_frame)) < 0.0 ? 1u : 0u;
        out.instances.push_back(m);
        DoubleBox object;
        object.extend(glm::dvec3(g.box.lower));
        object.extend(glm::dvec3(g.box.upper));
        const DoubleBox mapped = mapped_box(object, to_frame);
        Bounds3f b;
        b.lower = glm::vec3(mapped.lower - glm::dvec3(slack));
        b.upper = glm::vec3(mapped.upper + glm::dvec3(slack));
        out.instance_boxes.push_back(widened(b));
    }
}

// The mean of a colour's channels: what a light's power is compared by.
double channel_mean(const glm::dvec3& c) {
    return (c.x + c.y + c.z) / 3.0;
}

// The emitters in the float frame, and the probabilities of choosing them
// and the emissive triangles: proportional to an estimate of the power each
// emits (the mean of its channels), so that a faint light takes few samples.
// Point, 4 pi I; spot, 2 pi (1 - cos cutoff) I (its cone at full
// intensity); triangles, pi L A summed; directional, E through the disk of
// the scene's bounding sphere (pi R^2 E), constant, L through that sphere
// (4 pi^2 R^2 L), and envmap, pi R^2 times its radiance integrated over the
// sphere of directions, which is what of them can reach the scene. Any
// choice with every light's probability > 0 is unbiased: the kernels divide
// by the probability and multiple importance sampling weighs by it
// (lights.h, shade.cl). Emitters of zero power are left out. The
// environment (constant or envmap) comes first (shade.cl finds it there for
// an escaping ray).
void flatten_emitters(const Scene& scene, const FloatFrame& frame, double triangle_area_power,
                      DeviceScene& out) {
    if (!has_lights_besides_triangles(scene))
        return;
    // The scene's bounding box in the float frame: its diagonal gives the
    // radius for the infinite emitters' power and their shadow rays' reach.
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const Triangle& t : scene.triangles)
        for (const glm::dvec3& v : t.v) {
            lo = glm::min(lo, frame.point(v));
            hi = glm::max(hi, frame.point(v));
        }
    for (const Sphere& s : scene.spheres) {
        lo = glm::min(lo, frame.point(s.center) - glm::dvec3(frame.scale * s.radius));
        hi = glm::max(hi, frame.point(s.center) + glm::dvec3(frame.scale * s.radius));
    }
    for (const Bounds3f& b : out.instance_boxes) { // flatten_instances came first
        lo = glm::min(lo, glm::dvec3(b.lower));
        hi = glm::max(hi, glm::dvec3(b.upper));
    }
    const double diagonal = glm::length(hi - lo);
    const double radius = 0.5 * diagonal / frame.scale; // scene units, for the power
    std::vector<double> power;
    DeviceArray<WpEmitter> emitters;
    for (const Emitter& e : scene.emitters) {
        WpEmitter w{};
        w.kind = static_cast<wp_uint>(e.kind);
        const double mean = channel_mean(e.value);
        double p = 0.0;
        switch (e.kind) {
        case EmitterKind::Point:
        case EmitterKind::Spot: {
            // Intensity over a squared distance: lengths in the float frame
            // are scale times longer, so the intensity is scale^2 larger.
            w.position = to_float4(frame.point(e.position));
            w.direction = to_float4(glm::normalize(e.direction));
            w.radiance = to_float4(e.value * (frame.scale * frame.scale));
            const double cutoff = e.cutoff_angle * M_PI / 180.0;
            const double beam = e.beam_width * M_PI / 180.0;
            w.cos_cutoff = static_cast<float>(std::cos(cutoff));
            w.cos_beam = static_cast<float>(std::cos(beam));
            w.cutoff = static_cast<float>(cutoff);
            // A beam as wide as the cutoff has no falloff (the kernel's
            // first test takes every direction inside): no 1 / 0.
            w.inv_transition = beam < cutoff ? static_cast<float>(1.0 / (cutoff - beam)) : 0.0f;
            p = e.kind == EmitterKind::Point ? 4.0 * M_PI * mean
                                             : 2.0 * M_PI * (1.0 - std::cos(cutoff)) * mean;
            break;
        }
        case EmitterKind::Directional:
            w.direction = to_float4(glm::normalize(e.direction));
            w.radiance = to_float4(e.value);
            p = M_PI * radius * radius * mean;
            break;
        case EmitterKind::Constant:
            w.radiance = to_float4(e.value);
            p = 4.0 * M_PI * M_PI * radius * radius * mean;
            break;
        case EmitterKind::Envmap: {
            const EnvironmentTables tables = build_environment_tables(*e.image);
            if (tables.cdf.empty())
                break; // black: zero power, left out
            // The kernels index texels with 32-bit offsets.
            if (out.texels.size() + tables.rgb.size() > std::size_t{0xffffffffu})
                throw std::runtime_error(
                    "the scene's textures and environment map hold more than 16 GiB of texels; "
                    "the device's 32-bit offsets cannot reach past that");
            w.radiance = to_float4(e.value);
            // Rows of the inverse rotation: its transpose's columns.
            const glm::dmat3 to_local = glm::transpose(e.to_world);
            for (int r = 0; r < 3; ++r)
                w.to_local[r] =
                    to_float4(glm::dvec3(to_local[0][r], to_local[1][r], to_local[2][r]));
            w.width = tables.width;
            w.height = tables.height;
            w.texels_first = static_cast<wp_uint>(out.texels.size());
            for (float c : tables.rgb)
                out.texels.push_back(std::bit_cast<wp_uint>(c));
            w.cdf_first = static_cast<wp_uint>(out.environment_cdf.size());
            out.environment_cdf.insert(out.environment_cdf.end(), tables.cdf.begin(),
                                       tables.cdf.end());
            p = M_PI * radius * radius * tables.integral * mean;
            break;
        }
        }
        // Twice the diagonal, so that a shadow ray from anywhere inside
        // leaves the box whatever its direction.
        w.reach = static_cast<float>(std::max(2.0 * diagonal, 1.0));
        if (!(p > 0.0))
            continue;
        if (e.kind == EmitterKind::Constant || e.kind == EmitterKind::Envmap) {
            emitters.insert(emitters.begin(), w);
            power.insert(power.begin(), p);
        } else {
            emitters.push_back(w);
            power.push_back(p);
        }
    }
    // Emitting spheres: pi L times their area, as triangles.
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& sphere = scene.spheres[i];
        const Material& material = scene.materials[sphere.material];
        const double p =
            M_PI * channel_mean(material.emission) * 4.0 * M_PI * sphere.radius * sphere.radius;
        if (!(p > 0.0))
            continue;
        WpEmitter w{};
        w.kind = WP_EMITTER_SPHERE;
        w.position = to_float4(frame.point(sphere.center), frame.scale * sphere.radius);
        w.radiance = to_float4(material.emission);
        w.sphere = static_cast<wp_uint>(i);
        emitters.push_back(w);
        power.push_back(p);
    }
    if (emitters.empty())
        return;
    const double area_power = M_PI * triangle_area_power;
    double total = area_power;
    for (double p : power)
        total += p;
    out.emitter_pick = static_cast<float>((total - area_power) / total);
    double running = area_power;
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        emitters[i].pick = static_cast<float>(power[i] / total);
        running += power[i];
        emitters[i].cdf = static_cast<float>(running / total);
    }
    emitters.back().cdf = 1.0f; // never let rounding leave u in no bin
    out.emitters = std::move(emitters);
}

// With lights: the spheres of a mirror material (DeviceScene::mirror_spheres),
// by their place in out.spheres.
void list_mirror_spheres(DeviceScene& out, const std::vector<Material>& materials) {
    if (!out.lights.empty())
        for (std::size_t i = 0; i < out.spheres.size(); ++i)
            if (materials[out.spheres[i].material].kind == MaterialKind::Mirror)
                out.mirror_spheres.push_back(static_cast<wp_uint>(i));
}

// Hierarchies built by add_hierarchy in this process (scene_hierarchies_built).
std::atomic<std::uint64_t> hierarchies_built{0};

} // namespace

void set_light_guides(DeviceArray<WpLight>& lights) {
    const std::size_t count = lights.size();
    std::size_t j = 0;
    for (std::size_t k = 0; k < count; ++k) {
        const double start = static_cast<double>(k) / static_cast<double>(count);
        while (j + 1 < count && static_cast<double>(lights[j].cdf) <= start)
            ++j;
        lights[k].guide = static_cast<wp_uint>(j);
    }
}

std::string SceneFeatures::build_options() const {
    std::string options;
#define WP_FEATURE_FLAG(member, kernel_switch) append_word(options, flag(#kernel_switch, member));
    WP_SCENE_FEATURES(WP_FEATURE_FLAG)
#undef WP_FEATURE_FLAG
    if (fixed_counts)
        options += " -D WP_TRIANGLE_COUNT=" + std::to_string(triangle_count) +
                   " -D WP_SPHERE_COUNT=" + std::to_string(sphere_count) +
                   " -D WP_LIGHT_COUNT=" + std::to_string(light_count) +
                   " -D WP_MIRROR_GROUP_TRIANGLES=" + std::to_string(mirror_group_triangles);
    if (fixed_counts && shadow_culling) {
        options += " -D WP_SHADOW_OCCLUDER_COUNT=" + std::to_string(shadow_occluders.size());
        std::string list;
        for (std::uint32_t i : shadow_occluders) {
            if (!list.empty())
                list += ',';
            list += std::to_string(i);
        }
        if (!list.empty())
            options += " -D WP_SHADOW_OCCLUDERS=" + list;
    }
    if (bvh)
        options += " -D WP_USE_BVH=1";
    return options;
}

std::string SceneFeatures::describe() const {
    std::string out;
#define WP_FEATURE_NAME(member, kernel_switch)                                                     \
    if (member)                                                                                    \
        append_word(out, #member);
    WP_SCENE_FEATURES(WP_FEATURE_NAME)
#undef WP_FEATURE_NAME
    if (fixed_counts)
        out += "; counts " + std::to_string(triangle_count) + "+" + std::to_string(sphere_count);
    if (fixed_counts && shadow_culling)
        out += "; shadow tests " + std::to_string(shadow_occluders.size()) + " of " +
               std::to_string(triangle_count) + " triangles";
    if (bvh)
        out += "; bvh";
    return out;
}

SceneFeatures analyse_features(const Scene& scene, std::uint32_t max_fixed_count_primitives) {
    SceneFeatures f;
    f.triangles = !scene.triangles.empty();
    f.spheres = !scene.spheres.empty();
    f.instances = !scene.instances.empty();
    // One pass over the triangles (a big mesh's take most of the analysis):
    // which materials are used, and whether any triangle has vertex normals.
    std::vector<bool> material_used(scene.materials.size(), false);
    f.shading_normals = false;
    for_each_defined_triangle(scene, [&](const Triangle& t) {
        material_used[t.material] = true;
        f.shading_normals |= t.has_normals;
    });
    for (const Sphere& s : scene.spheres)
        material_used[s.material] = true;
    auto uses = [&](MaterialKind kind) {
        for (std::size_t m = 0; m < scene.materials.size(); ++m)
            if (material_used[m] && scene.materials[m].kind == kind)
                return true;
        return false;
    };
    // One feature per material kind with a BSDF: on when the scene uses it.
#define WP_MATERIAL_FEATURE_USED(features, KIND, Name, name, value, bsdf, glossy)                  \
    WP_IF(bsdf)(features.name = uses(MaterialKind::Name);)
    WP_MATERIALS_WITH(WP_MATERIAL_FEATURE_USED, f)
#undef WP_MATERIAL_FEATURE_USED
    const auto lights = static_cast<std::uint32_t>(
        std::count_if(scene.triangles.begin(), scene.triangles.end(), [&](const Triangle& t) {
            return scene.materials[t.material].is_emissive();
        }));
    f.lights = lights > 0;
    auto has_emitter = [&](EmitterKind kind) {
        return std::any_of(scene.emitters.begin(), scene.emitters.end(),
                           [&](const Emitter& e) { return e.kind == kind; });
    };
    f.point_light = has_emitter(EmitterKind::Point);
    f.spot_light = has_emitter(EmitterKind::Spot);
    f.directional_light = has_emitter(EmitterKind::Directional);
    f.constant_light = has_emitter(EmitterKind::Constant);
    f.envmap_light = has_emitter(EmitterKind::Envmap);
    f.sphere_light = has_sphere_lights(scene);
    f.power_light_pick = f.lights && triangle_radiances_differ(scene);
    // Next-event estimation through planar mirrors needs both (kernels/mirror_light.h).
    // It is an estimator of its own beside the light sample, of the emissive
    // triangles' light by way of a mirror, so it holds beside other emitters
    // too (their light by way of a mirror is found by the path itself).
    const bool mirror_nee = f.lights;
    const std::vector<PlanarMirror> mirrors = find_planar_mirrors(scene);
    f.planar_mirrors = mirror_nee && !mirrors.empty();
    f.mirror_spheres =
        mirror_nee && std::any_of(scene.spheres.begin(), scene.spheres.end(), [&](const Sphere& s) {
            return scene.materials[s.material].kind == MaterialKind::Mirror;
        });
    f.lens = scene.camera.aperture_radius > 0.0;
    f.anisotropy = has_anisotropy(scene);
    // One feature per texture kind: on when a material uses one.
#define WP_TEXTURE_FEATURE_USED(features, KIND, Name, name, value)                                 \
    features.name##_texture =                                                                      \
        std::any_of(scene.textures.begin(), scene.textures.end(),                                  \
                    [](const Texture& t) { return t.kind == TextureKind::Name; });
    WP_TEXTURES_WITH(WP_TEXTURE_FEATURE_USED, f)
#undef WP_TEXTURE_FEATURE_USED
    // One feature per filter with sampling code: on when the camera uses it.
#define WP_FILTER_FEATURE_USED(features, KIND, Name, name, value, sampled)                         \
    WP_IF(sampled)(features.name##_filter = scene.camera.filter == FilterKind::Name;)
    WP_FILTERS_WITH(WP_FILTER_FEATURE_USED, f)
#undef WP_FILTER_FEATURE_USED
    const std::size_t primitives = scene.triangles.size() + scene.spheres.size();
    // Instances are traversed only through the hierarchy (kernels/instance.h).
    f.bvh = primitives >= kMinBvhPrimitives || f.instances;
    f.fixed_counts = !f.bvh && primitives <= max_fixed_count_primitives;
    if (f.fixed_counts) {
        f.triangle_count = static_cast<std::uint32_t>(scene.triangles.size());
        f.sphere_count = static_cast<std::uint32_t>(scene.spheres.size());
        f.light_count = lights;
        if (f.planar_mirrors)
            for (const PlanarMirror& mirror : mirrors)
                f.mirror_group_triangles = std::max(
                    f.mirror_group_triangles, static_cast<std::uint32_t>(mirror.triangles.size()));
        f.shadow_occluders = shadow_occluders(scene);
        // The occluders are chosen by the side of each plane the eye is on;
        // a lens's camera rays leave anywhere on its aperture, so it keeps
        // every occluder.
        // Nor can emitters keep it: a sun, the sky or a point outside must be
        // blocked by the very bounding faces culling leaves out.
        f.shadow_culling = !f.lens && !has_lights_besides_triangles(scene) &&
                           f.shadow_occluders.size() < scene.triangles.size();
    }
    return f;
}

void check_triangle_indices(std::size_t materials, std::size_t normal_sets) {
    if (materials > WP_TRIANGLE_INDEX_LIMIT || normal_sets > WP_TRIANGLE_INDEX_LIMIT)
        throw std::runtime_error("the scene has " + std::to_string(materials) + " materials and " +
                                 std::to_string(normal_sets) +
                                 " triangles with vertex normals; the device's triangles hold at "
                                 "most " +
                                 std::to_string(WP_TRIANGLE_INDEX_LIMIT) + " of each");
}

void flatten_textures(const Scene& scene, DeviceScene& out) {
    // A file named by several textures is uploaded once.
    std::map<const TextureImage*, wp_uint> first_texel;
    for (const Texture& t : scene.textures) {
        WpTexture w{};
        w.kind = static_cast<wp_uint>(t.kind);
        w.to_u = to_float4(t.to_u);
        w.to_v = to_float4(t.to_v);
        w.color0 = to_float4(t.color0);
        w.color1 = to_float4(t.color1);
        w.wrap = static_cast<wp_uint>(t.wrap);
        w.filter = static_cast<wp_uint>(t.filter);
        if (t.image) {
            const TextureImage& image = *t.image;
            w.width = image.width;
            w.height = image.height;
            w.format = image.encoding == TexelEncoding::Float32 ? WP_TEXELS_RGB32F
                       : image.encoding == TexelEncoding::Srgb8 ? WP_TEXELS_RGBA8_SRGB
                                                                : WP_TEXELS_RGBA8;
            // The kernels index texels with 32-bit offsets.
            if (out.texels.size() + image.texels.size() > std::size_t{0xffffffffu})
                throw std::runtime_error(
                    "the scene's textures hold more than 16 GiB of texels; the device's "
                    "texture offsets are 32-bit");
            if (const auto it = first_texel.find(&image); it != first_texel.end()) {
                w.first = it->second;
            } else {
                w.first = static_cast<wp_uint>(out.texels.size());
                first_texel.emplace(&image, w.first);
                out.texels.insert(out.texels.end(), image.texels.begin(), image.texels.end());
            }
        }
        out.textures.push_back(w);
    }
}

DeviceScene flatten_scene(const Scene& scene, bool hierarchy, LightPick pick) {
    DeviceScene out = flatten_without_hierarchy(scene, hierarchy, pick);
    if (hierarchy)
        add_hierarchy(out, scene.materials);
    return out;
}

DeviceScene flatten_without_hierarchy(const Scene& scene, bool hierarchy, LightPick pick) {
    std::size_t normal_sets = 0, uv_sets = 0; // with the shape groups', which share the tables
    for_each_defined_triangle(scene, [&](const Triangle& t) {
        normal_sets += t.has_normals;
        uv_sets += t.has_uvs;
    });
    check_triangle_indices(scene.materials.size(), normal_sets);
    check_triangle_indices(0, uv_sets);
    if (!scene.instances.empty() && !hierarchy)
        throw std::logic_error("a scene with instances is traversed through a hierarchy");
    DeviceScene out;
    out.width = scene.camera.width;
    out.height = scene.camera.height;

    for (const Material& m : scene.materials) {
        WpMaterial w{};
        w.reflectance = to_float4(m.reflectance);
        w.emission = to_float4(m.emission);
        w.kind = static_cast<wp_uint>(m.kind);
        w.eta = to_float4(m.eta);
        w.k = to_float4(m.k);
        // Material "none" (eta 0, k 1) reflects everything: F = 1 exactly,
        // without the Fresnel formula's rounding.
        w.fresnel = m.eta == glm::dvec3(0.0) && m.k == glm::dvec3(1.0) ? 0u : 1u;
        w.distribution = static_cast<wp_uint>(m.distribution);
        w.alpha_u = static_cast<float>(m.alpha_u);
        w.alpha_v = static_cast<float>(m.alpha_v);
        w.transmittance = to_float4(m.transmittance);
        w.specular = to_float4(m.specular);
        if (m.kind == MaterialKind::Dielectric || m.kind == MaterialKind::ThinDielectric ||
            m.kind == MaterialKind::RoughDielectric || m.kind == MaterialKind::Plastic ||
            m.kind == MaterialKind::RoughPlastic)
            w.eta = to_float4(glm::dvec3(m.int_ior / m.ext_ior));
        if (m.kind == MaterialKind::Plastic || m.kind == MaterialKind::RoughPlastic) {
            const double eta = m.int_ior / m.ext_ior;
            if (m.kind == MaterialKind::Plastic) {
                w.fdr_int = static_cast<float>(fresnel_diffuse_reflectance(1.0 / eta));
            } else {
                const RoughCoating coating = rough_coating(m.distribution, m.alpha_u, eta);
                w.fdr_int = static_cast<float>(coating.internal_reflectance);
                for (int i = 0; i < WP_ROUGH_TRANSMITTANCE_RES; ++i)
                    w.rough_transmittance[i] =
                        static_cast<float>(coating.transmittance[static_cast<std::size_t>(i)]);
            }
            // Mitsuba's specular_sampling_weight: the coating's share of the
            // mean reflectances (it steers sampling only, never the estimate).
            // A textured reflectance counts with the texture's mean, as in Mitsuba.
            auto mean = [&](const glm::dvec3& constant, std::uint32_t texture) {
                const glm::dvec3 c = texture ? scene.textures[texture - 1].mean() : constant;
                return (c.x + c.y + c.z) / 3.0;
            };
            const double s = mean(m.specular, m.specular_texture);
            const double d = mean(m.reflectance, m.reflectance_texture);
            w.specular_weight = static_cast<float>(s + d > 0.0 ? s / (s + d) : 0.5);
            w.nonlinear = m.nonlinear ? 1u : 0u;
        }
        w.reflectance_texture = m.reflectance_texture;
        w.specular_texture = m.specular_texture;
        w.transmittance_texture = m.transmittance_texture;
        w.alpha_u_texture = m.alpha_u_texture;
        w.alpha_v_texture = m.alpha_v_texture;
        out.materials.push_back(w);
    }
    flatten_textures(scene, out);
    // Texture coordinates only where a texture or an anisotropic BSDF's
    // tangent can read them: any other scene keeps its triangles (and
    // images) as they were.
    const bool uvs = !scene.textures.empty() || has_anisotropy(scene);

    // Coordinates in float32's comfortable range, exactly (render/float_range.hpp).
    const FloatFrame frame = float_frame(scene);

    std::vector<double> areas;
    double total_area = 0.0;
    double triangle_power = 0.0; // sum of mean radiance x area: the triangles' power / pi
    out.triangles.reserve(scene.triangles.size()); // exactly: no growth by doubling
    out.triangle_normals.reserve(normal_sets);     // (the shape groups' included)
    if (uvs)
        out.triangle_uvs.reserve(uv_sets);
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        out.triangles.push_back(flatten_triangle(
            t, uvs, [&](const glm::dvec3& p) { return frame.point(p); }, out));
        if (scene.materials[t.material].is_emissive()) {
            const glm::dvec3 e1 = frame.scale * (t.v[1] - t.v[0]);
            const glm::dvec3 e2 = frame.scale * (t.v[2] - t.v[0]);
            double area = 0.5 * glm::length(glm::cross(e1, e2));
            WpLight light{};
            light.triangle = static_cast<wp_uint>(i);
            out.lights.push_back(light);
            areas.push_back(area);
            total_area += area;
            triangle_power += channel_mean(scene.materials[t.material].emission) * area;
        }
    }
    build_light_pick(scene, areas, pick == LightPick::Power && triangle_radiances_differ(scene),
                     out.lights, out.materials);
    out.light_area = static_cast<float>(total_area);

    flatten_instances(scene, frame, uvs, out);
    flatten_emitters(scene, frame, triangle_power / (frame.scale * frame.scale), out);

    // Planar mirrors in the float frame: the plane from the frame's vertices.
    for (const PlanarMirror& mirror : find_planar_mirrors(scene)) {
        WpMirrorGroup g{};
        const Triangle& first = scene.triangles[mirror.triangles.front()];
        g.plane = to_float4(mirror.normal, glm::dot(mirror.normal, frame.point(first.v[0])));
        g.first = static_cast<wp_uint>(out.mirror_triangles.size());
        g.count = static_cast<wp_uint>(mirror.triangles.size());
        for (std::uint32_t i : mirror.triangles)
            out.mirror_triangles.push_back(out.triangles[i]);
        out.mirror_groups.push_back(g);
    }

    for (const Sphere& s : scene.spheres) {
        WpSphere w{};
        w.center_radius = to_float4(frame.point(s.center), frame.scale * s.radius);
        w.material = s.material;
        out.spheres.push_back(w);
    }

    const Camera& c = scene.camera;
    glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
    glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    glm::dvec3 up = glm::cross(right, forward);
    double half_height = std::tan(0.5 * c.vertical_fov_degrees * M_PI / 180.0);
    double aspect = static_cast<double>(c.width) / static_cast<double>(c.height);
    out.camera.eye = to_float4(frame.point(c.eye));
    out.camera.forward = to_float4(forward);
    out.camera.right = to_float4(right * (half_height * aspect));
    out.camera.up = to_float4(up * half_height);
    // Lengths scale with the scene's float frame, as coordinates do.
    const double aperture = frame.scale * c.aperture_radius;
    out.camera.lens_right = to_float4(right * aperture, frame.scale * c.focus_distance);
    out.camera.lens_up = to_float4(up * aperture, aperture);
    out.camera.filter = static_cast<wp_uint>(c.filter);
    switch (c.filter) {
    case FilterKind::Box:
        out.camera.filter_radius = 0.5f;
        break;
    case FilterKind::Tent:
        out.camera.filter_radius = static_cast<float>(c.filter_radius);
        break;
    case FilterKind::Gaussian: {
        // Mitsuba's: cut off at 4 standard deviations, less its value there.
        const double radius = 4.0 * c.filter_stddev;
        const double scale = 1.0 / (c.filter_stddev * std::sqrt(2.0));
        out.camera.filter_radius = static_cast<float>(radius);
        out.camera.filter_scale = static_cast<float>(scale);
        out.camera.filter_bias = static_cast<float>(std::exp(-(radius * scale) * (radius * scale)));
        break;
    }
    }

    if (!hierarchy)
        list_mirror_spheres(out, scene.materials);
    return out;
}

void add_hierarchy(DeviceScene& scene, const std::vector<Material>& materials) {
    build_hierarchy(scene);
    hierarchies_built.fetch_add(1, std::memory_order_relaxed);
    list_mirror_spheres(scene, materials); // after the hierarchy, which may reorder the spheres
}

std::uint64_t scene_hierarchies_built() {
    return hierarchies_built.load(std::memory_order_relaxed);
}

std::vector<Bounds3f> primitive_boxes(const DeviceScene& scene) {
    std::vector<Bounds3f> boxes;
    boxes.reserve(scene.triangles.size() + scene.spheres.size());
    for (const WpTriangle& t : scene.triangles) {
        Bounds3f b;
        for (const wp_float4* v : {&t.v0, &t.v1, &t.v2})
            b.extend(glm::vec3(v->s[0], v->s[1], v->s[2]));
        boxes.push_back(widened(b));
    }
    for (const WpSphere& s : scene.spheres) {
        const glm::dvec3 c(s.center_radius.s[0], s.center_radius.s[1], s.center_radius.s[2]);
        const double r = s.center_radius.s[3];
        Bounds3f b;
        b.extend(glm::vec3(c - glm::dvec3(r)));
        b.extend(glm::vec3(c + glm::dvec3(r)));
        boxes.push_back(widened(b));
    }
    boxes.insert(boxes.end(), scene.instance_boxes.begin(), scene.instance_boxes.end());
    return boxes;
}

} // namespace wp
