#!/usr/bin/env python3
"""Writes vplkit's two in-repo Cornell-style boxes as single-file glTF 2.0 (buffer embedded as a
base64 data URI):

  cornell_point/cornell_point.gltf        lit by one KHR_lights_punctual point light
  cornell_emissive/cornell_emissive.gltf  lit by an emissive quad just below the ceiling

The committed .gltf files are what vplkit loads; this script is how they were made (python3 is
not needed to use vplkit). Run from anywhere: python3 scenes/make_cornell.py

Layout (metres, Y up, the open side faces +Z where the camera is):
  box x in [-1, 1], y in [0, 2], z in [-1, 1]; white floor, ceiling and back wall, red left wall
  (x = -1), green right wall (x = +1); every wall one-sided, facing into the box.
  Two blocks are one unit-cube mesh instanced by two nodes under a parent node "blocks"
  (translation 0.3 up), so the file exercises a transform hierarchy and instancing:
    short_block: translation (0.35, 0, 0.3), rotated -17 degrees about Y, scale 0.6
    tall_block:  translation (-0.35, 0.3, -0.3), rotated +17 degrees about Y, scale (0.6, 1.2, 0.6)
  Camera at (0, 1, 3.4) looking down -Z, vertical field of view 45 degrees, aspect 1: the opening
  (2 x 2 at distance 2.4) just fills the view.

Light levels are matched: the point light (8 cd at y = 1.9) gives the floor centre 8 / 1.9^2 =
2.2 lux; the 0.5 x 0.5 emissive quad (radiance 40 x (1, 0.85, 0.6) at y = 1.99) gives it about
L * A / d^2 = 40 * 0.25 / 1.99^2 = 2.5 (white channel).
"""

import base64
import json
import math
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent

WHITE, RED, GREEN, LIGHT = 0, 1, 2, 3


def quad(corners, normal):
    """Four corners in counter-clockwise order seen from the side `normal` points to."""
    return [(c, normal) for c in corners], [0, 1, 2, 0, 2, 3]


def walls():
    return {
        "floor": quad([(-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1)], (0, 1, 0)),
        "ceiling": quad([(-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1)], (0, -1, 0)),
        "back_wall": quad([(-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1)], (0, 0, 1)),
        "left_wall": quad([(-1, 0, 1), (-1, 0, -1), (-1, 2, -1), (-1, 2, 1)], (1, 0, 0)),
        "right_wall": quad([(1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1)], (-1, 0, 0)),
    }


def unit_cube():
    """Cube [-0.5, 0.5]^3 with outward faces, 4 vertices per face (flat normals)."""
    vertices, indices = [], []
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = 0.5 * sign
                p[u_axis] = 0.5 * du
                p[v_axis] = 0.5 * dv
                corners.append(tuple(p))
            # (u, v, n) is right-handed, so the corners run counter-clockwise seen from +n;
            # reverse them for the faces looking down -n.
            if sign < 0:
                corners.reverse()
            base = len(vertices)
            vertices += [(c, tuple(n)) for c in corners]
            indices += [base + i for i in (0, 1, 2, 0, 2, 3)]
    return vertices, indices


def ceiling_light():
    h = 0.25
    return quad([(-h, 1.99, -h), (h, 1.99, -h), (h, 1.99, h), (-h, 1.99, h)], (0, -1, 0))


def y_rotation(degrees):
    a = math.radians(degrees) / 2
    return [0.0, math.sin(a), 0.0, math.cos(a)]


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors, self.meshes = [], [], []

    def _view(self, payload, target):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload), "target": target})
        self.data += payload
        return len(self.views) - 1

    def mesh(self, name, vertices, indices, material):
        positions = [p for p, _ in vertices]
        normals = [n for _, n in vertices]
        pos_view = self._view(b"".join(struct.pack("<3f", *p) for p in positions), 34962)
        nrm_view = self._view(b"".join(struct.pack("<3f", *n) for n in normals), 34962)
        idx_view = self._view(b"".join(struct.pack("<H", i) for i in indices), 34963)
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        base = len(self.accessors)
        self.accessors += [
            {"bufferView": pos_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": nrm_view, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": idx_view, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ]
        self.meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": base, "NORMAL": base + 1}, "indices": base + 2, "material": material}]})
        return len(self.meshes) - 1


def material(name, rgb, emissive=None, strength=None):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0,
                                                "roughnessFactor": 1.0}}
    if emissive:
        m["emissiveFactor"] = list(emissive)
        m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    return m


# The camera every box scene has: at (0, 1, 3.4) on its node, looking down -Z.
FRONT_CAMERA = {"name": "front", "type": "perspective",
                "perspective": {"yfov": math.radians(45.0), "aspectRatio": 1.0, "znear": 0.05, "zfar": 20.0}}


def buffer_parts(b):
    """A Builder's accessors and views and its data as the file's one embedded buffer."""
    return {
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"byteLength": len(b.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode()}],
    }


def write_scene(name, gltf):
    """Writes scenes/NAME/NAME.gltf."""
    path = HERE / name / (name + ".gltf")
    path.parent.mkdir(exist_ok=True)
    path.write_text(json.dumps(gltf, indent=1) + "\n")
    print("wrote", path)


def build(emissive):
    b = Builder()
    wall_material = {"floor": WHITE, "ceiling": WHITE, "back_wall": WHITE, "left_wall": RED, "right_wall": GREEN}
    nodes = []
    for name, (vertices, indices) in walls().items():
        nodes.append({"name": name, "mesh": b.mesh(name, vertices, indices, wall_material[name])})
    cube = b.mesh("block", *unit_cube(), WHITE)
    short_block = len(nodes) + 1
    nodes.append({"name": "blocks", "translation": [0.0, 0.3, 0.0], "children": [short_block, short_block + 1]})
    nodes.append({"name": "short_block", "mesh": cube, "translation": [0.35, 0.0, 0.3],
                  "rotation": y_rotation(-17.0), "scale": [0.6, 0.6, 0.6]})
    nodes.append({"name": "tall_block", "mesh": cube, "translation": [-0.35, 0.3, -0.3],
                  "rotation": y_rotation(17.0), "scale": [0.6, 1.2, 0.6]})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.0, 3.4]})

    materials = [material("white", (0.73, 0.73, 0.73)), material("red", (0.65, 0.05, 0.05)),
                 material("green", (0.12, 0.45, 0.15))]
    gltf = {"asset": {"version": "2.0", "generator": "vplkit scenes/make_cornell.py",
                      "copyright": "Written for vplkit; same licence as the vplkit repository"}}
    if emissive:
        materials.append(material("ceiling_light", (0.78, 0.78, 0.78), emissive=(1.0, 0.85, 0.6), strength=40.0))
        nodes.append({"name": "ceiling_light", "mesh": b.mesh("ceiling_light", *ceiling_light(), LIGHT)})
        gltf["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    else:
        nodes.append({"name": "light", "translation": [0.0, 1.9, 0.0],
                      "extensions": {"KHR_lights_punctual": {"light": 0}}})
        gltf["extensionsUsed"] = ["KHR_lights_punctual"]
        gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling_point", "type": "point", "color": [1.0, 0.85, 0.6], "intensity": 8.0}]}}

    roots = [i for i in range(len(nodes)) if i not in (short_block, short_block + 1)]
    gltf.update({
        "scene": 0,
        "scenes": [{"name": "cornell", "nodes": roots}],
        "nodes": nodes,
        "meshes": b.meshes,
        "materials": materials,
        "cameras": [FRONT_CAMERA],
        **buffer_parts(b),
    })
    return gltf


def main():
    for name, emissive in (("cornell_point", False), ("cornell_emissive", True)):
        write_scene(name, build(emissive))


if __name__ == "__main__":
    main()
