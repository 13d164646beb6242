#!/usr/bin/env python3
"""Errors of linear PFM images against a reference (pure Python, no numpy):
  relative RMSE   sqrt(mean((a - ref)^2)) / mean(ref), over all pixels and channels;
  mean            the image's mean over the reference's;
  block error     (with --block K) the same relative RMSE after averaging both images over K x K
                  pixel blocks (partial blocks at the right and bottom edges left out): the
                  low-frequency error that no further blur removes, so a converging estimate's
                  falls like 1/sqrt(frames) and a bias's stays;
  brightest       the image's brightest pixel (luminance, Rec. 709) over the reference's.

usage: scripts/pfm_error.py [--block K] REFERENCE.pfm IMAGE.pfm...
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
        return width, height, channels, values


def luminances(channels, values):
    if channels == 1:
        return list(values)
    return [0.2126 * values[i] + 0.7152 * values[i + 1] + 0.0722 * values[i + 2] for i in range(0, len(values), 3)]


def block_means(width, height, channels, values, k):
    """Per K x K block and channel, the mean (full blocks only)."""
    out = []
    for by in range(height // k):
        for bx in range(width // k):
            for c in range(channels):
                s = 0.0
                for y in range(by * k, by * k + k):
                    row = (y * width) * channels
                    for x in range(bx * k, bx * k + k):
                        s += values[row + x * channels + c]
                out.append(s / (k * k))
    return out


def relative_rmse(image, reference):
    mean_ref = sum(reference) / len(reference)
    return math.sqrt(sum((a - b) ** 2 for a, b in zip(image, reference)) / len(reference)) / mean_ref


def main():
    args = sys.argv[1:]
    block = 0
    if args[:1] == ["--block"]:
        if len(args) < 2 or not args[1].isdigit() or int(args[1]) < 1:
            raise SystemExit("--block expects a whole number >= 1")
        block = int(args[1])
        args = args[2:]
    if len(args) < 2:
        raise SystemExit(__doc__)
    rw, rh, rc, ref = read_pfm(args[0])
    mean_ref = sum(ref) / len(ref)
    if not mean_ref > 0:
        raise SystemExit(f"{args[0]}: the reference is black")
    ref_blocks = block_means(rw, rh, rc, ref, block) if block else None
    ref_brightest = max(luminances(rc, ref))
    for path in args[1:]:
        w, h, c, img = read_pfm(path)
        if (w, h, c) != (rw, rh, rc):
            raise SystemExit(f"{path}: {w}x{h}x{c}, the reference is {rw}x{rh}x{rc}")
        line = f"{path}: relative RMSE {relative_rmse(img, ref):.4f}, mean {sum(img) / len(img) / mean_ref:.4f} of the reference's"
        if block:
            line += f", {block}x{block}-block error {relative_rmse(block_means(w, h, c, img, block), ref_blocks):.4f}"
            line += f", brightest pixel {max(luminances(c, img)) / ref_brightest:.3f} of the reference's"
        print(line)


if __name__ == "__main__":
    main()
