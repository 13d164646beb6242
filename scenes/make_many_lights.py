#!/usr/bin/env python3
"""Writes vplkit's in-repo many-light scene as a single-file glTF 2.0 (buffer embedded):

  many_lights/many_lights.gltf   the Cornell-style box of make_cornell.py (same walls, blocks and
                                 camera), lit by 256 small emissive panels of varied colour and
                                 power on the ceiling and the back wall, and 3 bright ones

It is the scene where direct light needs a light tree: the flat sampler draws every
panel by its power alone, wherever the shading point is, while the tree's cut and traversal
prefer the panels near it. Run from anywhere: python3 scenes/make_many_lights.py (the committed
.gltf is what vplkit loads). Deterministic: a fixed random seed. With --emitters N OUT.gltf it
writes the same box lit by N small triangles on the ceiling instead (cost per emitter count).
With --mesh-lights OUT.gltf it writes the box lit by irregular mesh lights instead (one- vs
two-level trees, the RTSLC paper sec. 3.1): 40 round lamps (triangle fans) of 1 to 1536 triangles and
3 to 25 cm radius on the ceiling and the back wall, and two 1.6 m strip lights of 1024 triangles
along the ceiling's sides; each lamp its own mesh (one primitive: one mesh light), in one of the
12 classes. 12,317 emissive triangles in 42 mesh lights.

Panels (one-sided squares, facing into the box, 1 cm off their wall):
  ceiling: 16 x 12 jittered grid over x, z in [-0.9, 0.9], 6 cm squares, facing down;
  back wall: 8 x 8 jittered grid over x in [-0.9, 0.9], y in [0.2, 1.8], 5 cm squares, facing +Z;
  each in one of 12 classes: a colour of the palette below and emissive strength 0.5 .. 16
  (log-spaced), the class drawn at random;
  bright: two 20 cm squares on the ceiling at (-0.6, -0.6) and (0.55, 0.25), strength 40, and one
  on the right wall (x = 0.99) at y = 1.2, z = -0.3, facing -X, strength 25.
So 259 panels, 518 emissive triangles; the box, blocks and their materials are make_cornell.py's.
"""

import base64
import json
import math
import random
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import make_cornell as cornell  # noqa: E402  (the box, blocks, builder and material helpers)

PALETTE = [(1.0, 0.85, 0.6), (0.6, 0.8, 1.0), (1.0, 0.4, 0.3), (0.5, 1.0, 0.5), (1.0, 1.0, 1.0), (0.9, 0.6, 1.0)]
CLASSES = 12


def square(centre, half, normal):
    """A square of side 2 half centred at `centre`, facing `normal` (an axis), corners CCW from it."""
    axis = [i for i in range(3) if normal[i] != 0][0]
    u, v = (axis + 1) % 3, (axis + 2) % 3
    corners = []
    for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        p = list(centre)
        p[u] += half * du
        p[v] += half * dv
        corners.append(tuple(p))
    # (u, v, axis) is right-handed: CCW seen from +axis; reverse for panels facing -axis.
    if normal[axis] < 0:
        corners.reverse()
    return corners


def panels(rng):
    """(corners, normal, class) of the small panels."""
    out = []
    for i in range(16):
        for j in range(12):
            x = -0.9 + 1.8 * (i + 0.2 + 0.6 * rng.random()) / 16
            z = -0.9 + 1.8 * (j + 0.2 + 0.6 * rng.random()) / 12
            out.append((square((x, 1.99, z), 0.03, (0, -1, 0)), (0, -1, 0), rng.randrange(CLASSES)))
    for i in range(8):
        for j in range(8):
            x = -0.9 + 1.8 * (i + 0.2 + 0.6 * rng.random()) / 8
            y = 0.2 + 1.6 * (j + 0.2 + 0.6 * rng.random()) / 8
            out.append((square((x, y, -0.99), 0.025, (0, 0, 1)), (0, 0, 1), rng.randrange(CLASSES)))
    return out


def mesh_of(shapes):
    """Squares (4 corners: two triangles) or triangles (3 corners), as vertices and indices."""
    vertices, indices = [], []
    for corners, normal in shapes:
        base = len(vertices)
        vertices += [(c, normal) for c in corners]
        indices += [base + k for k in ((0, 1, 2, 0, 2, 3) if len(corners) == 4 else (0, 1, 2))]
    return vertices, indices


def ceiling_triangles(count, rng):
    """`count` small triangles facing down over the ceiling (a jittered grid), for the cost-per-emitter
    measurements: (corners, normal, class) each."""
    side = max(1, math.ceil(math.sqrt(count)))
    cell = 1.8 / side
    out = []
    for k in range(count):
        i, j = k % side, k // side
        x = -0.9 + cell * (i + 0.5)
        z = -0.9 + cell * (j + 0.5)
        r = 0.35 * cell
        corners = [(x - r, 1.99, z - r), (x, 1.99, z + r), (x + r, 1.99, z - r)]  # CCW seen from below
        out.append((corners, (0, -1, 0), rng.randrange(CLASSES)))
    return out


def lamps(rng):
    """(triangles, class) per mesh light for --mesh-lights: each triangle 3 corners and the normal."""
    out = []
    counts = [1, 2, 6, 24, 96, 384, 1536]
    for k in range(40):
        n = counts[k % len(counts)] if k < 35 else 1 + rng.randrange(8)
        radius = 0.03 + 0.22 * rng.random()
        on_ceiling = k % 4 != 3
        if on_ceiling:
            centre = (-0.8 + 1.6 * rng.random(), 1.99, -0.8 + 1.6 * rng.random())
            normal = (0, -1, 0)
        else:
            centre = (-0.8 + 1.6 * rng.random(), 0.3 + 1.4 * rng.random(), -0.99)
            normal = (0, 0, 1)
        fan = []
        # A fan of n triangles (n = 1, 2: a triangle, a square), CCW seen from the side it faces.
        sides = max(n, 3)
        for i in range(n):
            a0 = 2 * math.pi * i / sides
            a1 = 2 * math.pi * (i + 1) / sides
            if n == 1:
                ring = [2 * math.pi * j / 3 for j in range(3)]
                offsets = [(radius * math.cos(a), radius * math.sin(a)) for a in ring]
            elif n == 2:
                corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
                quad = [(radius * u, radius * v) for u, v in corners]
                offsets = [quad[0], quad[1], quad[2]] if i == 0 else [quad[0], quad[2], quad[3]]
            else:
                offsets = [(0.0, 0.0), (radius * math.cos(a0), radius * math.sin(a0)),
                           (radius * math.cos(a1), radius * math.sin(a1))]
            fan.append(([in_plane(centre, normal, du, dv) for du, dv in offsets], normal))
        out.append((fan, rng.randrange(CLASSES)))
    for x in (-0.85, 0.85):
        strip = []
        for i in range(512):
            z0, z1 = -0.8 + 1.6 * i / 512, -0.8 + 1.6 * (i + 1) / 512
            strip.append((square_between((x - 0.01, 1.99, z0), (x + 0.01, 1.99, z1)), (0, -1, 0)))
        out.append((strip, rng.randrange(CLASSES)))
    return out


def in_plane(centre, normal, du, dv):
    """centre + du u + dv v, (u, v, normal) right-handed, so (du, dv) CCW is CCW seen from the normal."""
    axis = [i for i in range(3) if normal[i] != 0][0]
    u, v = (axis + 1) % 3, (axis + 2) % 3
    if normal[axis] < 0:
        u, v = v, u
    p = list(centre)
    p[u] += du
    p[v] += dv
    return tuple(p)


def square_between(lo, hi):
    """A ceiling square (y = lo[1]) between two x-z corners, CCW seen from below: 4 corners."""
    return [(lo[0], lo[1], lo[2]), (hi[0], lo[1], lo[2]), (hi[0], lo[1], hi[2]), (lo[0], lo[1], hi[2])]


def build(emitters=None, mesh_lights=False):
    # The box and blocks as make_cornell.py writes them, in one builder so one buffer holds all.
    b = cornell.Builder()
    wall_material = {"floor": cornell.WHITE, "ceiling": cornell.WHITE, "back_wall": cornell.WHITE,
                     "left_wall": cornell.RED, "right_wall": cornell.GREEN}
    nodes = []
    for name, (vertices, indices) in cornell.walls().items():
        nodes.append({"name": name, "mesh": b.mesh(name, vertices, indices, wall_material[name])})
    cube = b.mesh("block", *cornell.unit_cube(), cornell.WHITE)
    short_block = len(nodes) + 1
    nodes.append({"name": "blocks", "translation": [0.0, 0.3, 0.0], "children": [short_block, short_block + 1]})
    nodes.append({"name": "short_block", "mesh": cube, "translation": [0.35, 0.0, 0.3],
                  "rotation": cornell.y_rotation(-17.0), "scale": [0.6, 0.6, 0.6]})
    nodes.append({"name": "tall_block", "mesh": cube, "translation": [-0.35, 0.3, -0.3],
                  "rotation": cornell.y_rotation(17.0), "scale": [0.6, 1.2, 0.6]})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.0, 3.4]})
    materials = [cornell.material("white", (0.73, 0.73, 0.73)), cornell.material("red", (0.65, 0.05, 0.05)),
                 cornell.material("green", (0.12, 0.45, 0.15))]

    rng = random.Random(15)
    small = [] if mesh_lights else panels(rng) if emitters is None else ceiling_triangles(emitters, rng)
    for k in range(CLASSES):
        strength = 0.5 * math.pow(32.0, k / (CLASSES - 1))
        colour = PALETTE[k % len(PALETTE)]
        materials.append(cornell.material("panel_%d" % k, (0.78, 0.78, 0.78), emissive=colour, strength=strength))
        shapes = [(corners, normal) for corners, normal, c in small if c == k]
        # Meshes of at most 16384 shapes: 16-bit indices reach 65535 vertices.
        for part in range(0, len(shapes), 16384):
            name = "panels_%d_%d" % (k, part // 16384)
            nodes.append({"name": name, "mesh": b.mesh(name, *mesh_of(shapes[part:part + 16384]),
                                                       len(materials) - 1)})
    for i, (shapes, k) in enumerate(lamps(rng) if mesh_lights else []):
        # One mesh per lamp: its emitters are one primitive instance, one mesh light.
        name = "lamp_%d" % i
        nodes.append({"name": name, "mesh": b.mesh(name, *mesh_of(shapes), 3 + k)})
    bright = [] if emitters is not None or mesh_lights else [((-0.6, 1.99, -0.6), 0.1, (0, -1, 0), 40.0, (1.0, 0.9, 0.75)),
              ((0.55, 1.99, 0.25), 0.1, (0, -1, 0), 40.0, (0.75, 0.85, 1.0)),
              ((0.99, 1.2, -0.3), 0.1, (-1, 0, 0), 25.0, (1.0, 0.7, 0.5))]
    for i, (centre, half, normal, strength, colour) in enumerate(bright):
        materials.append(cornell.material("bright_%d" % i, (0.78, 0.78, 0.78), emissive=colour, strength=strength))
        nodes.append({"name": "bright_%d" % i,
                      "mesh": b.mesh("bright_%d" % i, *mesh_of([(square(centre, half, normal), normal)]),
                                     len(materials) - 1)})

    roots = [i for i in range(len(nodes)) if i not in (short_block, short_block + 1)]
    gltf = {"asset": {"version": "2.0", "generator": "vplkit scenes/make_many_lights.py",
                      "copyright": "Written for vplkit; same licence as the vplkit repository"},
            "extensionsUsed": ["KHR_materials_emissive_strength"],
            "scene": 0,
            "scenes": [{"name": "many_lights", "nodes": roots}],
            "nodes": nodes,
            "meshes": b.meshes,
            "materials": materials,
            "cameras": [{"name": "front", "type": "perspective",
                         "perspective": {"yfov": math.radians(45.0), "aspectRatio": 1.0, "znear": 0.05,
                                         "zfar": 20.0}}],
            "accessors": b.accessors,
            "bufferViews": b.views,
            "buffers": [{"byteLength": len(b.data), "uri": "data:application/octet-stream;base64," +
                         base64.b64encode(bytes(b.data)).decode()}]}
    return gltf


def main():
    # --emitters N OUT.gltf: the same box lit by N small triangles on the ceiling instead (the
    # README's cost-per-emitter measurements; not committed).
    if len(sys.argv) == 3 and sys.argv[1] == "--mesh-lights":
        path = Path(sys.argv[2])
        gltf = build(mesh_lights=True)
    elif len(sys.argv) == 4 and sys.argv[1] == "--emitters":
        path = Path(sys.argv[3])
        gltf = build(emitters=int(sys.argv[2]))
    elif len(sys.argv) == 1:
        path = HERE / "many_lights" / "many_lights.gltf"
        gltf = build()
    else:
        sys.exit("usage: make_many_lights.py [--emitters N OUT.gltf | --mesh-lights OUT.gltf]")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(gltf, indent=1) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
