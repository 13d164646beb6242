#!/usr/bin/env python3
"""Writes vplkit's glossy test scene as a single-file glTF 2.0 (buffer embedded as a base64
data URI):

  glossy_floor/glossy_floor.gltf   a box with a dark glossy floor under coloured walls

The scene of the glossy branch (the SST paper sec. 4.2, shaders/include/vplkit/gi_lobe.glsl): the
walls are lit by the point light, and their light, one bounce later, is what the floor reflects:
the coloured walls' mirror images in the floor are indirect highlights, which a method that
samples the whole BRDF towards each cluster's mean smears. Run from anywhere:
python3 scenes/make_glossy.py

Layout (metres, Y up, the open side faces +Z where the camera is), the box of make_cornell.py:
  box x in [-1, 1], y in [0, 2], z in [-1, 1]; every wall one-sided, facing into the box.
  floor      'glossy_floor': dark grey dielectric, base colour 0.08, roughness 0.25, metallic 0
  left wall  'red' (0.65, 0.05, 0.05), right wall 'green' (0.12, 0.45, 0.15),
  back wall  'blue' (0.1, 0.15, 0.6), ceiling 'white' 0.73 (all roughness 1, metallic 0)
  one block  'copper': metal, base colour (0.95, 0.64, 0.54), roughness 0.3, a 0.5 m cube at
             (0.45, 0.25, -0.35) rotated 25 degrees about Y
  light      point light 'ceiling_point', 6 cd, warm white, at (0, 1.8, 0.2)
  camera     at (0, 1, 2.4) looking at (0, 0.35, -0.2): the floor fills the lower half of the view,
             seen at ~15 degrees above grazing at its back, where the reflections are brightest
"""

import math

from make_cornell import FRONT_CAMERA, buffer_parts, write_scene, Builder, unit_cube, walls, y_rotation


def material(name, rgb, roughness=1.0, metallic=0.0):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0],
                                                   "metallicFactor": metallic, "roughnessFactor": roughness}}


def look_at_rotation(position, target):
    """The quaternion (x, y, z, w) turning glTF's camera (looking down -Z, +Y up) towards target."""
    d = [t - p for p, t in zip(position, target)]
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))  # about X, positive looks up
    yaw = math.atan2(-d[0], -d[2])                   # about Y
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    # q = q_yaw * q_pitch
    return [cy * sp, sy * cp, -sy * sp, cy * cp]


def build():
    b = Builder()
    names = ["glossy_floor", "red", "green", "blue", "white", "copper"]
    materials = [material("glossy_floor", (0.08, 0.08, 0.08), roughness=0.25),
                 material("red", (0.65, 0.05, 0.05)), material("green", (0.12, 0.45, 0.15)),
                 material("blue", (0.1, 0.15, 0.6)), material("white", (0.73, 0.73, 0.73)),
                 material("copper", (0.95, 0.64, 0.54), roughness=0.3, metallic=1.0)]
    index = {n: i for i, n in enumerate(names)}
    wall_material = {"floor": "glossy_floor", "ceiling": "white", "back_wall": "blue", "left_wall": "red",
                     "right_wall": "green"}
    nodes = []
    for name, (vertices, indices) in walls().items():
        nodes.append({"name": name, "mesh": b.mesh(name, vertices, indices, index[wall_material[name]])})
    cube = b.mesh("block", *unit_cube(), index["copper"])
    nodes.append({"name": "copper_block", "mesh": cube, "translation": [0.45, 0.25, -0.35],
                  "rotation": y_rotation(25.0), "scale": [0.5, 0.5, 0.5]})
    position, target = [0.0, 1.0, 2.4], [0.0, 0.35, -0.2]
    nodes.append({"name": "camera", "camera": 0, "translation": position,
                  "rotation": look_at_rotation(position, target)})
    nodes.append({"name": "light", "translation": [0.0, 1.8, 0.2],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    return {
        "asset": {"version": "2.0", "generator": "vplkit scenes/make_glossy.py",
                  "copyright": "Written for vplkit; same licence as the vplkit repository"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling_point", "type": "point", "color": [1.0, 0.9, 0.75], "intensity": 6.0}]}},
        "scene": 0,
        "scenes": [{"name": "glossy_floor", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": b.meshes,
        "materials": materials,
        "cameras": [FRONT_CAMERA],
        **buffer_parts(b),
    }


def main():
    write_scene("glossy_floor", build())


if __name__ == "__main__":
    main()
