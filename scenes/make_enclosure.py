#!/usr/bin/env python3
"""Writes vplkit's closed diffuse enclosure as single-file glTF 2.0 (buffer embedded as a base64
data URI):

  enclosure_sphere/enclosure_sphere.gltf   an inward-facing sphere lit by a point light at its centre

The analytic case for energy tests: inside a sphere every surface point sees every other one,
and a point light at the centre gives every point the same irradiance E. One bounce off a
diffuse surface of albedo rho then gives every point irradiance rho E again (a uniformly bright
sphere lights its own inside uniformly), so one-bounce indirect / direct = rho at every pixel.
The mesh is an icosahedron subdivided 3 times (1280 flat triangles, radius 1 m at the vertices):
the faceting moves the ratio by well under 1% (each facet's irradiance varies by its cosine,
for direct and indirect alike). Grey albedo 0.5, metallic 0, roughness 1; a 1 cd white point
light at the centre; the camera at (0, 0.3, 0.4) looking at (0, -0.2, -1) sees only the wall.

The committed .gltf is what vplkit loads; this script is how it was made (python3 is not needed
to use vplkit). Run from anywhere: python3 scenes/make_enclosure.py
"""

import base64
import json
import math
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent
ALBEDO = 0.5
SUBDIVISIONS = 3


def normalize(v):
    length = math.sqrt(sum(c * c for c in v))
    return tuple(c / length for c in v)


def icosphere(levels):
    """Unit icosphere: vertex list and outward counter-clockwise triangles."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    points = [normalize(p) for p in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                                     (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        midpoints = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoints:
                points.append(normalize(tuple((points[a][k] + points[b][k]) / 2 for k in range(3))))
                midpoints[key] = len(points) - 1
            return midpoints[key]

        next_faces = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            next_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = next_faces
    return points, faces


def inward_triangles():
    """Flat-shaded triangles facing the centre: each outward face reversed, its own 3 vertices."""
    points, faces = icosphere(SUBDIVISIONS)
    vertices, indices = [], []
    for a, b, c in faces:
        p0, p1, p2 = points[a], points[c], points[b]  # reversed winding: front faces the centre
        e1 = [p1[k] - p0[k] for k in range(3)]
        e2 = [p2[k] - p0[k] for k in range(3)]
        n = normalize((e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]))
        base = len(vertices)
        vertices += [(p0, n), (p1, n), (p2, n)]
        indices += [base, base + 1, base + 2]
    return vertices, indices


def pack(vertices, indices):
    data = bytearray()
    views = []

    def view(payload, target):
        while len(data) % 4:
            data.append(0)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(payload), "target": target})
        data.extend(payload)
        return len(views) - 1

    positions = [p for p, _ in vertices]
    pos_view = view(b"".join(struct.pack("<3f", *p) for p, _ in vertices), 34962)
    nrm_view = view(b"".join(struct.pack("<3f", *n) for _, n in vertices), 34962)
    idx_view = view(b"".join(struct.pack("<H", i) for i in indices), 34963)
    accessors = [
        {"bufferView": pos_view, "componentType": 5126, "count": len(vertices), "type": "VEC3",
         "min": [min(p[k] for p in positions) for k in range(3)],
         "max": [max(p[k] for p in positions) for k in range(3)]},
        {"bufferView": nrm_view, "componentType": 5126, "count": len(vertices), "type": "VEC3"},
        {"bufferView": idx_view, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
    ]
    return data, views, accessors


def look_at_rotation(eye, target):
    """Quaternion turning the camera's -Z towards target (Y stays as up as it can)."""
    f = normalize([target[k] - eye[k] for k in range(3)])
    z = [-c for c in f]
    x = normalize((z[2], 0.0, -z[0]))  # up (0, 1, 0) x z
    y = (z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0])
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]
    w = math.sqrt(max(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2])) / 2.0
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]


def build():
    vertices, indices = inward_triangles()
    data, views, accessors = pack(vertices, indices)
    eye, target = (0.0, 0.3, 0.4), (0.0, -0.2, -1.0)
    return {
        "asset": {"version": "2.0", "generator": "vplkit scenes/make_enclosure.py",
                  "copyright": "Written for vplkit; same licence as the vplkit repository"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "centre", "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 1.0}]}},
        "scene": 0,
        "scenes": [{"name": "enclosure", "nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "sphere", "mesh": 0},
            {"name": "light", "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_rotation(eye, target)},
        ],
        "meshes": [{"name": "sphere", "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {
            "baseColorFactor": [ALBEDO, ALBEDO, ALBEDO, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "cameras": [{"name": "inside", "type": "perspective",
                     "perspective": {"yfov": math.radians(60.0), "aspectRatio": 1.0, "znear": 0.01, "zfar": 10.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()}],
    }


def main():
    path = HERE / "enclosure_sphere" / "enclosure_sphere.gltf"
    path.parent.mkdir(exist_ok=True)
    path.write_text(json.dumps(build(), indent=1) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
