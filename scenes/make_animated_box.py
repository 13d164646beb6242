#!/usr/bin/env python3
"""Writes vplkit's animated test scene as a single-file glTF 2.0 (buffer embedded as a base64
data URI):

  animated_box/animated_box.gltf   the Cornell box of make_cornell.py with a swinging spot light
                                   and a turning block (two glTF animations, 4 s, loopable)

The scene for things that move (`vplkit sequence --animate`, set-up `animated-box`): the light
moves (VPLs, shadow maps and light trees must follow it), the tall block turns (the BVH is refitted,
the denoiser must reproject its surface and reject history where it uncovers the wall behind).
Run from anywhere: python3 scenes/make_animated_box.py

Layout (metres, Y up, the open side faces +Z where the camera is), the box of make_cornell.py:
  box x in [-1, 1], y in [0, 2], z in [-1, 1]; white floor, ceiling and back wall, red left wall,
  green right wall; the short block as in make_cornell.py (0.6 m cube at (0.35, 0.3, 0.3),
  -17 degrees about Y).
  turning block  'tall_block': 0.6 x 1.2 x 0.6 m at (-0.35, 0.6, -0.3), animation 'turn' rotates it
                 about Y once in 4 s (keys every 90 degrees, LINEAR: slerp, a constant rate)
  swinging light 'pendulum' hangs from (0, 1.95, 0); animation 'swing' rotates it about Z,
                 35 sin(2 pi t / 4) degrees (LINEAR keys every 0.25 s); its child 'lamp' 0.45 m
                 below the pivot holds a KHR_lights_punctual spot light (16 cd, warm white, cone
                 0.5 / 1.0 rad) pointing along the pendulum, away from the pivot: the lit spot
                 sweeps the floor from side to side, lighting the red and green walls in turn.
  camera         at (0, 1, 3.4) looking down -Z, vertical field of view 45 degrees.
Both animations last 4 s and end where they start, so `--loop` plays them without a jump.
"""

import math
import struct

from make_cornell import FRONT_CAMERA, buffer_parts, write_scene, Builder, material, unit_cube, walls, y_rotation


WHITE, RED, GREEN = 0, 1, 2
PERIOD = 4.0
SWING_DEGREES = 35.0


def axis_rotation(axis, degrees):
    a = math.radians(degrees) / 2
    s = math.sin(a)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(a)]


class AnimationWriter:
    """Adds float keyframe accessors to a Builder's buffer."""

    def __init__(self, builder):
        self.b = builder

    def accessor(self, values, kind, with_bounds=False):
        flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
        view = self.b._view(b"".join(struct.pack("<f", x) for x in flat), None)
        del self.b.views[view]["target"]  # animation data is not a vertex or index buffer
        a = {"bufferView": view, "componentType": 5126, "count": len(values), "type": kind}
        if with_bounds:
            a["min"], a["max"] = [min(values)], [max(values)]
        self.b.accessors.append(a)
        return len(self.b.accessors) - 1

    def animation(self, name, node, path, times, values):
        kind = {"translation": "VEC3", "rotation": "VEC4", "scale": "VEC3"}[path]
        t = self.accessor(times, "SCALAR", with_bounds=True)
        v = self.accessor(values, kind)
        return {"name": name, "samplers": [{"input": t, "output": v, "interpolation": "LINEAR"}],
                "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]}


def build():
    b = Builder()
    wall_material = {"floor": WHITE, "ceiling": WHITE, "back_wall": WHITE, "left_wall": RED, "right_wall": GREEN}
    nodes = []
    for name, (vertices, indices) in walls().items():
        nodes.append({"name": name, "mesh": b.mesh(name, vertices, indices, wall_material[name])})
    cube = b.mesh("block", *unit_cube(), WHITE)
    nodes.append({"name": "short_block", "mesh": cube, "translation": [0.35, 0.3, 0.3],
                  "rotation": y_rotation(-17.0), "scale": [0.6, 0.6, 0.6]})
    tall_block = len(nodes)
    nodes.append({"name": "tall_block", "mesh": cube, "translation": [-0.35, 0.6, -0.3],
                  "rotation": y_rotation(17.0), "scale": [0.6, 1.2, 0.6]})
    pendulum = len(nodes)
    nodes.append({"name": "pendulum", "translation": [0.0, 1.95, 0.0], "children": [pendulum + 1]})
    # The spot looks down its node's -Z: turned -90 degrees about X it looks down -Y, along the rod.
    nodes.append({"name": "lamp", "translation": [0.0, -0.45, 0.0], "rotation": axis_rotation((1, 0, 0), -90.0),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.0, 3.4]})

    writer = AnimationWriter(b)
    # The block: 17 degrees at t = 0, a whole turn in PERIOD; keys every 90 degrees (slerp takes
    # the short way, so a key per quarter turn keeps the direction).
    turn_times = [PERIOD * k / 4 for k in range(5)]
    turn_values = [y_rotation(17.0 + 90.0 * k) for k in range(5)]
    # The pendulum: 40 sin(2 pi t / T) degrees about Z, 17 keys.
    swing_times = [PERIOD * k / 16 for k in range(17)]
    swing_values = [axis_rotation((0, 0, 1), SWING_DEGREES * math.sin(2 * math.pi * t / PERIOD))
                    for t in swing_times]
    animations = [writer.animation("turn", tall_block, "rotation", turn_times, turn_values),
                  writer.animation("swing", pendulum, "rotation", swing_times, swing_values)]

    materials = [material("white", (0.73, 0.73, 0.73)), material("red", (0.65, 0.05, 0.05)),
                 material("green", (0.12, 0.45, 0.15))]
    roots = [i for i in range(len(nodes)) if i != pendulum + 1]
    return {
        "asset": {"version": "2.0", "generator": "vplkit scenes/make_animated_box.py",
                  "copyright": "Written for vplkit; same licence as the vplkit repository"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "swinging_spot", "type": "spot", "color": [1.0, 0.85, 0.6], "intensity": 16.0,
             "spot": {"innerConeAngle": 0.5, "outerConeAngle": 1.0}}]}},
        "scene": 0,
        "scenes": [{"name": "animated_box", "nodes": roots}],
        "nodes": nodes,
        "meshes": b.meshes,
        "materials": materials,
        "animations": animations,
        "cameras": [FRONT_CAMERA],
        **buffer_parts(b),
    }


def main():
    write_scene("animated_box", build())


if __name__ == "__main__":
    main()
