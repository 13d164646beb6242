#!/usr/bin/env python3
"""Writes vplkit's deforming test scene as a single-file glTF 2.0 (buffer embedded as a base64
data URI):

  deforming_box/deforming_box.gltf   the Cornell box of make_cornell.py with a skinned reed that
                                     sways and a panel whose morph target bulges (4 s, loopable)

The scene for meshes whose vertices move under their node (`vplkit sequence --animate`, set-up
`deforming-box`): skinning and morph targets change the triangles themselves, so the BVH is refitted
or rebuilt from posed vertices rather than moved as a whole.
Run from anywhere: python3 scenes/make_deforming_box.py

Layout (metres, Y up, the open side faces +Z where the camera is), the box of make_cornell.py with
its point light and its short block:
  reed    'reed': a blue 0.16 x 1.4 m square bar standing at (-0.45, 0, -0.25), 8 segments, skinned to
          three joints on its axis (at heights 0, 0.7 and 1.4; each vertex weighted between the two
          nearest); animation 'sway' bends joints 1 and 2 about Z by 20 sin(2 pi t / 4) degrees each,
          so the top sways about 0.45 m to either side (LINEAR keys every 0.25 s).
  panel   'panel': a yellow 1.0 x 1.0 m grid of 10 x 10 quads 2 cm in front of the back wall, centred at
          (0.3, 1.1), with one morph target that pushes its centre 0.3 m toward the camera (a
          smooth cosine bump, position and normal deltas); animation 'breathe' sets its weight to
          (1 - cos(2 pi t / 4)) / 2 (LINEAR keys every 0.25 s): flat at t = 0 and 4, full at t = 2.
  camera  at (0, 1, 3.4) looking down -Z, vertical field of view 45 degrees.
"""

import math
import struct

from make_animated_box import AnimationWriter, axis_rotation
from make_cornell import FRONT_CAMERA, buffer_parts, write_scene, Builder, material, unit_cube, walls, y_rotation


WHITE, RED, GREEN, BLUE, YELLOW = 0, 1, 2, 3, 4
PERIOD = 4.0
SWAY_DEGREES = 20.0
REED_HEIGHT, REED_HALF_WIDTH, REED_SEGMENTS = 1.4, 0.08, 8
REED_BASE = (-0.45, 0.0, -0.25)
PANEL_SIZE, PANEL_QUADS, PANEL_BULGE = 1.0, 10, 0.3
PANEL_CENTRE = (0.3, 1.1, -0.98)


def float_view(b, values, fmt, target=34962):
    return b._view(b"".join(struct.pack(fmt, *v) for v in values), target)


def add_accessor(b, view, component, count, kind, bounds=None):
    a = {"bufferView": view, "componentType": component, "count": count, "type": kind}
    if bounds:
        a["min"], a["max"] = bounds
    b.accessors.append(a)
    return len(b.accessors) - 1


def bounds(points):
    return [min(p[k] for p in points) for k in range(3)], [max(p[k] for p in points) for k in range(3)]


def reed_geometry():
    """Four flat sides of a square bar along +Y from REED_BASE (the bind pose, in world space),
    rings every segment; per vertex
    the joints (0, 1, 2) and weights of its height (linear between the two nearest joints)."""
    positions, normals, joints, weights, indices = [], [], [], [], []
    w = REED_HALF_WIDTH
    sides = [((1, 0, 0), (0, 0, -1)), ((0, 0, 1), (1, 0, 0)), ((-1, 0, 0), (0, 0, 1)), ((0, 0, -1), (-1, 0, 0))]
    for normal, along in sides:
        base = len(positions)
        for ring in range(REED_SEGMENTS + 1):
            y = REED_HEIGHT * ring / REED_SEGMENTS
            s = 2.0 * ring / REED_SEGMENTS  # joint coordinate: 0, 1, 2 at the three joints
            lower = min(int(s), 1)
            upper_weight = s - lower
            for side in (-1, 1):
                x = REED_BASE[0] + normal[0] * w + along[0] * w * side
                z = REED_BASE[2] + normal[2] * w + along[2] * w * side
                positions.append((x, REED_BASE[1] + y, z))
                normals.append(normal)
                joints.append((lower, lower + 1, 0, 0))
                weights.append((1.0 - upper_weight, upper_weight, 0.0, 0.0))
        for ring in range(REED_SEGMENTS):
            a, c = base + 2 * ring, base + 2 * ring + 2
            # (along, +Y, normal) is right-handed: a, a+1, c+1, c run counter-clockwise seen from outside.
            indices += [a, a + 1, c + 1, a, c + 1, c]
    return positions, normals, joints, weights, indices


def panel_geometry():
    """The flat grid facing +Z, and its bulge target's position and normal deltas."""
    n = PANEL_QUADS
    positions, deltas, normal_deltas, indices = [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            u, v = i / n - 0.5, j / n - 0.5  # in [-0.5, 0.5]
            positions.append((u * PANEL_SIZE, v * PANEL_SIZE, 0.0))
            # Bump h(u, v) = B c(u) c(v), c(x) = (1 + cos(2 pi x)) / 2: zero with zero slope at the rim.
            cu, cv = (1 + math.cos(2 * math.pi * u)) / 2, (1 + math.cos(2 * math.pi * v)) / 2
            h = PANEL_BULGE * cu * cv
            dh_dx = PANEL_BULGE * (-math.pi * math.sin(2 * math.pi * u)) * cv / PANEL_SIZE
            dh_dy = PANEL_BULGE * cu * (-math.pi * math.sin(2 * math.pi * v)) / PANEL_SIZE
            length = math.sqrt(dh_dx * dh_dx + dh_dy * dh_dy + 1.0)
            deltas.append((0.0, 0.0, h))
            normal_deltas.append((-dh_dx / length, -dh_dy / length, 1.0 / length - 1.0))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            indices += [a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]
    return positions, deltas, normal_deltas, indices


def build():
    b = Builder()
    wall_material = {"floor": WHITE, "ceiling": WHITE, "back_wall": WHITE, "left_wall": RED, "right_wall": GREEN}
    nodes = []
    for name, (vertices, indices) in walls().items():
        nodes.append({"name": name, "mesh": b.mesh(name, vertices, indices, wall_material[name])})
    nodes.append({"name": "short_block", "mesh": b.mesh("block", *unit_cube(), WHITE), "translation": [0.35, 0.3, 0.3],
                  "rotation": y_rotation(-17.0), "scale": [0.6, 0.6, 0.6]})

    # The reed: a skinned mesh (its node's transform is ignored, glTF 3.7.3.3: the joints place it).
    positions, normals, joints, weights, indices = reed_geometry()
    pos = add_accessor(b, float_view(b, positions, "<3f"), 5126, len(positions), "VEC3", bounds(positions))
    nrm = add_accessor(b, float_view(b, normals, "<3f"), 5126, len(normals), "VEC3")
    jnt = add_accessor(b, float_view(b, joints, "<4H"), 5123, len(joints), "VEC4")
    wgt = add_accessor(b, float_view(b, weights, "<4f"), 5126, len(weights), "VEC4")
    idx = add_accessor(b, b._view(b"".join(struct.pack("<H", i) for i in indices), 34963), 5123, len(indices), "SCALAR")
    b.meshes.append({"name": "reed", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "JOINTS_0": jnt,
                                                                    "WEIGHTS_0": wgt}, "indices": idx, "material": BLUE}]})
    reed_mesh = len(b.meshes) - 1
    joint0 = len(nodes)
    step = REED_HEIGHT / 2
    nodes.append({"name": "reed_joint_0", "translation": list(REED_BASE), "children": [joint0 + 1]})
    nodes.append({"name": "reed_joint_1", "translation": [0.0, step, 0.0], "children": [joint0 + 2]})
    nodes.append({"name": "reed_joint_2", "translation": [0.0, step, 0.0]})
    # Inverse bind matrices (column-major): the joints' rest transforms are pure translations.
    inverse_binds = []
    for k in range(3):
        x, y, z = REED_BASE[0], REED_BASE[1] + step * k, REED_BASE[2]
        inverse_binds.append((1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -x, -y, -z, 1))
    view = float_view(b, inverse_binds, "<16f", None)
    del b.views[view]["target"]
    ibm = add_accessor(b, view, 5126, 3, "MAT4")
    nodes.append({"name": "reed", "mesh": reed_mesh, "skin": 0})

    # The panel: a morph target, weight animated.
    positions, deltas, normal_deltas, indices = panel_geometry()
    normals = [(0.0, 0.0, 1.0)] * len(positions)
    pos = add_accessor(b, float_view(b, positions, "<3f"), 5126, len(positions), "VEC3", bounds(positions))
    nrm = add_accessor(b, float_view(b, normals, "<3f"), 5126, len(normals), "VEC3")
    dpos = add_accessor(b, float_view(b, deltas, "<3f"), 5126, len(deltas), "VEC3", bounds(deltas))
    dnrm = add_accessor(b, float_view(b, normal_deltas, "<3f"), 5126, len(normal_deltas), "VEC3")
    idx = add_accessor(b, b._view(b"".join(struct.pack("<H", i) for i in indices), 34963), 5123, len(indices), "SCALAR")
    b.meshes.append({"name": "panel", "weights": [0.0], "primitives": [
        {"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx, "material": YELLOW,
         "targets": [{"POSITION": dpos, "NORMAL": dnrm}]}]})
    panel = len(nodes)
    nodes.append({"name": "panel", "mesh": len(b.meshes) - 1, "translation": list(PANEL_CENTRE)})

    nodes.append({"name": "light", "translation": [0.0, 1.9, 0.0], "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.0, 3.4]})

    writer = AnimationWriter(b)
    times = [PERIOD * k / 16 for k in range(17)]
    bend = [axis_rotation((0, 0, 1), SWAY_DEGREES * math.sin(2 * math.pi * t / PERIOD)) for t in times]
    sway = writer.animation("sway", joint0 + 1, "rotation", times, bend)
    sway["samplers"].append(dict(sway["samplers"][0]))
    sway["channels"].append({"sampler": 1, "target": {"node": joint0 + 2, "path": "rotation"}})
    breathe = {"name": "breathe",
               "samplers": [{"input": writer.accessor(times, "SCALAR", with_bounds=True),
                             "output": writer.accessor([(1 - math.cos(2 * math.pi * t / PERIOD)) / 2 for t in times],
                                                       "SCALAR"),
                             "interpolation": "LINEAR"}],
               "channels": [{"sampler": 0, "target": {"node": panel, "path": "weights"}}]}

    materials = [material("white", (0.73, 0.73, 0.73)), material("red", (0.65, 0.05, 0.05)),
                 material("green", (0.12, 0.45, 0.15)), material("blue", (0.15, 0.2, 0.6)), material("yellow", (0.7, 0.6, 0.2))]
    roots = [i for i in range(len(nodes)) if i not in (joint0 + 1, joint0 + 2)]
    return {
        "asset": {"version": "2.0", "generator": "vplkit scenes/make_deforming_box.py",
                  "copyright": "Written for vplkit; same licence as the vplkit repository"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling_point", "type": "point", "color": [1.0, 0.85, 0.6], "intensity": 8.0}]}},
        "scene": 0,
        "scenes": [{"name": "deforming_box", "nodes": roots}],
        "nodes": nodes,
        "meshes": b.meshes,
        "skins": [{"name": "reed_skin", "joints": [joint0, joint0 + 1, joint0 + 2], "inverseBindMatrices": ibm,
                   "skeleton": joint0}],
        "materials": materials,
        "animations": [sway, breathe],
        "cameras": [FRONT_CAMERA],
        **buffer_parts(b),
    }


def main():
    write_scene("deforming_box", build())


if __name__ == "__main__":
    main()
