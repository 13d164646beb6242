#!/usr/bin/env python3
"""Writes a closed room of six walls, each a grid of N x N quads (default 600: 4,320,000
triangles), as glTF 2.0 with its buffer in a .bin beside it, for trying scenes larger than one
storage buffer binding's range (maxStorageBufferRange: 128 MiB on lavapipe; this room's BVH
nodes alone need 138 MB, its triangles 207 MB).

Not committed as data (the default output, out/big_room/, is ignored by git): run it where the
scene is needed.

  python3 scenes/make_big_room.py [--quads N] [--out DIR]
  vplkit render --device cpu --scene out/big_room/big_room.gltf --position 0,0,4 --target 0,0,0 \\
      --fov 70 --point 0,3,0,1,1,1,20 --method hybrid --width 64 --height 64 --vpls 256

The room is the cube [-5, 5]^3 (metres), normals pointing inward, grey diffuse walls (albedo
0.5); each wall is one mesh primitive of (N + 1)^2 vertices (position, normal) and 2 N^2
triangles. No lights in the file: give one on the command line (a point light inside).
"""

import argparse
import array
import json
from pathlib import Path

HALF = 5.0  # the room's half size, metres


def wall(n, axis, sign):
    """A wall of the cube on the plane x[axis] = sign * HALF, facing inward: positions and normals
    (float32 triplets) and triangle indices (uint32), counter-clockwise seen from inside."""
    u_axis, v_axis = [(1, 2), (2, 0), (0, 1)][axis]
    positions = array.array("f")
    normals = array.array("f")
    normal = [0.0, 0.0, 0.0]
    normal[axis] = -sign
    for j in range(n + 1):
        v = -HALF + 2.0 * HALF * j / n
        for i in range(n + 1):
            u = -HALF + 2.0 * HALF * i / n
            p = [0.0, 0.0, 0.0]
            p[axis] = sign * HALF
            p[u_axis] = u
            p[v_axis] = v
            positions.extend(p)
            normals.extend(normal)
    indices = array.array("I")
    row = n + 1
    # (u, v, normal) is right-handed for sign -1 walls' inward normal (+axis); flip the winding for
    # sign +1 so that every wall is counter-clockwise seen from inside.
    for j in range(n):
        for i in range(n):
            a = j * row + i
            b, c, d = a + 1, a + row + 1, a + row
            if sign < 0:
                indices.extend((a, b, c, a, c, d))
            else:
                indices.extend((a, c, b, a, d, c))
    return positions, normals, indices


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quads", type=int, default=600, help="quads along each wall's side (default 600)")
    parser.add_argument("--out", default=str(Path(__file__).resolve().parent.parent / "out" / "big_room"),
                        help="output folder (default out/big_room in the repository)")
    args = parser.parse_args()
    if args.quads < 1:
        parser.error("--quads must be at least 1")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    n = args.quads

    blob = bytearray()
    views, accessors, primitives = [], [], []

    def add_view(data, target):
        offset = len(blob)
        blob.extend(data.tobytes())
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) * data.itemsize, "target": target})
        return len(views) - 1

    for axis in range(3):
        for sign in (-1.0, 1.0):
            positions, normals, indices = wall(n, axis, sign)
            count = len(positions) // 3
            lo = [-HALF, -HALF, -HALF]
            hi = [HALF, HALF, HALF]
            lo[axis] = hi[axis] = sign * HALF
            accessors.append({"bufferView": add_view(positions, 34962), "componentType": 5126, "count": count,
                              "type": "VEC3", "min": lo, "max": hi})
            accessors.append({"bufferView": add_view(normals, 34962), "componentType": 5126, "count": count,
                              "type": "VEC3"})
            accessors.append({"bufferView": add_view(indices, 34963), "componentType": 5125,
                              "count": len(indices), "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": len(accessors) - 3, "NORMAL": len(accessors) - 2},
                               "indices": len(accessors) - 1, "material": 0})

    (out / "big_room.bin").write_bytes(blob)
    gltf = {
        "asset": {"version": "2.0", "generator": "vplkit scenes/make_big_room.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "room"}],
        "meshes": [{"primitives": primitives, "name": "room"}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
                                                                 "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "buffers": [{"uri": "big_room.bin", "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    (out / "big_room.gltf").write_text(json.dumps(gltf, indent=1) + "\n")
    print(f"{out / 'big_room.gltf'}: {6 * 2 * n * n} triangles, {6 * (n + 1) ** 2} vertices, {len(blob)} bytes")


if __name__ == "__main__":
    main()
