# Builds a shadelab scene (Lambert and GGX spheres and quads, emissive spheres and quads, a uniform environment) in
# Blender and renders it with Cycles, for bench/cycles_compare.sh. Run as:
#   blender -b --factory-startup --python bench/cycles_compare.py -- SCENE.json SPP OUT.exr THREADS [SEED]
# Settings chosen to match shadelab exactly: the same number of scattering events (shadelab's max_depth counts
# path vertices, 1 = direct light only; Cycles' max_bounces counts bounces after the first hit, 0 = direct
# light only, so max_bounces = max_depth - 1), the same pixel filter (shadelab averages over the pixel square:
# Cycles' box filter of width 1 pixel), no denoising, no adaptive sampling, no clamping, no glossy blur and no
# light threshold (all of which bias Cycles' estimate). Cycles' sampling pattern stays its default
# (progressive multi-jitter in Blender 3.4), the one its users get.
# shadelab is Y-up, Blender Z-up: (x, y, z) -> (x, -z, y). Cycles' Diffuse BSDF is Lambert kd/pi, an Emission
# shader of strength 1 emits radiance equal to its colour, and the world Background is radiance: the scene's
# radiometric values carry over unchanged.
import json
import math
import sys
import time

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
scene_path, spp, out_path, threads = args[0], int(args[1]), args[2], int(args[3])
seed = int(args[4]) if len(args) > 4 else 0
with open(scene_path) as f:
    doc = json.load(f)
if doc.get("units", "game") != "radiometric":
    sys.exit("cycles_compare: the scene must use radiometric units")


def to_blender(v):
    return (v[0], -v[2], v[1])


def colour(v):
    return (v, v, v) if isinstance(v, (int, float)) else tuple(v)


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_denoising = False
scene.cycles.use_adaptive_sampling = False
scene.cycles.seed = seed
depth = doc.get("render", {}).get("max_depth", 8)
bounces = depth - 1  # see the top of this file
scene.cycles.max_bounces = bounces
scene.cycles.diffuse_bounces = bounces
scene.cycles.glossy_bounces = bounces
scene.cycles.transmission_bounces = bounces
scene.cycles.sample_clamp_direct = 0.0
scene.cycles.sample_clamp_indirect = 0.0
scene.cycles.blur_glossy = 0.0
scene.cycles.light_sampling_threshold = 0.0
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0  # pixels: the box over the pixel square that shadelab averages
scene.render.threads_mode = "FIXED"
scene.render.threads = threads
cam = doc["camera"]
scene.render.resolution_x = cam["width"]
scene.render.resolution_y = cam["height"]
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.filepath = out_path
scene.view_settings.view_transform = "Standard"

materials = {}
for name, m in doc.get("materials", {}).items():
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    if "emission" in m:
        node = nodes.new("ShaderNodeEmission")
        node.inputs["Color"].default_value = (*colour(m["emission"]), 1.0)
        node.inputs["Strength"].default_value = 1.0
        mat.node_tree.links.new(node.outputs["Emission"], out.inputs["Surface"])
    else:
        params = m.get("params", {})
        if m.get("model") == "lambert":
            node = nodes.new("ShaderNodeBsdfDiffuse")
            node.inputs["Color"].default_value = (*colour(params.get("kd", 0.5)), 1.0)
            node.inputs["Roughness"].default_value = 0.0
            mat.node_tree.links.new(node.outputs["BSDF"], out.inputs["Surface"])
        elif m.get("model") == "ggx":
            # ggx with f = none, g = smith-separable, ms = none, isotropic: kd/pi + ks D G1 G1 / (4 N.L N.V) is
            # Cycles 3.4's Diffuse BSDF (kd) added to its Glossy BSDF, distribution GGX (colour ks, no Fresnel,
            # separable Smith G1(i) G1(o), alpha = Roughness^2, the same perceptual roughness as ggx's).
            want = {"f": "none", "g": "smith-separable", "ms": "none"}
            for key, value in want.items():
                if params.get(key) != value:
                    sys.exit("cycles_compare: material %s: ggx needs %s = %s for Cycles' Glossy GGX" % (name, key, value))
            if any(k in params for k in ("alpha_x", "alpha_y")):
                sys.exit("cycles_compare: material %s: anisotropic ggx is not compared" % name)
            roughness = params["roughness"] if "roughness" in params else math.sqrt(params.get("alpha", 0.25))
            glossy = nodes.new("ShaderNodeBsdfGlossy")
            glossy.distribution = "GGX"
            glossy.inputs["Color"].default_value = (*colour(params.get("ks", 1.0)), 1.0)
            glossy.inputs["Roughness"].default_value = roughness
            kd = colour(params.get("kd", 0.2))
            if max(kd) > 0.0:
                diffuse = nodes.new("ShaderNodeBsdfDiffuse")
                diffuse.inputs["Color"].default_value = (*kd, 1.0)
                diffuse.inputs["Roughness"].default_value = 0.0
                add = nodes.new("ShaderNodeAddShader")
                mat.node_tree.links.new(diffuse.outputs["BSDF"], add.inputs[0])
                mat.node_tree.links.new(glossy.outputs["BSDF"], add.inputs[1])
                mat.node_tree.links.new(add.outputs["Shader"], out.inputs["Surface"])
            else:
                mat.node_tree.links.new(glossy.outputs["BSDF"], out.inputs["Surface"])
        else:
            sys.exit("cycles_compare: material %s: only lambert, ggx and emission have an exact Cycles equivalent" % name)
    materials[name] = mat

for shape in doc.get("shapes", []):
    if shape["type"] == "sphere":
        bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=shape["radius"],
                                             location=to_blender(shape["center"]))
        bpy.ops.object.shade_smooth()
    elif shape["type"] == "quad":
        c, u, v = shape["corner"], shape["u"], shape["v"]
        pts = [c, [c[i] + u[i] for i in range(3)], [c[i] + u[i] + v[i] for i in range(3)], [c[i] + v[i] for i in range(3)]]
        mesh = bpy.data.meshes.new("quad")
        mesh.from_pydata([to_blender(p) for p in pts], [], [(0, 1, 2, 3)])
        obj = bpy.data.objects.new("quad", mesh)
        scene.collection.objects.link(obj)
        bpy.context.view_layer.objects.active = obj
    else:
        sys.exit("cycles_compare: shape type %s is not supported" % shape["type"])
    bpy.context.view_layer.objects.active.data.materials.append(materials[shape["material"]])

world = bpy.data.worlds.new("world")
world.use_nodes = True
bg = world.node_tree.nodes["Background"]
env = doc.get("environment", {})
bg.inputs["Color"].default_value = (*colour(env.get("uniform", 0.0)), 1.0)
bg.inputs["Strength"].default_value = 1.0
scene.world = world

cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(cam["fov"])
cam_obj = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(cam_obj)
cam_obj.location = to_blender(cam["position"])
target = bpy.data.objects.new("target", None)
scene.collection.objects.link(target)
target.location = to_blender(cam["look_at"])
track = cam_obj.constraints.new("TRACK_TO")
track.target = target
track.track_axis = "TRACK_NEGATIVE_Z"
track.up_axis = "UP_Y"
scene.camera = cam_obj

start = time.time()
bpy.ops.render.render(write_still=True)
seconds = time.time() - start
# seconds: scene synchronisation (BVH build, light distributions) + rendering + writing the file. The render
# time without synchronisation is read by the caller from Cycles' progress lines ("Sample 0/N" to "Finished").
print("CYCLES_RESULT %s" % json.dumps({"seconds": seconds, "samples": cam["width"] * cam["height"] * spp,
                                       "sampling_pattern": scene.cycles.sampling_pattern, "max_bounces": bounces,
                                       "samples_per_second": cam["width"] * cam["height"] * spp / seconds}))
