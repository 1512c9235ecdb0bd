#!/usr/bin/env python3
"""Writes scenes/animated_box.gltf: a box that slides and turns over a floor, seen by a camera
that slides sideways, lit by one point light; one 2-second animation. Written for sst (no
external data); the buffer is embedded as a base64 data URI so the file stands alone.

    python3 scenes/tools/make_animated_box.py scenes/animated_box.gltf
"""
import base64
import json
import math
import struct
import sys

FLOAT, USHORT = 5126, 5123


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, fmt, values, count, gltf_type, component, minmax=False, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        raw = struct.pack("<%d%s" % (len(values), fmt), *values)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)}
        if target:
            view["target"] = target
        self.data += raw
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": gltf_type}
        if minmax:  # glTF requires min/max on POSITION and on animation inputs
            n = len(values) // count
            acc["min"] = [min(values[i::n]) for i in range(n)]
            acc["max"] = [max(values[i::n]) for i in range(n)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def floats(self, values, gltf_type, minmax=False):
        n = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[gltf_type]
        return self.add("f", values, len(values) // n, gltf_type, FLOAT, minmax)


def box(half):
    """24 vertices (4 a face, so normals are flat) and 36 indices, outward-facing, CCW."""
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = [0, 0, 0], [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v[(axis + 2) % 3] = 1
            if sign < 0:
                u, v = v, u
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos += [half * (n[i] + a * u[i] + b * v[i]) for i in range(3)]
                nrm += n
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, idx


def quat_y(degrees):
    h = math.radians(degrees) / 2
    return [0.0, math.sin(h), 0.0, math.cos(h)]


def main(out):
    buf = Buffer()
    meshes = []

    def mesh(pos, nrm, idx, material):
        p = buf.add("f", pos, len(pos) // 3, "VEC3", FLOAT, minmax=True, target=34962)
        n = buf.add("f", nrm, len(nrm) // 3, "VEC3", FLOAT, target=34962)
        i = buf.add("H", idx, len(idx), "SCALAR", USHORT, target=34963)
        meshes.append({"primitives": [{"attributes": {"POSITION": p, "NORMAL": n}, "indices": i, "material": material}]})
        return len(meshes) - 1

    floor = mesh([-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2], [0, 1, 0] * 4, [0, 1, 2, 0, 2, 3], 0)
    cube = mesh(*box(0.25), 1)

    # Keys at 0, 1, 2 s: the box slides from x = -1 to 1, hopping to y = 0.75 halfway, and turns
    # half a turn about Y; the camera slides from x = -0.5 to 0.5 (linear, one segment).
    times = buf.floats([0.0, 1.0, 2.0], "SCALAR", minmax=True)
    box_path = buf.floats([-1, 0.25, 0, 0, 0.75, 0, 1, 0.25, 0], "VEC3")
    box_turn = buf.floats(quat_y(0) + quat_y(90) + quat_y(180), "VEC4")
    cam_times = buf.floats([0.0, 2.0], "SCALAR", minmax=True)
    cam_path = buf.floats([-0.5, 1.2, 4.0, 0.5, 1.2, 4.0], "VEC3")

    tilt = math.radians(-12) / 2  # the camera looks slightly down
    doc = {
        "asset": {"version": "2.0", "generator": "sst scenes/tools/make_animated_box.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"name": "key", "type": "point", "intensity": 8.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"name": "floor", "mesh": floor},
            {"name": "box", "mesh": cube, "translation": [-1, 0.25, 0]},
            {"name": "main", "camera": 0, "translation": [-0.5, 1.2, 4.0], "rotation": [math.sin(tilt), 0, 0, math.cos(tilt)]},
            {"name": "key", "translation": [0.0, 3.0, 1.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"name": "main", "type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.05}}],
        "materials": [
            {"name": "floor", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
            {"name": "box", "doubleSided": True, "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.15, 1], "metallicFactor": 0, "roughnessFactor": 1}},
        ],
        "meshes": meshes,
        "animations": [{
            "name": "move",
            "samplers": [
                {"input": times, "output": box_path, "interpolation": "LINEAR"},
                {"input": times, "output": box_turn, "interpolation": "LINEAR"},
                {"input": cam_times, "output": cam_path, "interpolation": "LINEAR"},
            ],
            "channels": [
                {"sampler": 0, "target": {"node": 1, "path": "translation"}},
                {"sampler": 1, "target": {"node": 1, "path": "rotation"}},
                {"sampler": 2, "target": {"node": 2, "path": "translation"}},
            ],
        }],
        "accessors": buf.accessors,
        "bufferViews": buf.views,
        "buffers": [{"byteLength": len(buf.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf.data)).decode()}],
    }
    with open(out, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "scenes/animated_box.gltf")
