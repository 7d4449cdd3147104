// Mitsuba 3's shapes as triangles and spheres (shapes.hpp).
#include "scene/mitsuba/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include "scene/json_reader.hpp"
#include "scene/mesh.hpp"
#include "scene/mesh_normals.hpp"
#include "scene/mitsuba/parameters.hpp"
#include "scene/validate.hpp"

namespace wp::mitsuba {
namespace {

// A triangle of an analytic shape in its own space, with the texture
// coordinates Mitsuba gives its corners.
struct Corners {
    std::array<glm::dvec3, 3> p;
    std::array<glm::dvec2, 3> uv;
};

// (x, y) of [-1, 1]^2 as [0, 1]^2: the rectangle's texture coordinates.
glm::dvec2 unit_square(double x, double y) {
    return {0.5 * (x + 1.0), 0.5 * (y + 1.0)};
}

// Triangles of Mitsuba's analytic shapes in their own space, each facing
// its front (the side of cross(v1 - v0, v2 - v0)).
std::vector<Corners> rectangle() {
    // [-1, 1]^2 in the plane z = 0, facing +z.
    const glm::dvec3 a{-1, -1, 0}, b{1, -1, 0}, c{1, 1, 0}, d{-1, 1, 0};
    auto uv = [](const glm::dvec3& q) { return unit_square(q.x, q.y); };
    return {{{a, b, c}, {uv(a), uv(b), uv(c)}}, {{a, c, d}, {uv(a), uv(c), uv(d)}}};
}

// Mitsuba 3.9.1's cube: each face's texture coordinates as a function of the
// point (measured with ray_intersect, two points a face).
glm::dvec2 cube_uv(int axis, double side, const glm::dvec3& q) {
    const double x = q.x, y = q.y, z = q.z;
    switch (axis) {
    case 0:
        return side < 0.0 ? unit_square(y, z) : unit_square(y, -z);
    case 1:
        return side < 0.0 ? unit_square(z, x) : unit_square(-x, -z);
    default:
        return side < 0.0 ? unit_square(-y, x) : unit_square(y, x);
    }
}

std::vector<Corners> cube() {
    // [-1, 1]^3, every face outwards: each face is a rectangle turned onto
    // its axis.
    std::vector<Corners> out;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            // u, v span the face so that cross(u, v) points along +side on axis.
            glm::dvec3 n(0.0), u(0.0), v(0.0);
            n[axis] = side;
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = side;
            const glm::dvec3 a = n - u - v, b = n + u - v, c = n + u + v, d = n - u + v;
            auto uv = [&](const glm::dvec3& q) { return cube_uv(axis, side, q); };
            out.push_back({{a, b, c}, {uv(a), uv(b), uv(c)}});
            out.push_back({{a, c, d}, {uv(a), uv(c), uv(d)}});
        }
    return out;
}

std::vector<Corners> disk() {
    // The unit disk in the plane z = 0, facing +z, as a fan about its centre.
    // Mitsuba's texture coordinates are polar, (r, phi / 2 pi): linear along
    // each fan triangle's radii, nearly so across its 1/256 of a turn.
    std::vector<Corners> out;
    for (int i = 0; i < kDiskSegments; ++i) {
        const double a0 = 2.0 * M_PI * i / kDiskSegments;
        const double a1 = 2.0 * M_PI * (i + 1) / kDiskSegments;
        const double v0 = static_cast<double>(i) / kDiskSegments;
        const double v1 = static_cast<double>(i + 1) / kDiskSegments;
        out.push_back(
            {{glm::dvec3(0.0), glm::dvec3(std::cos(a0), std::sin(a0), 0.0),
              glm::dvec3(std::cos(a1), std::sin(a1), 0.0)},
             {glm::dvec2(0.0, 0.5 * (v0 + v1)), glm::dvec2(1.0, v0), glm::dvec2(1.0, v1)}});
    }
    return out;
}

void refuse_other_children(const Object& shape) {
    for (const auto& child : shape.children)
        if (child->tag != "bsdf" && child->tag != "emitter")
            fail_at(child->where, child->element(),
                    "wavepath does not support a <" + child->tag + "> inside " + shape.element() +
                        " (it reads one bsdf and one area emitter)");
}

void check_coordinates(Parameters& p, const glm::dvec3& v) {
    for (int i = 0; i < 3; ++i)
        if (!(std::abs(v[i]) <= scene_limits::max_coordinate))
            p.fail("to_world", "places a point at " + json::number_text(v[i]) +
                                   ", beyond wavepath's limit of 1e30");
}

// Rectangle, cube, disk. Under a mirroring to_world Mitsuba 3.9.1 keeps
// the disk's front (it transforms the disk's normal as a normal), so
// wavepath reverses the winding to match, and turns the rectangle's and the
// cube's round, as a mesh's (measured: a ray at each shape mirrored by
// <scale x="-1"/> sees the normal -z on a rectangle, a cube face and a PLY
// triangle, +z on a disk; docs/mitsuba-import.md).
void add_triangles(Parameters& p, const std::vector<Corners>& local, bool keep_front,
                   std::uint32_t material, Scene& scene) {
    const wp::Transform to_world = p.transform("to_world").value_or(wp::Transform());
    const bool flip = p.boolean("flip_normals").value_or(false);
    const bool reverse = flip != (keep_front && to_world.flips_orientation());
    for (const Corners& t : local) {
        Triangle out{};
        for (std::size_t k = 0; k < 3; ++k) {
            out.v[k] = to_world.apply_to_point(t.p[k]);
            check_coordinates(p, out.v[k]);
        }
        out.has_uvs = true;
        out.uvs = t.uv;
        if (reverse) {
            std::swap(out.v[1], out.v[2]);
            std::swap(out.uvs[1], out.uvs[2]);
        }
        out.material = material;
        if (is_zero_area(out.v[0], out.v[1], out.v[2]))
            p.fail("to_world", "flattens the shape to zero area");
        scene.triangles.push_back(out);
    }
}

// obj, ply and serialized through wavepath's mesh readers. Mitsuba shades a mesh by the
// file's vertex normals, or by smooth ones it computes when the file has
// none, unless face_normals is set; a mesh's front is the winding of its
// transformed positions, so a mirroring to_world turns it around (where
// wavepath's own mesh shapes keep it: load_mesh reverses, this undoes it).
void add_mesh_file(Parameters& p, const Object& shape, std::uint32_t material, Scene& scene) {
    const std::optional<std::string> filename = p.string("filename");
    if (!filename || filename->empty())
        p.fail("a " + shape.type + " shape needs a filename");
    MeshLoadOptions options;
    options.transform = p.transform("to_world").value_or(wp::Transform());
    const bool face_normals = p.boolean("face_normals").value_or(false);
    const bool flip = p.boolean("flip_normals").value_or(false);
    options.normals = face_normals ? NormalSource::None : NormalSource::File;
    options.texture_coordinates = scene.materials[material].is_textured();
    // The OBJ reader flips v as Mitsuba does by default (mesh.hpp); a file
    // that asks not to keeps the file's v.
    const bool flip_tex_coords = p.boolean("flip_tex_coords").value_or(true);
    if (shape.type == "serialized") {
        // Mitsuba refuses a negative index; wavepath's reader also checks
        // the upper end against the file's dictionary.
        const long long index = p.integer("shape_index").value_or(0);
        if (index < 0 || index > std::numeric_limits<std::uint32_t>::max())
            p.fail("shape_index",
                   "must be a mesh's index in the file (0 or more), got " + std::to_string(index));
        options.shape_index = static_cast<std::uint32_t>(index);
    }

    const std::filesystem::path path = shape.resolve(*filename);
    scene.files.push_back(path.string());
    TriangleMesh mesh;
    try {
        mesh = load_mesh(path, options);
    } catch (const MeshError& e) {
        p.fail("filename", e.what());
    }
    if (!face_normals && !mesh.has_normals())
        mesh.normals = smooth_vertex_normals(mesh.positions, mesh.triangles);
    const bool reverse = flip != options.transform.flips_orientation();
    for (const std::string& w : mesh.warnings)
        scene.warnings.push_back(shape.where.text() + ": " + w);
    // The mesh is kept indexed (scene/triangle_list.hpp); its triangles are
    // what they were when they were stored whole: the flips apply to each
    // vertex's texture coordinates and normal, the reversal to each triple.
    if (shape.type == "obj" && !flip_tex_coords)
        for (glm::dvec2& uv : mesh.uvs)
            uv.y = 1.0 - uv.y;
    if (reverse)
        for (auto& corners : mesh.triangles)
            std::swap(corners[1], corners[2]);
    if (flip)
        for (glm::dvec3& n : mesh.normals)
            n = -n;
    IndexedTriangles indexed;
    indexed.positions = std::move(mesh.positions);
    indexed.normals = std::move(mesh.normals);
    indexed.uvs = std::move(mesh.uvs);
    indexed.corners = std::move(mesh.triangles);
    indexed.material = material;
    scene.triangles.append(std::move(indexed));
}

// Mitsuba's sphere is its center and radius, then to_world: a uniform scale,
// a rotation and a translation (a non-uniform scale would make an ellipsoid,
// which wavepath has not).
void add_sphere(Parameters& p, std::uint32_t material, Scene& scene) {
    Sphere s;
    s.center = p.point("center").value_or(glm::dvec3(0.0));
    s.radius = p.number("radius").value_or(1.0);
    if (!(s.radius > 0.0) || s.radius > scene_limits::max_coordinate)
        p.fail("radius", "must be in (0, 1e30], got " + json::number_text(s.radius));
    if (const std::optional<wp::Transform> to_world = p.transform("to_world")) {
        const glm::dvec3 x = to_world->apply_to_vector({1, 0, 0});
        const glm::dvec3 y = to_world->apply_to_vector({0, 1, 0});
        const glm::dvec3 z = to_world->apply_to_vector({0, 0, 1});
        const double scale = glm::length(x);
        const double tolerance = 1e-9 * scale * scale;
        if (std::abs(glm::dot(y, y) - scale * scale) > tolerance ||
            std::abs(glm::dot(z, z) - scale * scale) > tolerance ||
            std::abs(glm::dot(x, y)) > tolerance || std::abs(glm::dot(x, z)) > tolerance ||
            std::abs(glm::dot(y, z)) > tolerance)
            p.fail("to_world", "a sphere's to_world must scale uniformly (a non-uniform scale or "
                               "a shear makes an ellipsoid, which wavepath has not)");
        // wavepath's sphere has no orientation: its texture coordinates are
        // about the world's axes, so a textured one may not turn.
        const double turned = 1e-9 * scale;
        if (scene.materials[material].is_textured() &&
            (std::abs(x.y) > turned || std::abs(x.z) > turned || std::abs(y.x) > turned ||
             std::abs(y.z) > turned || x.x < 0.0 || y.y < 0.0 || z.z < 0.0))
            p.fail("to_world", "a textured sphere's to_world may scale and translate but not "
                               "rotate or mirror (wavepath's sphere keeps the world's axes for "
                               "its texture coordinates)");
        s.center = to_world->apply_to_point(s.center);
        s.radius *= scale;
    }
    check_coordinates(p, s.center);
    if (!(s.radius <= scene_limits::max_coordinate))
        p.fail("radius", "is beyond wavepath's limit of 1e30 once placed");
    // wavepath's sphere faces outwards; only a dielectric tells the sides
    // apart (its outside is the exterior), and spheres do not emit.
    if (p.boolean("flip_normals").value_or(false)) {
        const MaterialKind kind = scene.materials[material].kind;
        if (kind == MaterialKind::Dielectric || kind == MaterialKind::ThinDielectric)
            p.fail("flip_normals", "a dielectric sphere turned inside out is not supported "
                                   "(swap int_ior and ext_ior instead)");
    }
    s.material = material;
    scene.spheres.push_back(s);
}

} // namespace

bool is_supported_shape(const std::string& type) {
    return type == "obj" || type == "ply" || type == "serialized" || type == "sphere" ||
           type == "rectangle" || type == "cube" || type == "disk";
}

void add_shape(const Object& shape, std::uint32_t material, Scene& scene) {
    Parameters p(shape);
    refuse_other_children(shape);
    const std::string& type = shape.type;
    if (type == "obj" || type == "ply" || type == "serialized") {
        add_mesh_file(p, shape, material, scene);
    } else if (type == "sphere") {
        add_sphere(p, material, scene);
    } else if (type == "rectangle" || type == "cube" || type == "disk") {
        p.ignore("face_normals"); // flat already
        add_triangles(p,
                      type == "rectangle" ? rectangle()
                      : type == "cube"    ? cube()
                                          : disk(),
                      type == "disk", material, scene);
    } else {
        p.fail("unsupported shape type '" + json::shorten(type, 40) +
               "' (wavepath reads obj, ply, serialized, rectangle, cube, sphere and disk)");
    }
    p.finish();
}

} // namespace wp::mitsuba
