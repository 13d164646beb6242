#!/usr/bin/env python3
"""vplkit's one-bounce indirect / direct ratio against Blender Cycles' (../shared/reference).

usage: scripts/cycles_ratio.py REFERENCE_DIR DIRECT.pfm INDIRECT.pfm [DIRECT.pfm INDIRECT.pfm ...]

REFERENCE_DIR holds Cycles' DiffDir.exr, DiffInd.exr and DiffCol.exr (uncompressed single-part
scanline float OpenEXR, channels B,G,R; see ../shared/reference/README.md). Several vplkit
renders (other seeds: independent VPL sets) are averaged pixel by pixel first: `exact` over
one VPL set is an unbiased but noisy estimate per pixel. Cycles' passes are irradiance / pi
without the albedo; vplkit's direct and indirect radiance carry the albedo, so they are divided
by DiffCol first. Only pixels whose albedo is at least 0.02 in every channel count, for both
renderers (dividing by a darker albedo only amplifies noise). Both are then measured as the
reference's ratio_map.txt is: channel means; the ratio of the means over those pixels, and the
median per-pixel ratio (p10, p90) over those whose direct light is above 5% of its mean.

The median of a noisy per-pixel ratio is biased low: a pixel's VPL sum is right-skewed (most
VPL sets hold fewer than their share of the VPLs that light it, a few hold many more), so its
median lies below its mean: on Sponza-sun by 66% at 573 VPLs and about 30% at 9,000. Also
printed, linear in vplkit's indirect and so unbiased at any VPL count: over Cycles' median
pixels, the sum of vplkit's per-pixel ratio x Cycles' direct over the sum of Cycles' indirect
("ratio on Cycles' direct"), and vplkit's direct and indirect radiance over Cycles' (albedo x
pass), all pixels. And over the pixels both renderers light (direct above 5% of its mean in
both): the two median ratios, and the median of the per-pixel quotient of vplkit's ratio by
Cycles', which a rank shift among pixels of very different ratios cannot move.
"""
import math
import struct
import sys

sys.path.insert(0, __import__("os").path.dirname(__file__))
from pfm_error import read_pfm  # noqa: E402


def read_exr(path):
    """(width, height, {channel: [float]}) rows top to bottom, of an uncompressed float EXR."""
    with open(path, "rb") as f:
        data = f.read()
    if struct.unpack_from("<I", data, 0)[0] != 20000630:
        raise SystemExit(f"{path}: not an OpenEXR file")
    pos, channels, window, compression = 8, [], None, None
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        end2 = data.index(b"\0", end + 1)
        kind = data[end + 1:end2].decode()
        size = struct.unpack_from("<i", data, end2 + 1)[0]
        value = data[end2 + 5:end2 + 5 + size]
        if name == "channels":
            p = 0
            while value[p] != 0:
                e = value.index(b"\0", p)
                pixel_type = struct.unpack_from("<i", value, e + 1)[0]
                channels.append((value[p:e].decode(), pixel_type))
                p = e + 1 + 16
        elif name == "dataWindow":
            window = struct.unpack("<4i", value)
        elif name == "compression":
            compression = value[0]
        pos = end2 + 5 + size
    pos += 1
    if compression != 0 or any(t != 2 for _, t in channels):
        raise SystemExit(f"{path}: only uncompressed 32-bit float EXR is read here")
    x0, y0, x1, y1 = window
    width, height = x1 - x0 + 1, y1 - y0 + 1
    offsets = struct.unpack_from(f"<{height}Q", data, pos)
    out = {name: [0.0] * (width * height) for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        row = y - y0
        p = offset + 8
        for name, _ in channels:  # stored in alphabetical order, as the header lists them
            values = struct.unpack_from(f"<{width}f", data, p)
            out[name][row * width:(row + 1) * width] = values
            p += 4 * width
    return width, height, out


def stats(direct, indirect):
    """ratio of means, median ratio, p10, p90, pixel count over pixels with direct > 5% mean."""
    valid = [i for i in range(len(direct)) if direct[i] is not None and indirect[i] is not None]
    mean_direct = sum(direct[i] for i in valid) / len(valid)
    chosen = [i for i in valid if direct[i] > 0.05 * mean_direct]
    ratio_of_means = sum(indirect[i] for i in valid) / sum(direct[i] for i in valid)
    ratios = sorted(indirect[i] / direct[i] for i in chosen)

    def quantile(q):
        return ratios[min(len(ratios) - 1, int(q * len(ratios)))]

    return ratio_of_means, quantile(0.5), quantile(0.1), quantile(0.9), len(chosen)


def read_image(path):
    """(width, height, rgb values) of a PFM, rows bottom to top (pfm_error.read_pfm, any version)."""
    image = read_pfm(path)
    return image[0], image[1], image[-1]


def main():
    if len(sys.argv) < 4 or len(sys.argv) % 2 != 0:
        raise SystemExit(__doc__)
    ref = sys.argv[1]
    pairs = list(zip(sys.argv[2::2], sys.argv[3::2]))
    w, h, ddir = read_exr(f"{ref}/DiffDir.exr")
    _, _, dind = read_exr(f"{ref}/DiffInd.exr")
    _, _, dcol = read_exr(f"{ref}/DiffCol.exr")
    vdir, vind = None, None
    for direct_pfm, indirect_pfm in pairs:
        vw, vh, d = read_image(direct_pfm)
        _, _, i = read_image(indirect_pfm)
        if (vw, vh) != (w, h):
            raise SystemExit(f"vplkit's images are {vw}x{vh}, the reference {w}x{h}")
        vdir = list(d) if vdir is None else [a + b for a, b in zip(vdir, d)]
        vind = list(i) if vind is None else [a + b for a, b in zip(vind, i)]
    vdir = [v / len(pairs) for v in vdir]
    vind = [v / len(pairs) for v in vind]
    n = w * h
    cycles_dir = [(ddir["R"][i] + ddir["G"][i] + ddir["B"][i]) / 3 for i in range(n)]
    cycles_ind = [(dind["R"][i] + dind["G"][i] + dind["B"][i]) / 3 for i in range(n)]
    ours_dir, ours_ind = [None] * n, [None] * n
    for i in range(n):
        # PFM rows run bottom to top; the EXR's top to bottom.
        row, col = divmod(i, w)
        j = (h - 1 - row) * w + col
        albedo = (dcol["R"][i], dcol["G"][i], dcol["B"][i])
        if min(albedo) < 0.02:
            continue
        ours_dir[i] = sum(vdir[3 * j + c] / albedo[c] for c in range(3)) / 3
        ours_ind[i] = sum(vind[3 * j + c] / albedo[c] for c in range(3)) / 3
    cycles_dir = [v if ours_dir[i] is not None else None for i, v in enumerate(cycles_dir)]
    cycles_ind = [v if ours_ind[i] is not None else None for i, v in enumerate(cycles_ind)]
    c = stats(cycles_dir, cycles_ind)
    o = stats(ours_dir, ours_ind)
    print(f"vplkit: {len(pairs)} render(s) averaged")
    for name, s in (("cycles", c), ("vplkit", o)):
        print(f"{name}: ratio of means {s[0]:.4f}, median ratio {s[1]:.4f} (p10 {s[2]:.4f}, p90 {s[3]:.4f}), "
              f"{s[4]} pixels")
    print(f"vplkit / cycles: ratio of means {o[0] / c[0] - 1:+.1%}, median ratio {o[1] / c[1] - 1:+.1%}")
    # Linear in vplkit's indirect: its per-pixel ratio on Cycles' direct, over Cycles' median pixels.
    valid = [i for i in range(n) if cycles_dir[i] is not None]
    mean_direct = sum(cycles_dir[i] for i in valid) / len(valid)
    chosen = [i for i in valid if cycles_dir[i] > 0.05 * mean_direct and ours_dir[i] > 0.0]
    on_cycles = sum(cycles_dir[i] * ours_ind[i] / ours_dir[i] for i in chosen) / sum(cycles_ind[i] for i in chosen)
    print(f"vplkit's ratio on Cycles' direct, {len(chosen)} pixels: vplkit / cycles {on_cycles - 1:+.1%}")
    # The same pixels for both: those whose direct light is above 5% of its mean in both images
    # (each renderer's own set differs by the shadow edges the two draw differently, and the
    # ratios' distribution is steep at its median: 0.032 at p40, 0.088 at p60 in Cycles').
    ours_mean = sum(ours_dir[i] for i in valid) / len(valid)
    common = [i for i in chosen if ours_dir[i] > 0.05 * ours_mean]
    theirs_r = sorted(cycles_ind[i] / cycles_dir[i] for i in common)
    ours_r = sorted(ours_ind[i] / ours_dir[i] for i in common)
    per_pixel = sorted((ours_ind[i] / ours_dir[i]) / (cycles_ind[i] / cycles_dir[i]) for i in common
                       if cycles_ind[i] > 0.0)
    mid = lambda v, q=0.5: v[min(len(v) - 1, int(q * len(v)))]  # noqa: E731
    print(f"both lit, {len(common)} pixels: median ratio cycles {mid(theirs_r):.4f}, vplkit {mid(ours_r):.4f} "
          f"({mid(ours_r) / mid(theirs_r) - 1:+.1%}); per pixel vplkit / cycles: median {mid(per_pixel) - 1:+.1%} "
          f"(p25 {mid(per_pixel, 0.25) - 1:+.1%}, p75 {mid(per_pixel, 0.75) - 1:+.1%})")
    flip = lambda v, i, c: v[3 * ((h - 1 - i // w) * w + i % w) + c]  # noqa: E731
    for name, ours, theirs in (("direct", vdir, ddir), ("indirect", vind, dind)):
        sum_ours = sum(flip(ours, i, c) for i in range(n) for c in range(3))
        sum_theirs = sum(dcol[ch][i] * theirs[ch][i] for i in range(n) for ch in "RGB")
        print(f"{name} radiance (albedo x pass for Cycles), all pixels: vplkit / cycles {sum_ours / sum_theirs - 1:+.1%}")
    if not (math.isfinite(o[0]) and math.isfinite(o[1])):
        raise SystemExit("vplkit's ratios are not finite")


if __name__ == "__main__":
    main()
