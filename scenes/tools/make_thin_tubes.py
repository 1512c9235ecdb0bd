#!/usr/bin/env python3
"""Writes a scene of thin smooth-shaded tubes, for checking how the path tracer shades coarse
curved geometry against Blender Cycles.

Four vertical tubes (1 m high, `--segments` facets around, vertex normals pointing straight out of
the axis, albedo 0.8) stand on a 6 x 6 m ground (albedo 0.5) under a sun (3 W/m^2, from the side
and above) and a sky of one emissive quad 4 m up. The camera looks at them from `--camera-distance`
metres; `--shift` moves everything along x and z, to put the scene far from the origin. With few
segments the interpolated normals differ from the facets' by up to 180/segments degrees, which is
where a renderer's rules for shading normals show: light arriving under a facet, views under the
shading normal, and shadow rays that leave a facet toward a light its neighbour hides (the shadow
terminator).

    python3 scenes/tools/make_thin_tubes.py out/tubes.gltf --segments 6
    sst-render out/tubes.gltf --spp 1024 --width 256 --diffuse-only --max-bounces 8 -o out/tubes.exr

Everything is generated; metres, +Y up, diffuse materials, radiometric KHR_lights_punctual.
"""
import argparse
import base64
import json
import math
import struct


def look_rotation(direction):
    """The quaternion (x, y, z, w) that turns -Z toward `direction` by a yaw about +Y, then a pitch."""
    length = math.sqrt(sum(c * c for c in direction))
    f = [c / length for c in direction]
    yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(f[1])
    cy, sy, cp, sp = math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2), math.sin(pitch / 2)
    return [cy * sp, sy * cp, -sy * sp, cy * cp]


def build(segments, radius, shift, camera_distance):
    positions, normals = [], []

    def vertex(p, n):
        positions.append(p)
        normals.append(n)
        return len(positions) - 1

    g = [vertex((x, 0.0, z), (0.0, 1.0, 0.0)) for x, z in [(-3, -3), (3, -3), (3, 3), (-3, 3)]]
    ground = [g[0], g[3], g[2], g[0], g[2], g[1]]
    tubes = []
    for cx, cz in [(-0.3, 0.0), (-0.1, 0.1), (0.1, -0.1), (0.3, 0.0)]:
        bottom, top = [], []
        for i in range(segments):
            a = 2.0 * math.pi * i / segments
            n = (math.cos(a), 0.0, math.sin(a))
            bottom.append(vertex((cx + radius * n[0], 0.0, cz + radius * n[2]), n))
            top.append(vertex((cx + radius * n[0], 1.0, cz + radius * n[2]), n))
        for i in range(segments):
            j = (i + 1) % segments
            tubes += [bottom[i], top[i], top[j], bottom[i], top[j], bottom[j]]
    s = [vertex((x, 4.0, z), (0.0, -1.0, 0.0)) for x, z in [(-4, -4), (4, -4), (4, 4), (-4, 4)]]
    sky = [s[0], s[1], s[2], s[0], s[2], s[3]]

    data = b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(struct.pack("<3f", *n) for n in normals)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * len(positions)},
             {"buffer": 0, "byteOffset": 12 * len(positions), "byteLength": 12 * len(normals)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                  "min": [min(p[i] for p in positions) for i in range(3)],
                  "max": [max(p[i] for p in positions) for i in range(3)]},
                 {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"}]
    primitives = []
    for material, indices in enumerate([ground, tubes, sky]):
        block = b"".join(struct.pack("<I", i) for i in indices)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(block)})
        data += block
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
        primitives.append({"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": len(accessors) - 1, "material": material})

    def diffuse(name, albedo):
        return {"name": name, "doubleSided": True,
                "pbrMetallicRoughness": {"baseColorFactor": [albedo] * 3 + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}

    sky_material = diffuse("sky", 0.0)
    sky_material.update(emissiveFactor=[0.3, 0.35, 0.45], doubleSided=False)
    return {
        "asset": {"version": "2.0", "generator": "sst scenes/tools/make_thin_tubes.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1.0, 0.95, 0.9], "intensity": 3.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0, "translation": [shift, 0.0, shift]},
                  {"camera": 0, "translation": [shift, 0.5, shift + camera_distance], "rotation": look_rotation([0.0, 0.0, -1.0])},
                  {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": look_rotation([-0.6, -0.5, -0.62])}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [{"primitives": primitives}],
        "materials": [diffuse("ground", 0.5), diffuse("tube", 0.8), sky_material],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="the .gltf to write")
    ap.add_argument("--segments", type=int, default=12, help="facets around each tube (default 12)")
    ap.add_argument("--radius", type=float, default=0.01, help="tube radius in metres (default 0.01)")
    ap.add_argument("--shift", type=float, default=0.0, help="move the scene by this along x and z (default 0)")
    ap.add_argument("--camera-distance", type=float, default=1.5, help="camera to the tubes, metres (default 1.5)")
    a = ap.parse_args()
    if a.segments < 3 or a.radius <= 0.0 or a.camera_distance <= 0.0:
        ap.error("--segments must be at least 3, --radius and --camera-distance positive")
    with open(a.out, "w") as f:
        json.dump(build(a.segments, a.radius, a.shift, a.camera_distance), f)


if __name__ == "__main__":
    main()
