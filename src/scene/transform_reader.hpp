// The `transform` list of a scene file's mesh shape (docs/scene-format.md),
// read into one wp::Transform. Each step is an object with exactly one key:
//   {"translate": [x, y, z]}
//   {"rotate": {"angle": degrees, "axis": [x, y, z]}}
//   {"scale": s} or {"scale": [sx, sy, sz]}
//   {"look_at": {"from": [x, y, z], "to": [x, y, z], "up": [x, y, z]}}
//   {"matrix": [[a, b, c, d], [e, f, g, h], [i, j, k, l], [0, 0, 0, 1]]}
// and the steps apply in list order (the first acts on the object first), as
// Transform::compose does. A step the JSON reader accepts but the Transform
// factory refuses (a zero axis, a zero scale) fails with the factory's message
// at the step's pointer: "scene.json: /shapes/3/transform/1: rotate: axis has
// zero length".
#pragma once

#include "scene/json_reader.hpp"
#include "scene/transform.hpp"

namespace wp {

// `steps` is the value of the `transform` key, `p` its pointer. Throws
// SceneError through `reader`.
Transform read_transform(const json::Reader& reader, const json::Json& steps,
                         const json::Pointer& p);

} // namespace wp
