"""Builds a Glint scene in Blender and renders it with Cycles, for the bench's
light-transport comparison (glint-bench --sections transport).

    blender -b --factory-startup --python glint_scene.py -- SCENE.json OUT.exr SAMPLES BOUNCES [SEED]

Takes what a path-transport scene of quads and triangles with diffuse and
emitting materials holds (scenes/cornell.json): the camera (eye, look_at,
up, fov_y), the image size, each material as a diffuse BSDF of albedo
color x diffuse plus an emission of radiance `emission`, a black world.
Glint's y-up scene is turned into Blender's z-up one by a rotation of 90
degrees about x (a proper rotation: the image is not mirrored). The film
is linear (view transform Standard, EXR), its pixel filter a box one pixel
wide, no sample clamping, Cycles' light tree off, as Glint samples.

An emitting quad is cut into an 8 x 8 grid of quads. Cycles samples a
light triangle by solid angle when the triangle is large beside its
distance to the shaded point, and that sampling is dark at grazing angles:
with the Cornell box's light as two triangles, Cycles 3.4's direct light on
the back wall 0.29 below the ceiling is 1.8 % under the closed form (and
3.7 % at 0.09 below), where Glint's is within 0.02 %. Cut into small
triangles, the light is sampled by area, as Glint samples it, and Cycles'
direct light there matches the closed form to 0.02 %; the integral is the
same, only Cycles' estimator changes.
"""
import json
import math
import sys
import time

import bpy
from mathutils import Vector


def turned(p):
    """Glint (x, y, z), y up, as Blender's (x, -z, y), z up."""
    return Vector((p[0], -p[2], p[1]))


def material(name, m):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    albedo = [c * m.get("diffuse", 1.0) for c in m.get("color", [1, 1, 1])]
    diffuse.inputs["Color"].default_value = (*albedo, 1.0)
    emission = m.get("emission")
    if emission:
        light = nodes.new("ShaderNodeEmission")
        light.inputs["Color"].default_value = (*emission, 1.0)
        light.inputs["Strength"].default_value = 1.0
        add = nodes.new("ShaderNodeAddShader")
        mat.node_tree.links.new(diffuse.outputs[0], add.inputs[0])
        mat.node_tree.links.new(light.outputs[0], add.inputs[1])
        mat.node_tree.links.new(add.outputs[0], out.inputs["Surface"])
    else:
        mat.node_tree.links.new(diffuse.outputs[0], out.inputs["Surface"])
    return mat


EMITTER_CUTS = 8


def grid(corners, n):
    """The quad's n x n cells, each as four corners in the quad's order."""
    c = [Vector(p) for p in corners]

    def at(a, b):
        return list((c[0] * (1 - a) + c[1] * a) * (1 - b) + (c[3] * (1 - a) + c[2] * a) * b)

    return [[at(i / n, j / n), at((i + 1) / n, j / n), at((i + 1) / n, (j + 1) / n), at(i / n, (j + 1) / n)]
            for i in range(n) for j in range(n)]


def build(scene_file):
    with open(scene_file) as f:
        scene = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    mats = {name: material(name, m) for name, m in scene["materials"].items()}
    verts, faces, face_mats = [], [], []
    names = list(mats)
    for o in scene["objects"]:
        corners = o["corners"] if o["type"] == "quad" else o["vertices"]
        emits = "emission" in scene["materials"][o["material"]]
        for polygon in grid(corners, EMITTER_CUTS) if emits and o["type"] == "quad" else [corners]:
            first = len(verts)
            verts += [turned(p) for p in polygon]
            faces.append(tuple(range(first, first + len(polygon))))
            face_mats.append(names.index(o["material"]))
    mesh = bpy.data.meshes.new("scene")
    mesh.from_pydata(verts, [], faces)
    for m in names:
        mesh.materials.append(mats[m])
    for poly, index in zip(mesh.polygons, face_mats):
        poly.material_index = index
    obj = bpy.data.objects.new("scene", mesh)
    bpy.context.scene.collection.objects.link(obj)

    cam = scene["camera"]
    camera = bpy.data.cameras.new("camera")
    camera.sensor_fit = "VERTICAL"
    camera.angle = math.radians(cam.get("fov_y", 60))
    cam_obj = bpy.data.objects.new("camera", camera)
    eye, target = turned(cam["eye"]), turned(cam["look_at"])
    cam_obj.location = eye
    # Looking along its -Z with its Y toward Blender's +z: Glint's up, +y
    # (the scenes this script takes keep the default up).
    cam_obj.rotation_euler = (target - eye).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.collection.objects.link(cam_obj)
    bpy.context.scene.camera = cam_obj

    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    bpy.context.scene.world = world
    return scene


def settings(scene, samples, bounces, seed):
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    s.cycles.device = "CPU"
    s.cycles.samples = samples
    s.cycles.seed = seed
    s.cycles.use_adaptive_sampling = False
    s.cycles.use_denoising = False
    s.cycles.max_bounces = bounces
    s.cycles.diffuse_bounces = bounces
    s.cycles.glossy_bounces = bounces
    s.cycles.transmission_bounces = bounces
    s.cycles.sample_clamp_direct = 0.0
    s.cycles.sample_clamp_indirect = 0.0
    s.cycles.filter_width = 1.0  # Cycles' box filter is one pixel wide whatever this says
    s.cycles.pixel_filter_type = "BOX"
    if hasattr(s.cycles, "use_light_tree"):
        s.cycles.use_light_tree = False
    s.render.resolution_x = scene["image"]["width"]
    s.render.resolution_y = scene["image"]["height"]
    s.render.resolution_percentage = 100
    s.view_settings.view_transform = "Standard"
    s.render.image_settings.file_format = "OPEN_EXR"
    s.render.image_settings.color_depth = "32"


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    scene_file, out, samples, bounces = args[0], args[1], int(args[2]), int(args[3])
    seed = int(args[4]) if len(args) > 4 else 0
    scene = build(scene_file)
    settings(scene, samples, bounces, seed)
    bpy.context.scene.render.filepath = out
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print("cycles: %d samples, %d bounces, %.1f s" % (samples, bounces, time.time() - start))


main()
