#!/usr/bin/env python3
"""Writes a sunlit interior inside a ground plane of any size, for checking that no result depends
on how far the scene extends beyond what the camera sees (docs/design/lengths.md).

A closed room (6 x 2.8 x 5 m, walls albedo 0.7, warm floor, ceiling 0.8) with two windows in its
+x wall stands on a square ground of half-size `--half` metres (albedo 0.3). A sun (5 W/m^2)
shines through the windows onto the floor; everything else in the room is lit by light that
bounced at least once (off the sunlit floor patches or the ground outside). From `--half 50` on,
four boxes ("hills", 10% of the half-size high) stand at 70% of the half-size, so the far geometry
grows with the ground. The camera stands inside and sees the sunlit floor and, through the
windows, the ground outside. Only the geometry outside the room changes with `--half`.

With `--near-half N --far-albedo 0` the ground beyond N metres and the hills are black: the scene's
extent grows with `--half` while its light does not change at all, which is what the tests of
tests/core/manylight/large_extent_test.cpp need (scenes/window-room-*.gltf were made so). A larger
grey ground does change the light: more of it reflects sunlight through the windows.

    python3 scenes/tools/make_window_room.py out/window-room-5km.gltf --half 5000
    sst-render out/window-room-5km.gltf --diffuse-only --max-bounces 8 -o out/room.exr

Cycles reference (Blender 3.4 from Debian; ../shared/tools/render_gltf.py):

    blender -b --factory-startup -noaudio --python render_gltf.py -- --scene window-room-5km.gltf \
      --out window-room-5km-cycles --res 320 --resy 180 --spp 1024 --bounces 8 --diffuse-only

Everything is generated; metres, +Y up, diffuse materials, radiometric KHR_lights_punctual
(directional intensity = irradiance in W/m^2).
"""
import argparse
import base64
import json
import math
import struct

from make_thin_tubes import look_rotation  # this folder's: -Z turned toward a direction

ROOM_X, ROOM_Y, ROOM_Z = 3.0, 2.8, 2.5  # half-width, height, half-depth
WINDOWS_Z = [(-1.8, -0.4), (0.4, 1.8)]  # in the +x wall
WINDOW_Y = (0.8, 2.2)
GROUND_Y = -0.01
SUN_DIRECTION = (-0.75, -0.55, -0.35)  # the way the light travels
CAMERA_EYE = (-2.6, 1.5, 2.1)
CAMERA_TARGET = (1.0, 0.7, -1.0)


class Mesh:
    def __init__(self):
        self.positions, self.normals, self.groups = [], [], {}

    def quad(self, group, a, b, c, d, n):
        """Two triangles a-b-c, a-c-d with the flat normal n, wound counter-clockwise about n (glTF's
        front face), whichever order the corners come in."""
        e1 = [b[i] - a[i] for i in range(3)]
        e2 = [c[i] - a[i] for i in range(3)]
        cross = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        if sum(cross[i] * n[i] for i in range(3)) < 0.0:
            b, d = d, b
        first = len(self.positions)
        self.positions += [a, b, c, d]
        self.normals += [n] * 4
        self.groups.setdefault(group, []).extend([first, first + 1, first + 2, first, first + 2, first + 3])

    def box(self, group, lo, hi):
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        self.quad(group, (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (0, 1, 0))
        self.quad(group, (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1), (1, 0, 0))
        self.quad(group, (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0), (-1, 0, 0))
        self.quad(group, (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (0, 0, 1))
        self.quad(group, (x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (0, 0, -1))


def wall_x(mesh, group, x, normal_x, z_lo, z_hi, y_lo, y_hi):
    mesh.quad(group, (x, y_lo, z_lo), (x, y_hi, z_lo), (x, y_hi, z_hi), (x, y_lo, z_hi), (normal_x, 0, 0))


def ground_square(m, group, h):
    m.quad(group, (-h, GROUND_Y, -h), (-h, GROUND_Y, h), (h, GROUND_Y, h), (h, GROUND_Y, -h), (0, 1, 0))


def ground_ring(m, group, inner, outer):
    """The square of half-size `outer` less the one of half-size `inner`, as four quads."""
    i, o, g = inner, outer, GROUND_Y
    m.quad(group, (-o, g, -o), (-o, g, -i), (o, g, -i), (o, g, -o), (0, 1, 0))
    m.quad(group, (-o, g, i), (-o, g, o), (o, g, o), (o, g, i), (0, 1, 0))
    m.quad(group, (-o, g, -i), (-o, g, i), (-i, g, i), (-i, g, -i), (0, 1, 0))
    m.quad(group, (i, g, -i), (i, g, i), (o, g, i), (o, g, -i), (0, 1, 0))


def build(half, near_half):
    m = Mesh()
    x, y, z = ROOM_X, ROOM_Y, ROOM_Z
    if near_half < half:
        ground_square(m, "ground", near_half)
        ground_ring(m, "far", near_half, half)
    else:
        ground_square(m, "ground", half)
    m.quad("floor", (-x, 0, -z), (-x, 0, z), (x, 0, z), (x, 0, -z), (0, 1, 0))
    m.quad("ceiling", (-x, y, -z), (x, y, -z), (x, y, z), (-x, y, z), (0, -1, 0))
    # walls reach down to the ground so that no light slips under them
    m.quad("walls", (-x, GROUND_Y, -z), (x, GROUND_Y, -z), (x, y, -z), (-x, y, -z), (0, 0, 1))
    m.quad("walls", (x, GROUND_Y, z), (-x, GROUND_Y, z), (-x, y, z), (x, y, z), (0, 0, -1))
    wall_x(m, "walls", -x, 1, -z, z, GROUND_Y, y)
    # the +x wall around its two windows
    (wy0, wy1) = WINDOW_Y
    wall_x(m, "walls", x, -1, -z, z, GROUND_Y, wy0)
    wall_x(m, "walls", x, -1, -z, z, wy1, y)
    edges = [-z] + [e for w in WINDOWS_Z for e in w] + [z]
    for i in range(0, len(edges), 2):
        wall_x(m, "walls", x, -1, edges[i], edges[i + 1], wy0, wy1)
    if half >= 50.0:
        s = 0.1 * half
        for sx, sz in [(1, 1), (1, -1), (-1, 1), (-1, -1)]:
            cx, cz = 0.7 * half * sx, 0.7 * half * sz
            m.box("far" if near_half < half else "hills", (cx - s, GROUND_Y, cz - s), (cx + s, s, cz + s))
    return m


def document(mesh, half, width, height, far_albedo, unit=1.0):
    data = b"".join(struct.pack("<3f", *p) for p in mesh.positions)
    data += b"".join(struct.pack("<3f", *n) for n in mesh.normals)
    count = len(mesh.positions)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * count},
             {"buffer": 0, "byteOffset": 12 * count, "byteLength": 12 * count}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                  "min": [min(p[i] for p in mesh.positions) for i in range(3)],
                  "max": [max(p[i] for p in mesh.positions) for i in range(3)]},
                 {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3"}]
    albedo = {"ground": [0.3] * 3, "floor": [0.55, 0.45, 0.35], "ceiling": [0.8] * 3, "walls": [0.7] * 3,
              "hills": [0.4, 0.45, 0.35], "far": [far_albedo] * 3}
    materials, primitives = [], []
    for name, indices in mesh.groups.items():
        block = b"".join(struct.pack("<I", i) for i in indices)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(block)})
        data += block
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
        materials.append({"name": name, "doubleSided": True,
                          "pbrMetallicRoughness": {"baseColorFactor": albedo[name] + [1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 1.0}})
        primitives.append({"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": len(accessors) - 1,
                           "material": len(materials) - 1})
    view = [t - e for t, e in zip(CAMERA_TARGET, CAMERA_EYE)]
    return {
        "asset": {"version": "2.0", "generator": "sst scenes/tools/make_window_room.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1.0, 0.96, 0.9],
                                                           "intensity": 5.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0, "name": "room", "scale": [unit] * 3},
                  {"camera": 0, "name": "main", "translation": [unit * e for e in CAMERA_EYE],
                   "rotation": look_rotation(view)},
                  {"name": "sun", "extensions": {"KHR_lights_punctual": {"light": 0}},
                   "rotation": look_rotation(SUN_DIRECTION)}],
        "cameras": [{"type": "perspective", "name": "main",
                     "perspective": {"yfov": 1.0, "aspectRatio": width / height, "znear": 0.01 * unit}}],
        "meshes": [{"primitives": primitives}],
        "materials": materials,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="the .gltf to write")
    ap.add_argument("--half", type=float, default=50.0, help="ground half-size in metres (default 50; at least 3.5)")
    ap.add_argument("--aspect", type=float, default=16.0 / 9.0, help="camera aspect ratio (default 16:9)")
    ap.add_argument("--near-half", type=float, default=None,
                    help="ground beyond this half-size (and the hills) takes --far-albedo (default: none does)")
    ap.add_argument("--far-albedo", type=float, default=0.0, help="albedo beyond --near-half (default 0: black)")
    ap.add_argument("--unit-scale", type=float, default=1.0,
                    help="scene units per metre (100: the same scene in centimetres): geometry and camera scale, the "
                         "sun's irradiance does not, so every image is the same at any scale (default 1)")
    a = ap.parse_args()
    near = a.half if a.near_half is None else a.near_half
    if not a.half >= 3.5 or not near >= 3.5 or not a.aspect > 0.0 or not 0.0 <= a.far_albedo <= 1.0 or not a.unit_scale > 0.0:
        ap.error("--half and --near-half must be at least 3.5 (the room's extent), --aspect positive and "
                 "--far-albedo in [0, 1], --unit-scale positive")
    with open(a.out, "w") as f:
        json.dump(document(build(a.half, near), a.half, a.aspect, 1.0, a.far_albedo, a.unit_scale), f, separators=(",", ":"))


if __name__ == "__main__":
    main()
