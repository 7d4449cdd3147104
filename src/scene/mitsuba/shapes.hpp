// Mitsuba 3's shape plugins as wavepath geometry: meshes from `obj`, `ply`
// and `serialized` files (through wavepath's own mesh readers, scene/mesh.hpp),
// `rectangle`, `cube` and `disk` as triangles, `sphere` as a sphere, each
// placed by its to_world, with flip_normals and face_normals.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/mitsuba/xml_reader.hpp"
#include "scene/scene.hpp"

namespace wp::mitsuba {

// The segments of a disk's triangle fan: its area is 256 sin(2 pi / 256) /
// (2 pi) = 0.9999 of the round disk's.
inline constexpr int kDiskSegments = 256;

// Whether add_shape reads shapes of this plugin (--lenient leaves the
// others out).
bool is_supported_shape(const std::string& type);

// Appends the shape's triangles or sphere to `scene` with `material`. The
// shape's <bsdf> and <emitter> children are the caller's; any other child is
// refused. Mesh files are recorded in Scene::files. Throws SceneError.
void add_shape(const Object& shape, std::uint32_t material, Scene& scene);

} // namespace wp::mitsuba
