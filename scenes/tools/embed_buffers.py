#!/usr/bin/env python3
"""Make a .gltf self-contained: every buffer that refers to a file becomes a base64 data URI.

Usage: embed_buffers.py IN.gltf OUT.gltf

Only the "uri" values of "buffers" change; the rest of the JSON text is kept byte for byte, so the
result renders exactly like its source (scenes/cornell-box.gltf is built this way from
../shared/scenes/cornell-box/cornell-box.gltf). Images are left alone.
"""
import base64
import json
import os
import re
import sys


def embed(text: str, base_dir: str) -> str:
    doc = json.loads(text)
    for buf in doc.get("buffers", []):
        uri = buf.get("uri")
        if not uri or uri.startswith("data:"):
            continue
        with open(os.path.join(base_dir, uri), "rb") as f:
            data = f.read()
        if len(data) < buf["byteLength"]:
            sys.exit(f"error: {uri} has {len(data)} bytes, buffer byteLength is {buf['byteLength']}")
        data_uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
        # Replace the string in place rather than re-serialising, so nothing else moves.
        pattern = re.compile(r'("uri"\s*:\s*)' + re.escape(json.dumps(uri)))
        text, n = pattern.subn(lambda m: m.group(1) + json.dumps(data_uri), text)
        if n == 0:
            sys.exit(f"error: could not find the uri {uri!r} in the text")
    json.loads(text)  # still valid JSON
    return text


def main() -> None:
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, dst = sys.argv[1], sys.argv[2]
    with open(src, encoding="utf-8") as f:
        text = f.read()
    out = embed(text, os.path.dirname(os.path.abspath(src)))
    with open(dst, "w", encoding="utf-8") as f:
        f.write(out)


if __name__ == "__main__":
    main()
