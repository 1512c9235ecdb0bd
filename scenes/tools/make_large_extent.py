#!/usr/bin/env python3
"""Writes a scene whose extent dwarfs its room: a shared interior with a large ground plane
outside it, for the ray-offset checks of issue 14 (results/README.md, "Ray offsets").

    python3 scenes/tools/make_large_extent.py ../shared/scenes/breakfast-room/breakfast-room.gltf \
        /work/scenes-gen/breakfast-ground [--half 100] [--albedo 0.3]

The output glTF is the input's JSON with one more mesh: a square ground (2 triangles, +Y up,
Lambert albedo `--albedo`, half-size `--half` metres) 1 cm below the input's lowest vertex. Its
buffers and images are referenced by relative paths to the input's folder (nothing is copied);
the ground's own buffer is a data URI. With the breakfast room (12 m across) and --half 100 the
scene diagonal grows from 20 m to 283 m, the proportions of the held-out classroom that issue 14
measured. Cycles reference (Blender 3.4 from Debian):

    cd /work/scenes-gen/breakfast-ground && blender -b --factory-startup -noaudio \
      --python /work/shared/tools/render_gltf.py -- --scene breakfast-ground.gltf \
      --out ref/cycles-4096spp --res 192 --resy 108 --spp 4096 --bounces 8 --diffuse-only --threads 2
"""
import argparse
import base64
import json
import os
import struct


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("out_dir")
    ap.add_argument("--half", type=float, default=100.0)
    ap.add_argument("--albedo", type=float, default=0.3)
    a = ap.parse_args()

    src_dir = os.path.dirname(os.path.abspath(a.scene))
    doc = json.load(open(a.scene))
    os.makedirs(a.out_dir, exist_ok=True)
    rel = os.path.relpath(src_dir, os.path.abspath(a.out_dir))
    for holder in ("buffers", "images"):
        for item in doc.get(holder, []):
            if "uri" in item and not item["uri"].startswith("data:"):
                item["uri"] = rel + "/" + item["uri"]

    lowest = min(acc["min"][1] for acc in doc["accessors"] if acc.get("type") == "VEC3" and "min" in acc and
                 any(p["attributes"].get("POSITION") == i for m in doc["meshes"] for p in m["primitives"]
                     for i in [doc["accessors"].index(acc)]))
    y = lowest - 0.01
    h = a.half
    positions = [-h, y, -h, -h, y, h, h, y, h, h, y, -h]
    normals = [0.0, 1.0, 0.0] * 4
    indices = [0, 1, 2, 0, 2, 3]
    data = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<6I", *indices)
    doc["buffers"].append({"byteLength": len(data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
    b = len(doc["buffers"]) - 1
    views = doc["bufferViews"]
    views += [{"buffer": b, "byteOffset": 0, "byteLength": 48},
              {"buffer": b, "byteOffset": 48, "byteLength": 48},
              {"buffer": b, "byteOffset": 96, "byteLength": 24}]
    v = len(views) - 3
    accs = doc["accessors"]
    accs += [{"bufferView": v, "componentType": 5126, "count": 4, "type": "VEC3",
              "min": [-h, y, -h], "max": [h, y, h]},
             {"bufferView": v + 1, "componentType": 5126, "count": 4, "type": "VEC3"},
             {"bufferView": v + 2, "componentType": 5125, "count": 6, "type": "SCALAR"}]
    k = len(accs) - 3
    doc["materials"].append({"name": "Ground", "doubleSided": True,
                             "pbrMetallicRoughness": {"baseColorFactor": [a.albedo, a.albedo, a.albedo, 1.0],
                                                      "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    doc["meshes"].append({"name": "Ground", "primitives": [{"attributes": {"POSITION": k, "NORMAL": k + 1},
                                                            "indices": k + 2,
                                                            "material": len(doc["materials"]) - 1}]})
    doc["nodes"].append({"name": "Ground", "mesh": len(doc["meshes"]) - 1})
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(len(doc["nodes"]) - 1)

    name = os.path.basename(os.path.normpath(a.out_dir))
    out = os.path.join(a.out_dir, name + ".gltf")
    json.dump(doc, open(out, "w"), indent=1)
    print(f"{out}: ground at y = {y:.4f}, half-size {h} m, albedo {a.albedo}")


if __name__ == "__main__":
    main()
