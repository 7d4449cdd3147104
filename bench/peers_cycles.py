"""Renders a wavepath scene (the hexroom, scenes/hexroom.json) with Blender
Cycles for bench/peers.py; run inside Blender:

    blender -b --factory-startup --python bench/peers_cycles.py -- \
        --scene scenes/hexroom.json --width 256 --height 256 --spp 64 --seed 1 \
        --threads 2 --out cycles.exr

The scene is built from the JSON itself, so it is the same geometry wavepath
traces: every quad and mesh triangle as a flat triangle (a quad split as
wavepath splits it, (v0 v1 v2) and (v0 v2 v3)), spheres as true spheres (a
point-cloud point of that radius made by geometry nodes, which Cycles
intersects analytically, not a tessellation), the camera as a pinhole with
the same eye, direction, up and horizontal field of view.

Materials, chosen so that Cycles computes what wavepath computes
(../shared/specs/hexroom.md):
- diffuse: Diffuse BSDF (Lambert, roughness 0) of the reflectance; Cycles'
  BSDFs reflect on both sides, as wavepath's do.
- mirror: Glossy BSDF, distribution Sharp, colour the reflectance: a
  perfect mirror with no Fresnel term.
- emitter: Emission of the radiance on the front face only (wavepath's
  lights emit on the side of cross(v1 - v0, v2 - v0); Cycles' emission is
  two-sided, so a Backfacing mix turns the back black), reflecting nothing.
  Emission Strength 1 with colour c reads c for a camera looking straight at
  it, so the colour is the radiance and Strength is 1; bench/peers.py checks
  by a calibration render that pixels seeing the light read exactly that.

Render settings that would make Cycles compute something else are off: box
pixel filter 1 px wide, no denoising, no clamping (direct and indirect 0), no
adaptive sampling, no light threshold (light_sampling_threshold 0, which
would drop dim light samples), no glossy filter (blur_glossy 0, which blurs
sharp reflections), both caustics on, bounce limits at wavepath's cap of 1024
(Russian roulette ends paths long before; min_light_bounces 0), no world
light (the room is closed), no motion blur. Blender 3.4 has no light tree.

Prints one line `peers_cycles {json}`: render_seconds (bpy.ops.render.render
alone: scene sync, BVH build and sampling; not Blender's start-up or the
EXR write), the sample pattern and Blender's version. Writes the image as a
32-bit float RGB EXR, linear, no view transform.
"""
import argparse
import json
import math
import sys
import time

import bpy


def parse_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser(prog="peers_cycles.py")
    parser.add_argument("--scene", required=True)
    parser.add_argument("--width", type=int, required=True)
    parser.add_argument("--height", type=int, required=True)
    parser.add_argument("--spp", type=int, required=True)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=0, help="0: all cores")
    parser.add_argument("--out", required=True)
    return parser.parse_args(argv)


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for collection in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for item in list(collection):
            collection.remove(item)


def make_material(name, spec):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    links = material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    kind = spec["type"]
    if kind == "diffuse":
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = (*spec["reflectance"], 1.0)
        bsdf.inputs["Roughness"].default_value = 0.0
        links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    elif kind == "mirror":
        bsdf = nodes.new("ShaderNodeBsdfGlossy")
        bsdf.distribution = "SHARP"
        bsdf.inputs["Color"].default_value = (*spec["reflectance"], 1.0)
        bsdf.inputs["Roughness"].default_value = 0.0
        links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    elif kind == "emitter":
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = (*spec["radiance"], 1.0)
        emission.inputs["Strength"].default_value = 1.0
        black = nodes.new("ShaderNodeEmission")  # the back face: emits and reflects nothing
        black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        black.inputs["Strength"].default_value = 0.0
        geometry = nodes.new("ShaderNodeNewGeometry")
        mix = nodes.new("ShaderNodeMixShader")
        links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        links.new(emission.outputs["Emission"], mix.inputs[1])
        links.new(black.outputs["Emission"], mix.inputs[2])
        links.new(mix.outputs["Shader"], output.inputs["Surface"])
        material.cycles.sample_as_light = True
    else:
        raise SystemExit(f"peers_cycles: error: material '{name}' has type '{kind}', "
                         "which this script does not map")
    if spec.get("emission"):
        raise SystemExit(f"peers_cycles: error: material '{name}' has an emission, "
                         "which this script does not map")
    return material


def add_triangles(name, vertices, triangles, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in vertices], [], [tuple(t) for t in triangles])
    mesh.update()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)


def add_sphere(name, center, radius, material):
    """A true sphere: one vertex turned into a point of the radius by geometry nodes."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(center)], [], [])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new(name + " points", "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    group_in = tree.nodes.new("NodeGroupInput")
    group_out = tree.nodes.new("NodeGroupOutput")
    to_points = tree.nodes.new("GeometryNodeMeshToPoints")
    to_points.inputs["Radius"].default_value = radius
    set_material = tree.nodes.new("GeometryNodeSetMaterial")
    set_material.inputs["Material"].default_value = material
    tree.links.new(group_in.outputs["Geometry"], to_points.inputs["Mesh"])
    tree.links.new(to_points.outputs["Points"], set_material.inputs["Geometry"])
    tree.links.new(set_material.outputs["Geometry"], group_out.inputs["Geometry"])
    modifier = obj.modifiers.new("points", "NODES")
    modifier.node_group = tree


def add_camera(spec):
    eye = spec["eye"]
    look_at = spec["look_at"]
    forward = [look_at[i] - eye[i] for i in range(3)]
    camera = bpy.data.cameras.new("camera")
    camera.type = "PERSP"
    camera.sensor_fit = "HORIZONTAL"
    camera.angle = math.radians(spec["fov"])  # square image: horizontal = vertical
    camera.clip_start = 1e-4
    camera.clip_end = 1e4
    obj = bpy.data.objects.new("camera", camera)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = eye
    # Blender's camera looks down its local -z with local +y up.
    from mathutils import Vector
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = Vector(forward).to_track_quat("-Z", "Y")
    bpy.context.scene.camera = obj
    return obj


def configure_render(args):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = args.spp
    cycles.seed = args.seed
    cycles.use_animated_seed = False
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.max_bounces = 1024
    cycles.diffuse_bounces = 1024
    cycles.glossy_bounces = 1024
    cycles.transmission_bounces = 1024
    cycles.transparent_max_bounces = 1024
    cycles.volume_bounces = 0
    cycles.min_light_bounces = 0
    cycles.min_transparent_bounces = 0
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.film_exposure = 1.0
    scene.render.use_motion_blur = False
    scene.render.film_transparent = False
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = 1.0
    scene.render.pixel_aspect_y = 1.0
    scene.render.use_persistent_data = False
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    else:
        scene.render.threads_mode = "AUTO"
    world = bpy.data.worlds.new("black") if scene.world is None else scene.world
    world.use_nodes = False
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"


def main():
    args = parse_arguments()
    with open(args.scene) as file:
        description = json.load(file)
    clear_scene()
    materials = {name: make_material(name, spec)
                 for name, spec in description["materials"].items()}
    for index, shape in enumerate(description["shapes"]):
        name = f"{index} {shape.get('name', shape['type'])}"[:60]
        material = materials[shape["material"]]
        if shape["type"] == "quad":
            add_triangles(name, shape["vertices"], [[0, 1, 2], [0, 2, 3]], material)
        elif shape["type"] == "triangle":
            add_triangles(name, shape["vertices"], [[0, 1, 2]], material)
        elif shape["type"] == "mesh" and "triangles" in shape:
            add_triangles(name, shape["vertices"], shape["triangles"], material)
        elif shape["type"] == "sphere":
            add_sphere(name, shape["center"], shape["radius"], material)
        else:
            raise SystemExit(f"peers_cycles: error: shape {index} has type '{shape['type']}', "
                             "which this script does not map")
    add_camera(description["camera"])
    configure_render(args)
    start = time.monotonic()
    bpy.ops.render.render(write_still=False)
    seconds = time.monotonic() - start
    bpy.data.images["Render Result"].save_render(args.out)
    print("peers_cycles " + json.dumps({
        "render_seconds": seconds,
        "sample_pattern": bpy.context.scene.cycles.sampling_pattern,
        "blender": bpy.app.version_string,
        "threads": bpy.context.scene.render.threads,
    }), flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as error:
        print(error, file=sys.stderr)
        sys.exit(1)
