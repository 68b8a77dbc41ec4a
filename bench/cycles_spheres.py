# Per-sphere mean ratios of two renders of one scene (shadelab / Cycles), for bench/cycles_compare.sh. Run in
# Blender's Python (it reads OpenEXR):
#   blender -b --factory-startup --python bench/cycles_spheres.py -- SCENE.json SHADELAB.exr CYCLES.exr
# A pixel counts for a sphere when the camera rays through its four corners all hit that sphere first (the
# scene's spheres and quads, the camera model of docs/scene-format.md): silhouettes, whose pixels mix shapes,
# are left out. Prints one JSON line "SPHERES_RESULT {...}": per sphere its material, pixel count and the
# ratio of the mean RGB sums, shadelab / Cycles.
import json
import math
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
scene_path, a_path, b_path = args[0], args[1], args[2]
with open(scene_path) as f:
    doc = json.load(f)
cam = doc["camera"]
w, h = cam["width"], cam["height"]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


eye = cam.get("position", [0, 1, 5])
forward = norm(sub(cam.get("look_at", [0, 1, 0]), eye))
right = norm(cross(forward, cam.get("up", [0, 1, 0])))
up = cross(right, forward)
tan_half = math.tan(math.radians(cam.get("fov", 40)) / 2)
shapes = doc.get("shapes", [])


def first_hit(px, py):
    # (px, py) in pixels from the top-left image corner; the pinhole ray through it.
    sx = (2 * px / w - 1) * tan_half * w / h
    sy = (1 - 2 * py / h) * tan_half
    d = norm([forward[i] + sx * right[i] + sy * up[i] for i in range(3)])
    best, best_t = None, float("inf")
    for k, s in enumerate(shapes):
        if s["type"] == "sphere":
            oc = sub(eye, s["center"])
            b = dot(oc, d)
            c = dot(oc, oc) - s["radius"] ** 2
            disc = b * b - c
            if disc < 0:
                continue
            t = -b - math.sqrt(disc)
            if t <= 1e-6:
                t = -b + math.sqrt(disc)
        elif s["type"] == "quad":
            n = cross(s["u"], s["v"])
            denom = dot(n, d)
            if abs(denom) < 1e-12:
                continue
            t = dot(sub(s["corner"], eye), n) / denom
            p = [eye[i] + t * d[i] - s["corner"][i] for i in range(3)]
            uu, vv = dot(p, s["u"]) / dot(s["u"], s["u"]), dot(p, s["v"]) / dot(s["v"], s["v"])
            if not (0 <= uu <= 1 and 0 <= vv <= 1):
                continue
        else:
            continue
        if 1e-6 < t < best_t:
            best, best_t = k, t
    return best


def pixels(path):
    img = bpy.data.images.load(path)
    img.colorspace_settings.name = "Non-Color"
    px = list(img.pixels)
    c = img.channels
    assert img.size[0] == w and img.size[1] == h, path
    return px, c


a, ca = pixels(a_path)
b, cb = pixels(b_path)
corners = [[first_hit(x, y) for x in range(w + 1)] for y in range(h + 1)]
sums = {}
for y in range(h):
    for x in range(w):
        k = corners[y][x]
        if k is None or shapes[k]["type"] != "sphere":
            continue
        if not (corners[y][x + 1] == k and corners[y + 1][x] == k and corners[y + 1][x + 1] == k):
            continue
        row = h - 1 - y  # Blender's pixels start at the bottom row
        ia, ib = (row * w + x) * ca, (row * w + x) * cb
        entry = sums.setdefault(k, [0, 0.0, 0.0])
        entry[0] += 1
        entry[1] += a[ia] + a[ia + 1] + a[ia + 2]
        entry[2] += b[ib] + b[ib + 1] + b[ib + 2]
result = []
for k in sorted(sums):
    n, sa, sb = sums[k]
    result.append({"shape": k, "material": shapes[k]["material"], "pixels": n, "ratio": sa / sb if sb > 0 else None})
print("SPHERES_RESULT %s" % json.dumps(result))
