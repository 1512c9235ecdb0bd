#!/usr/bin/env python3
"""Writes the many-light scenes of sst's light-sampler experiments (configs/lights-*.json).

  cornell-lamp/cornell-lamp.gltf  The Cornell box (scenes/cornell-box.gltf) with its lamp cut into
                                  a 78 x 78 grid of quads: 12,168 emissive triangles (the RTSLC
                                  paper's Cornell box has 12,146) in 16 materials of different
                                  radiance and colour, scaled so that the lamp's total power is
                                  the original lamp's.
  night-street/night-street.gltf  A street at night, 200 m long over a 240 m ground: 24 buildings,
                                  312 lit windows (two triangles each, one-sided), 20
                                  strings of 40 coloured bulbs (octahedra, eight triangles each),
                                  neon signs (boxes), 20 point-light street lamps and 10 spot lights
                                  over doors: 7,120 emissive triangles and 30 punctual lights.
  light-field/light-field.gltf    A 40 m field with 30 box occluders, 2,000 small double-sided
                                  emissive quads at random places and orientations whose radiance
                                  spans two orders of magnitude, 40 point and 10 spot lights:
                                  where a light tree's build decides its variance.
  light-field-open/...            The same field without the occluders.

A scene's emitters-only mask (`sst-render NAME --emitters-only`) marks the pixels a directly seen
emitter touches, which the light-sampler comparisons leave out (sst-eval compare --mask,
tests/benchmarks/light_tree_compare.sh, a sweep's reference "mask").

Everything is generated from a fixed seed (no third-party data); metres, +Y up, diffuse
materials, KHR_materials_emissive_strength radiance, radiometric KHR_lights_punctual intensities
(the conventions of ../shared/scenes). Large outputs stay out of the repository: write them to a
folder on the scene path, e.g.

    python3 scenes/tools/make_many_lights.py ../shared/scenes
    SST_SCENE_PATH=../shared/scenes sst-render night-street --light-sampler tree

Cycles references (Blender 3.4 from Debian, with python3-numpy; kept beside the scene, not in the
repository), as results/README.md's comparison used them:

    cd ../shared/scenes/night-street && blender -b --factory-startup -noaudio \
      --python ../../tools/render_gltf.py -- --scene night-street.gltf --out ref/cycles-2048spp \
      --res 192 --resy 108 --spp 2048 --bounces 8 --diffuse-only --threads 2
    (cornell-lamp: --res 192 --spp 1024; fairground: --res 192 --resy 108 --spp 1024)
"""
import argparse
import base64
import json
import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


class Builder:
    """Triangles grouped by material, flat-shaded, written as one mesh with one primitive per material."""

    def __init__(self):
        self.materials = []
        self.tris = {}  # material index -> list of (v0, v1, v2)
        self.lights = []
        self.light_nodes = []

    def material(self, name, base=(0.5, 0.5, 0.5), emission=None, strength=1.0, double_sided=True):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(base) + [1.0], "metallicFactor": 0.0,
                                                    "roughnessFactor": 1.0}, "doubleSided": double_sided}
        if emission is not None:
            m["emissiveFactor"] = list(emission)
            if strength != 1.0:
                m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        self.materials.append(m)
        return len(self.materials) - 1

    def tri(self, mat, a, b, c):
        self.tris.setdefault(mat, []).append((a, b, c))

    def quad(self, mat, a, b, c, d):
        """Counter-clockwise a, b, c, d seen from the front (normal (b - a) x (c - a))."""
        self.tri(mat, a, b, c)
        self.tri(mat, a, c, d)

    def box(self, mat, lo, hi):
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        p = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
        for f in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 4, 7, 3), (1, 2, 6, 5), (3, 7, 6, 2), (0, 1, 5, 4)):
            self.quad(mat, *[p[i] for i in f])

    def octahedron(self, mat, c, r):
        px, py, pz = c
        v = [(px + r, py, pz), (px - r, py, pz), (px, py + r, pz), (px, py - r, pz), (px, py, pz + r), (px, py, pz - r)]
        for a, b, cc in ((0, 2, 4), (4, 2, 1), (1, 2, 5), (5, 2, 0), (0, 4, 3), (4, 1, 3), (1, 5, 3), (5, 0, 3)):
            self.tri(mat, v[a], v[b], v[cc])

    def point_light(self, name, pos, color, intensity):
        self.lights.append({"name": name, "type": "point", "color": list(color), "intensity": intensity})
        self.light_nodes.append({"name": name, "translation": list(pos), "extensions": {"KHR_lights_punctual": {"light": len(self.lights) - 1}}})

    def spot_light(self, name, pos, rotation, color, intensity, inner, outer):
        self.lights.append({"name": name, "type": "spot", "color": list(color), "intensity": intensity,
                            "spot": {"innerConeAngle": inner, "outerConeAngle": outer}})
        self.light_nodes.append({"name": name, "translation": list(pos), "rotation": list(rotation),
                                 "extensions": {"KHR_lights_punctual": {"light": len(self.lights) - 1}}})

    def write(self, path, camera, extra_nodes=()):
        blob = bytearray()
        views, accessors, prims = [], [], []

        def add_view(data, target):
            while len(blob) % 4:
                blob.append(0)
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob.extend(data)
            return len(views) - 1

        for mat in sorted(self.tris):
            pos, nrm = [], []
            for a, b, c in self.tris[mat]:
                e1 = [b[i] - a[i] for i in range(3)]
                e2 = [c[i] - a[i] for i in range(3)]
                n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
                ln = math.sqrt(sum(x * x for x in n)) or 1.0
                n = [x / ln for x in n]
                for v in (a, b, c):
                    pos.append(v)
                    nrm.append(n)
            count = len(pos)
            lo = [min(p[i] for p in pos) for i in range(3)]
            hi = [max(p[i] for p in pos) for i in range(3)]
            pv = add_view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
            nv = add_view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
            iv = add_view(struct.pack("<%dI" % count, *range(count)), 34963)
            accessors += [{"bufferView": pv, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi},
                          {"bufferView": nv, "componentType": 5126, "count": count, "type": "VEC3"},
                          {"bufferView": iv, "componentType": 5125, "count": count, "type": "SCALAR"}]
            k = len(accessors)
            prims.append({"attributes": {"POSITION": k - 3, "NORMAL": k - 2}, "indices": k - 1, "mode": 4, "material": mat})
        nodes = [{"name": "geometry", "mesh": 0}, camera] + list(self.light_nodes) + list(extra_nodes)
        gltf = {"asset": {"version": "2.0", "generator": "sst scenes/tools/make_many_lights.py"},
                "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
                "meshes": [{"name": "geometry", "primitives": prims}], "materials": self.materials,
                "cameras": [{"name": camera["name"], "type": "perspective", "perspective": camera.pop("_perspective")}],
                "accessors": accessors, "bufferViews": views,
                "buffers": [{"uri": os.path.basename(path)[:-5] + ".bin", "byteLength": len(blob)}],
                "extensionsUsed": ["KHR_materials_emissive_strength"]}
        if self.lights:
            gltf["extensionsUsed"].append("KHR_lights_punctual")
            gltf["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path[:-5] + ".bin", "wb") as f:
            f.write(blob)
        with open(path, "w") as f:
            json.dump(gltf, f, indent=1)
        emissive = sum(len(t) for m, t in self.tris.items() if "emissiveFactor" in self.materials[m])
        total = sum(len(t) for t in self.tris.values())
        print("%s: %d triangles, %d emissive, %d punctual lights, %.1f MB" %
              (path, total, emissive, len(self.lights), (len(blob) + os.path.getsize(path)) / 1e6))


def read_gltf_triangles(path):
    """(material index, [(v0, v1, v2)]) per primitive of a glTF with an embedded or external buffer
    (node transforms: translation only, which is all scenes/cornell-box.gltf uses)."""
    g = json.load(open(path))
    uri = g["buffers"][0]["uri"]
    data = base64.b64decode(uri.split(",", 1)[1]) if uri.startswith("data:") else open(os.path.join(os.path.dirname(path), uri), "rb").read()

    def read(acc_index, fmt, width):
        acc = g["accessors"][acc_index]
        view = g["bufferViews"][acc["bufferView"]]
        off = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        size = struct.calcsize("<" + fmt)
        stride = view.get("byteStride", size * width)
        return [struct.unpack_from("<" + fmt * width, data, off + i * stride) for i in range(acc["count"])]

    out = []
    for node in g["nodes"]:
        if "mesh" not in node:
            continue
        t = node.get("translation", [0, 0, 0])
        for prim in g["meshes"][node["mesh"]]["primitives"]:
            pos = [tuple(p[i] + t[i] for i in range(3)) for p in read(prim["attributes"]["POSITION"], "f", 3)]
            comp = g["accessors"][prim["indices"]]["componentType"]
            idx = [i[0] for i in read(prim["indices"], {5125: "I", 5123: "H", 5121: "B"}[comp], 1)]
            out.append((prim["material"], [(pos[idx[k]], pos[idx[k + 1]], pos[idx[k + 2]]) for k in range(0, len(idx), 3)]))
    return g, out


def cornell_lamp(out_dir):
    g, prims = read_gltf_triangles(os.path.join(HERE, "..", "cornell-box.gltf"))
    b = Builder()
    remap = {}
    lamp = None
    for mi, m in enumerate(g["materials"]):
        if "emissiveFactor" in m:
            lamp = m
            continue
        base = m["pbrMetallicRoughness"]["baseColorFactor"][:3]
        remap[mi] = b.material(m["name"], base)
    strength = lamp.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
    radiance = [c * strength for c in lamp["emissiveFactor"]]
    lamp_tris = []
    for mat, tris in prims:
        if mat in remap:
            for t in tris:
                b.tri(remap[mat], *t)
        else:
            lamp_tris += tris
    pts = [p for t in lamp_tris for p in t]
    x0, x1 = min(p[0] for p in pts), max(p[0] for p in pts)
    z0, z1 = min(p[2] for p in pts), max(p[2] for p in pts)
    y = pts[0][1]
    # The original lamp faces down (-Y): keep the winding of its first triangle.
    a, bb, c = lamp_tris[0]
    ny = (bb[2] - a[2]) * (c[0] - a[0]) - (bb[0] - a[0]) * (c[2] - a[2])
    # 16 radiance levels: a radial falloff times a 4-step checker of colours; normalised to the
    # original mean so the lamp's power is unchanged.
    rng = random.Random(12146)
    tints = [(1.0, 1.0, 1.0), (1.0, 0.55, 0.35), (0.45, 0.75, 1.0), (0.8, 1.0, 0.5)]
    levels = [0.25, 0.6, 1.2, 2.4]
    n = 78
    cells = []
    for i in range(n):
        for j in range(n):
            r = math.hypot((i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5) / 0.7072
            level = min(3, int((1.0 - r) * 4.0 + rng.random() * 0.8))
            cells.append((i, j, level, (i // 6 + j // 6) % 4))
    mean = sum(levels[c[2]] * sum(tints[c[3]]) / 3.0 for c in cells) / len(cells)
    mats = {}
    for lv in range(4):
        for tn in range(4):
            e = [radiance[k] * levels[lv] * tints[tn][k] / mean for k in range(3)]
            s = max(e)
            mats[(lv, tn)] = b.material("lamp_%d_%d" % (lv, tn), (0.0, 0.0, 0.0), [x / s for x in e], s, double_sided=True)
    for i, j, lv, tn in cells:
        xa, xb = x0 + (x1 - x0) * i / n, x0 + (x1 - x0) * (i + 1) / n
        za, zb = z0 + (z1 - z0) * j / n, z0 + (z1 - z0) * (j + 1) / n
        quad = [(xa, y, za), (xb, y, za), (xb, y, zb), (xa, y, zb)]
        if ny > 0:  # our winding faces -Y; the original's faces +Y
            quad.reverse()
        b.quad(mats[(lv, tn)], *quad)
    cam_node = next(nd for nd in g["nodes"] if "camera" in nd)
    camera = {"name": "main", "camera": 0, "translation": cam_node["translation"], "rotation": cam_node.get("rotation", [0, 0, 0, 1]),
              "_perspective": g["cameras"][0]["perspective"]}
    b.write(os.path.join(out_dir, "cornell-lamp", "cornell-lamp.gltf"), camera)


def night_street(out_dir):
    rng = random.Random(2026)
    b = Builder()
    ground = b.material("asphalt", (0.12, 0.12, 0.13))
    pavement = b.material("pavement", (0.35, 0.34, 0.32))
    facades = [b.material("facade_%d" % k, c) for k, c in enumerate(
        [(0.55, 0.50, 0.45), (0.40, 0.42, 0.45), (0.60, 0.45, 0.35), (0.30, 0.30, 0.32), (0.65, 0.62, 0.58)])]
    pole = b.material("pole", (0.2, 0.2, 0.2))
    windows = [b.material("window_%d" % k, (0.0, 0.0, 0.0), c, s, double_sided=False) for k, (c, s) in enumerate(
        [((1.0, 0.78, 0.5), 2.0), ((1.0, 0.9, 0.75), 3.0), ((0.75, 0.85, 1.0), 2.5), ((1.0, 0.6, 0.3), 1.5), ((0.9, 1.0, 0.9), 1.2)])]
    bulbs = [b.material("bulb_%d" % k, (0.0, 0.0, 0.0), c, 40.0, double_sided=False) for k, c in enumerate(
        [(1.0, 0.2, 0.1), (0.2, 1.0, 0.2), (0.2, 0.3, 1.0), (1.0, 0.85, 0.2), (1.0, 1.0, 1.0)])]
    neon = [b.material("neon_%d" % k, (0.0, 0.0, 0.0), c, 12.0, double_sided=False) for k, c in enumerate(
        [(1.0, 0.1, 0.6), (0.1, 0.9, 1.0), (0.6, 0.2, 1.0)])]

    L = 120.0
    b.quad(ground, (-L, 0.0, -L), (-L, 0.0, L), (L, 0.0, L), (L, 0.0, -L))
    for side in (-1, 1):  # pavements, 15 cm kerbs
        xa, xb = (6.0, 9.0) if side > 0 else (-9.0, -6.0)
        b.box(pavement, (xa, 0.0, -100.0), (xb, 0.15, 100.0))
    window_count = 0
    for side in (-1, 1):
        z = -100.0
        while z < 100.0:
            width = rng.uniform(8.0, 16.0)
            depth = rng.uniform(10.0, 16.0)
            height = rng.uniform(6.0, 30.0)
            x_front = 9.5 * side
            x_back = x_front + depth * side
            lo = (min(x_front, x_back), 0.0, z)
            hi = (max(x_front, x_back), height, min(z + width - 0.5, 100.0))
            b.box(facades[rng.randrange(len(facades))], lo, hi)
            # Windows on the street-facing facade, 2 cm proud of it, facing the street.
            xf = x_front - 0.02 * side
            floors = int((height - 1.0) // 3.0)
            cols = int((hi[2] - lo[2] - 1.0) // 2.2)
            for f in range(floors):
                for c in range(cols):
                    if rng.random() > 0.4:
                        continue
                    y0, y1 = 1.0 + f * 3.0, 1.0 + f * 3.0 + 1.5
                    za, zb = lo[2] + 0.8 + c * 2.2, lo[2] + 0.8 + c * 2.2 + 1.2
                    q = [(xf, y0, za), (xf, y0, zb), (xf, y1, zb), (xf, y1, za)]  # faces -X
                    if side < 0:
                        q.reverse()  # the left side's windows face +X
                    b.quad(windows[rng.randrange(len(windows))], *q)
                    window_count += 1
            # A neon sign on one building in three.
            if rng.random() < 0.35:
                ys = rng.uniform(3.5, min(height - 1.0, 9.0))
                zs = rng.uniform(lo[2] + 1.0, max(lo[2] + 1.5, hi[2] - 4.0))
                xs = x_front - 0.3 * side
                b.box(neon[rng.randrange(len(neon))], (min(xs, xs + 0.15 * side), ys, zs), (max(xs, xs + 0.15 * side), ys + 0.25, zs + 3.0))
            z += width
    # Strings of bulbs across the street between poles, every 10 m.
    for k in range(20):
        zc = -95.0 + k * 10.0
        for side in (-1, 1):
            b.box(pole, (7.5 * side - 0.1, 0.0, zc - 0.1), (7.5 * side + 0.1, 6.5, zc + 0.1))
        for i in range(40):
            t = (i + 0.5) / 40.0
            x = -7.5 + 15.0 * t
            y = 6.4 - 1.6 * (1.0 - (2.0 * t - 1.0) ** 2)  # sagging string
            b.octahedron(bulbs[(i + k) % len(bulbs)], (x, y, zc + 0.3 * math.sin(7.0 * t)), 0.07)
    # Street lamps (point lights) and spot lights over doors.
    for k in range(20):
        side = -1 if k % 2 else 1
        z = -95.0 + k * 10.0 + 5.0
        b.point_light("lamp_%d" % k, (6.6 * side, 7.0, z), (1.0, 0.85, 0.6), 60.0)
    down = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 degrees about X: -Z turns to -Y
    for k in range(10):
        side = 1 if k % 2 else -1
        z = -80.0 + k * 17.0
        b.spot_light("door_%d" % k, (9.3 * side, 3.2, z), down, (1.0, 0.95, 0.85), 150.0, 0.35, 0.6)
    pitch = math.radians(4.0)
    camera = {"name": "main", "camera": 0, "translation": [0.0, 1.7, 96.0],
              "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)],
              "_perspective": {"yfov": 0.75, "aspectRatio": 16.0 / 9.0, "znear": 0.05, "zfar": 1000.0}}
    b.write(os.path.join(out_dir, "night-street", "night-street.gltf"), camera)
    print("night-street: %d lit windows" % window_count)


def fairground(out_dir):
    """1,000 lamp posts scattered over a 300 m field with 60 stalls: each point of the ground is lit
    mostly by the few lamps near it, the case a light tree is made for."""
    rng = random.Random(1000)
    b = Builder()
    grass = b.material("ground", (0.25, 0.3, 0.2))
    wood = b.material("post", (0.35, 0.25, 0.15))
    canvas = [b.material("stall_%d" % k, c) for k, c in enumerate([(0.7, 0.2, 0.2), (0.2, 0.3, 0.7), (0.8, 0.8, 0.7)])]
    bulbs = [b.material("lamp_%d" % k, (0.0, 0.0, 0.0), c, s, double_sided=False) for k, (c, s) in enumerate(
        [((1.0, 0.8, 0.5), 240.0), ((1.0, 0.3, 0.2), 160.0), ((0.3, 1.0, 0.4), 160.0), ((0.4, 0.5, 1.0), 200.0), ((1.0, 1.0, 1.0), 120.0)])]
    L = 150.0
    b.quad(grass, (-L, 0.0, -L), (-L, 0.0, L), (L, 0.0, L), (L, 0.0, -L))
    for _ in range(60):
        x, z = rng.uniform(-140, 140), rng.uniform(-140, 140)
        w, d, h = rng.uniform(3, 6), rng.uniform(3, 6), rng.uniform(2.5, 4.0)
        b.box(canvas[rng.randrange(3)], (x, 0.0, z), (x + w, h, z + d))
    for _ in range(1000):
        x, z = rng.uniform(-145, 145), rng.uniform(-145, 145)
        h = rng.uniform(2.5, 4.5)
        b.box(wood, (x - 0.05, 0.0, z - 0.05), (x + 0.05, h, z + 0.05))
        b.octahedron(bulbs[rng.randrange(len(bulbs))], (x, h + 0.15, z), rng.uniform(0.08, 0.2))
    pitch = math.radians(-25.0)
    camera = {"name": "main", "camera": 0, "translation": [0.0, 25.0, 150.0],
              "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)],
              "_perspective": {"yfov": 0.8, "aspectRatio": 16.0 / 9.0, "znear": 0.05, "zfar": 2000.0}}
    b.write(os.path.join(out_dir, "fairground", "fairground.gltf"), camera)


def light_field(out_dir, occluders=True):
    """2,000 small double-sided quads of mixed radiance with 40 point and 10 spot lights over a
    40 m field (with 30 box occluders unless occluders is False)."""
    rng = random.Random(40)
    b = Builder()
    ground = b.material("ground", (0.4, 0.4, 0.38))
    stone = b.material("occluder", (0.5, 0.45, 0.4))
    # Eight radiance levels, log-spaced over two orders of magnitude, in four tints.
    tints = [(1.0, 0.85, 0.6), (1.0, 0.5, 0.3), (0.5, 0.7, 1.0), (0.8, 1.0, 0.7)]
    levels = [2.0 * 100.0 ** (k / 7.0) for k in range(8)]
    emitters = [b.material("emitter_%d_%d" % (lv, tn), (0.0, 0.0, 0.0), tints[tn], levels[lv], double_sided=True)
                for lv in range(8) for tn in range(4)]
    L = 20.0
    b.quad(ground, (-L, 0.0, -L), (-L, 0.0, L), (L, 0.0, L), (L, 0.0, -L))
    boxes = []
    for _ in range(30):
        x, z = rng.uniform(-18, 16), rng.uniform(-18, 16)
        w, d, h = rng.uniform(0.8, 2.5), rng.uniform(0.8, 2.5), rng.uniform(0.8, 3.0)
        boxes.append(((x, 0.0, z), (x + w, h, z + d)))
    if occluders:
        for lo, hi in boxes:
            b.box(stone, lo, hi)
    for _ in range(2000):
        c = (rng.uniform(-19.5, 19.5), rng.uniform(0.3, 3.0), rng.uniform(-19.5, 19.5))
        side = rng.uniform(0.05, 0.15)
        # A random orientation: the quad's normal uniform on the sphere, its edges about it.
        nz = rng.uniform(-1.0, 1.0)
        phi = rng.uniform(0.0, 2.0 * math.pi)
        r = math.sqrt(max(0.0, 1.0 - nz * nz))
        n = (r * math.cos(phi), nz, r * math.sin(phi))
        t = (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)
        u = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
        lu = math.sqrt(sum(x * x for x in u))
        u = tuple(x / lu * side * 0.5 for x in u)
        v = (n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0])
        corner = lambda su, sv: tuple(c[i] + su * u[i] + sv * v[i] for i in range(3))
        b.quad(emitters[rng.randrange(len(emitters))], corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1))
    for k in range(40):
        pos = (rng.uniform(-19, 19), rng.uniform(0.5, 4.0), rng.uniform(-19, 19))
        b.point_light("point_%d" % k, pos, tints[k % 4], 10.0 ** rng.uniform(0.0, 1.5))
    for k in range(10):
        pos = (rng.uniform(-18, 18), rng.uniform(3.0, 6.0), rng.uniform(-18, 18))
        # Aimed down (-Z turned -90 degrees about X), tilted by up to 30 degrees, then turned
        # about Y: the quaternion yaw * tilt.
        tilt, yaw = math.radians(rng.uniform(-30.0, 30.0)) - 0.5 * math.pi, rng.uniform(0.0, 2.0 * math.pi)
        sx, cx, sy, cy = math.sin(tilt / 2), math.cos(tilt / 2), math.sin(yaw / 2), math.cos(yaw / 2)
        q = (cy * sx, cx * sy, -sy * sx, cy * cx)
        b.spot_light("spot_%d" % k, pos, q, tints[k % 4], 10.0 ** rng.uniform(1.5, 2.5), 0.3, 0.6)
    pitch = math.radians(-28.0)
    camera = {"name": "main", "camera": 0, "translation": [0.0, 14.0, 30.0],
              "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)],
              "_perspective": {"yfov": 0.9, "aspectRatio": 16.0 / 9.0, "znear": 0.05, "zfar": 500.0}}
    name = "light-field" if occluders else "light-field-open"
    b.write(os.path.join(out_dir, name, name + ".gltf"), camera)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out_dir", help="folder to write cornell-lamp/ and night-street/ into (e.g. a folder on SST_SCENE_PATH)")
    ap.add_argument("--only", choices=["cornell-lamp", "night-street", "fairground", "light-field"])
    a = ap.parse_args()
    if a.only in (None, "cornell-lamp"):
        cornell_lamp(a.out_dir)
    if a.only in (None, "night-street"):
        night_street(a.out_dir)
    if a.only in (None, "fairground"):
        fairground(a.out_dir)
    if a.only in (None, "light-field"):
        light_field(a.out_dir)
        light_field(a.out_dir, occluders=False)



if __name__ == "__main__":
    main()
