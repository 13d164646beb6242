#!/usr/bin/python3
"""Why vplkit's direct light on Sponza-sun reads ~8% above Blender Cycles', measured.

usage: scripts/cycles_direct.py [OUT_DIR] [VPLKIT]   (defaults: out/cycles-direct, build/release/samples/vplkit)

Renders direct light only (sun, 160x90, the reference's camera, `--brdf lambert`, full-resolution
textures) on copies of ../shared/reference/Sponza-sun whose materials are white (alpha-tested ones
keep their texture for its alpha), so the kit's radiance is irradiance / pi, as Cycles' DiffDir
pass is, with no albedo between them. Then it applies to the kit's own normals and visibility
(read back from its layered EXR) the two things Cycles 3.4 does to a normal-mapped diffuse
surface that vplkit does not:
  - bump shadowing (Chiang, Li and Burley 2019, "Taming the Shadow Terminator"; Cycles'
    bump_shadowing_term): diffuse light from wi is scaled by a smoothstep-like cubic of
    g = (Ns.wi) / ((N.wi)(Ns.N)), N the mapped normal, Ns the unmapped (smooth) one;
  - ensure_valid_reflection: a mapped normal whose mirror direction of the view falls below the
    surface is bent toward Ns until it does not.
Ns is read from a second render without normal maps. It prints kit / Cycles totals and the spread
of the per-pixel quotient before and after, so anyone can check the explanation.
"""
import json
import os
import re
import struct
import subprocess
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from cycles_ratio import read_exr  # noqa: E402

REFERENCE = "../shared/reference/Sponza-sun"


def read_vplkit_exr(path):
    """{layer.channel: HxW float32} of a single-part scanline EXR, uncompressed or ZIP (vplkit's)."""
    data = open(path, "rb").read()
    pos, channels, window, compression = 8, [], None, None
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        end2 = data.index(b"\0", end + 1)
        size = struct.unpack_from("<i", data, end2 + 1)[0]
        value = data[end2 + 5:end2 + 5 + size]
        if name == "channels":
            p = 0
            while value[p] != 0:
                e = value.index(b"\0", p)
                channels.append((value[p:e].decode(), struct.unpack_from("<i", value, e + 1)[0]))
                p = e + 17
        elif name == "dataWindow":
            window = struct.unpack("<4i", value)
        elif name == "compression":
            compression = value[0]
        pos = end2 + 5 + size
    if compression not in (0, 3):
        raise SystemExit(f"{path}: only uncompressed or ZIP EXR is read here")
    x0, y0, x1, y1 = window
    width, height = x1 - x0 + 1, y1 - y0 + 1
    lines = 16 if compression == 3 else 1
    offsets = struct.unpack_from(f"<{(height + lines - 1) // lines}Q", data, pos + 1)
    out = {name: np.zeros((height, width), np.float32) for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8:offset + 8 + size]
        rows = min(lines, y1 + 1 - y)
        raw = sum(width * rows * (2 if kind == 1 else 4) for _, kind in channels)
        if size < raw:  # ZIP: inflate, undo the byte predictor, then the two-halves interleave
            d = np.frombuffer(zlib.decompress(block), np.uint8).astype(np.int64)
            d[1:] -= 128
            t = (np.cumsum(d) % 256).astype(np.uint8)
            half = (len(t) + 1) // 2
            block = np.empty(len(t), np.uint8)
            block[0::2], block[1::2] = t[:half], t[half:]
            block = block.tobytes()
        p = 0
        for row in range(rows):
            for name, kind in channels:
                n = width * (2 if kind == 1 else 4)
                out[name][y - y0 + row] = np.frombuffer(block[p:p + n], "<f2" if kind == 1 else "<f4")
                p += n
    return out


def write_scene_copies(out):
    """White copies of the reference scene, with and without normal maps, full-resolution textures."""
    source = f"{REFERENCE}/scene/Sponza-sun.gltf"
    base = os.path.relpath(os.path.dirname(os.path.abspath(source)), os.path.abspath(out))
    paths = {}
    for variant in ("mapped", "unmapped"):
        gltf = json.load(open(source))
        for item in gltf.get("buffers", []) + gltf.get("images", []):
            if "uri" in item and not item["uri"].startswith("data:"):
                item["uri"] = os.path.join(base, item["uri"])
        gltf["samplers"] = [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}]
        for texture in gltf.get("textures", []):
            texture["sampler"] = 0
        for material in gltf["materials"]:
            if material.get("alphaMode", "OPAQUE") != "MASK":
                pbr = material.setdefault("pbrMetallicRoughness", {})
                pbr.pop("baseColorTexture", None)
                pbr["baseColorFactor"] = [1, 1, 1, 1]
            if variant == "unmapped":
                material.pop("normalTexture", None)
        paths[variant] = os.path.join(out, f"white-{variant}.gltf")
        json.dump(gltf, open(paths[variant], "w"))
    return paths


def blender_to_gltf(v):
    return np.array([v[0], v[2], -v[1]])


def camera_and_sun():
    """Pixel-independent camera frame and the direction toward the sun, from render_info.json."""
    info = json.load(open(f"{REFERENCE}/b1/render_info.json"))
    camera = next(c for c in info["checks"] if c.startswith("camera:"))
    vectors = {k: blender_to_gltf([float(x) for x in v.split(",")])
               for k, v in re.findall(r"(forward|up) \(([^)]*)\)", camera)}
    yfov = float(re.search(r"yfov ([0-9.]+)", camera).group(1))
    to_sun = -blender_to_gltf(info["lights"][0]["direction"])
    return vectors["forward"], vectors["up"], yfov, to_sun / np.linalg.norm(to_sun)


def dot(a, b):
    return (a * b).sum(-1)


def bump_shadowing(ns, n, wi):
    """Cycles' bump_shadowing_term(Ns, N, wi)."""
    denominator = dot(n, wi) * dot(ns, n)
    g = np.divide(dot(ns, wi), denominator, out=np.ones_like(denominator), where=denominator != 0)
    cubic = -g * g * g + g * g + g
    return np.where(g >= 1, 1.0, np.where(g < 0, 0.0, cubic))


def ensure_valid_reflection(ns, i, n):
    """Cycles' ensure_valid_reflection(Ng = Ns, I = towards the viewer, N)."""
    r = 2 * dot(n, i)[..., None] * n - i
    threshold = np.minimum(0.9 * dot(ns, i), 0.01)
    valid = dot(ns, r) >= threshold
    x = n - dot(n, ns)[..., None] * ns
    x /= np.maximum(np.linalg.norm(x, axis=-1, keepdims=True), 1e-12)
    ix, iz = dot(i, x), dot(i, ns)
    a = np.maximum(ix * ix + iz * iz, 1e-12)
    b = np.sqrt(np.maximum(ix * ix * (a - threshold * threshold), 0))
    c = iz * threshold + a
    z1, z2 = 0.5 / a * (b + c), 0.5 / a * (c - b)
    ok1, ok2 = (z1 > 1e-5) & (z1 <= 1 + 1e-5), (z2 > 1e-5) & (z2 <= 1 + 1e-5)
    n1 = np.stack([np.sqrt(np.maximum(1 - z1, 0)), np.sqrt(np.maximum(z1, 0))], -1)
    n2 = np.stack([np.sqrt(np.maximum(1 - z2, 0)), np.sqrt(np.maximum(z2, 0))], -1)
    r1 = 2 * (n1[..., 0] * ix + n1[..., 1] * iz) * n1[..., 1] - iz
    r2 = 2 * (n2[..., 0] * ix + n2[..., 1] * iz) * n2[..., 1] - iz
    both_reflect = (r1 >= 1e-5) & (r2 >= 1e-5)
    pick_first = np.where(ok1 & ok2, np.where(both_reflect, r1 < r2, r1 > r2), ok1)
    chosen = np.where(pick_first[..., None], n1, n2)
    bent = chosen[..., :1] * x + chosen[..., 1:] * ns
    bent = np.where((~ok1 & ~ok2)[..., None], ns, bent)
    return np.where(valid[..., None], n, bent)


def report(name, kit, cycles, lit):
    q = kit[lit] / cycles[lit]
    print(f"  {name:<48} total {kit.sum() / cycles.sum():.4f}   per-pixel quotient: median {np.median(q):.4f}, "
          f"p10 {np.percentile(q, 10):.3f}, p90 {np.percentile(q, 90):.3f}")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/cycles-direct"
    vplkit = sys.argv[2] if len(sys.argv) > 2 else "build/release/samples/vplkit"
    if not os.path.isdir(REFERENCE):
        raise SystemExit(f"cycles_direct: {REFERENCE} not found (../shared beside the repository)")
    os.makedirs(out, exist_ok=True)
    layers = {}
    for variant, scene in write_scene_copies(out).items():
        exr = os.path.join(out, f"direct-{variant}.exr")
        subprocess.run([vplkit, "render", "--scene", scene, "--camera", "0", "--width", "160", "--height", "90",
                        "--brdf", "lambert", "--method", "direct", "--out", os.path.join(out, f"direct-{variant}.png"),
                        "--out-hdr", exr], check=True, stdout=subprocess.DEVNULL)
        layers[variant] = read_vplkit_exr(exr)
    width, height, passes = read_exr(f"{REFERENCE}/b1/DiffDir.exr")
    cycles = np.array(passes["G"]).reshape(height, width)
    mapped, unmapped = layers["mapped"], layers["unmapped"]
    kit = mapped["direct.G"]
    n = np.stack([mapped[f"normal.{c}"] for c in "XYZ"], -1)
    ns = np.stack([unmapped[f"normal.{c}"] for c in "XYZ"], -1)

    forward, up, yfov, to_sun = camera_and_sun()
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    t = np.tan(yfov / 2)
    sx = ((np.arange(width) + 0.5) / width * 2 - 1) * t * width / height
    sy = (1 - (np.arange(height) + 0.5) / height * 2) * t
    ray = forward + right * sx[None, :, None] + up * sy[:, None, None]
    to_viewer = -ray / np.linalg.norm(ray, axis=-1, keepdims=True)

    # The kit's visibility x sun irradiance / pi, per pixel: its radiance over its own cosine.
    cosine = np.maximum(dot(n, to_sun), 0)
    unshadowed = np.where(cosine > 1e-4, kit / np.maximum(cosine, 1e-4), 0)
    wi = np.broadcast_to(to_sun, n.shape)
    bumped = unshadowed * cosine * bump_shadowing(ns, n, wi)
    bent = ensure_valid_reflection(ns, to_viewer, n)
    bent_and_bumped = unshadowed * np.maximum(dot(bent, to_sun), 0) * bump_shadowing(ns, bent, wi)

    lit = (cycles > 0.05 * cycles.mean()) & (kit > 0.05 * kit.mean())
    print(f"vplkit direct light / Cycles' DiffDir on Sponza-sun, white materials, {lit.sum()} pixels both light:")
    report("vplkit as it renders", kit, cycles, lit)
    report("with Cycles' bump shadowing", bumped, cycles, lit)
    report("with bump shadowing and ensure_valid_reflection", bent_and_bumped, cycles, lit)


if __name__ == "__main__":
    main()
