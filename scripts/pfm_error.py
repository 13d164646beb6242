#!/usr/bin/env python3
"""Relative RMSE of linear PFM images against a reference: sqrt(mean((a - ref)^2)) / mean(ref),
over all pixels and channels. A stopgap until the kit's own error metrics land.

usage: scripts/pfm_error.py REFERENCE.pfm IMAGE.pfm...
"""
import math
import struct
import sys


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        if kind not in (b"PF", b"Pf"):
            raise SystemExit(f"{path}: not a PFM file")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        count = width * height * channels
        data = f.read(4 * count)
        if len(data) != 4 * count:
            raise SystemExit(f"{path}: truncated")
        values = struct.unpack(("<" if scale < 0 else ">") + "f" * count, data)
        return width, height, values


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    rw, rh, ref = read_pfm(sys.argv[1])
    mean_ref = sum(ref) / len(ref)
    if not mean_ref > 0:
        raise SystemExit(f"{sys.argv[1]}: the reference is black")
    for path in sys.argv[2:]:
        w, h, img = read_pfm(path)
        if (w, h) != (rw, rh):
            raise SystemExit(f"{path}: {w}x{h}, the reference is {rw}x{rh}")
        rmse = math.sqrt(sum((a - b) ** 2 for a, b in zip(img, ref)) / len(ref))
        mean = sum(img) / len(img)
        print(f"{path}: relative RMSE {rmse / mean_ref:.4f}, mean {mean / mean_ref:.4f} of the reference's")


if __name__ == "__main__":
    main()
