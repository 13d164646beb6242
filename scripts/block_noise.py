#!/usr/bin/env python3
"""The block error a sampled method is expected to leave after N frames, from all its frames:
one draw of N frames (what scripts/pfm_residue.py reports) is a poor yardstick where a few rare,
heavy samples hold most of the variance (Sponza-lite's glossy floor: the largest 1% of rtslc's
per-frame block deviations over 1000 frames hold 2/3 of their variance; the ratio of two
methods' 64-frame block errors then spans 0.7-1.6 between draws of the same two estimators).

usage: scripts/block_noise.py --direct DIRECT.pfm --exact EXACT.pfm [--block K] [--frames N,N...]
                              NAME=FRAME_DIR...

For each FRAME_DIR (every frame_NNNN.pfm in it) and each N, prints, over exact's image mean:
  windows   the RMS over the disjoint windows of N frames of each window's K x K block error
            (as pfm_residue.py's block; the windows' count in brackets);
  variance  sqrt(mean over blocks and channels of the per-frame variance / N): the noise part of
            that expectation (equal to `windows` for an unbiased method, up to the spread).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pfm_residue  # noqa: E402


def main():
    w, h, direct, exact, k, counts, dirs = pfm_residue.read_inputs(__doc__)
    mean_ref = sum(exact) / len(exact)
    reference = pfm_residue.block_means(exact, w, h, k)
    print(f"{w}x{h}, {k}x{k} blocks, expected block error after N frames (over exact's image mean)")
    for entry in dirs:
        name, _, folder = entry.rpartition("=")
        name = name or folder
        frames = []
        while os.path.exists(os.path.join(folder, f"frame_{len(frames):04d}.pfm")):
            fw, fh, img = pfm_residue.read_pfm(os.path.join(folder, f"frame_{len(frames):04d}.pfm"))
            if (fw, fh) != (w, h):
                raise SystemExit(f"{folder}: frame {len(frames)} is {fw}x{fh}, expected {w}x{h}")
            frames.append(pfm_residue.block_means([a - d for a, d in zip(img, direct)], w, h, k))
        n = len(frames)
        if n < 2:
            print(f"{name}: fewer than 2 frames in {folder}")
            continue
        mean = [sum(f[i] for f in frames) / n for i in range(len(reference))]
        variance = sum(sum((f[i] - mean[i]) ** 2 for f in frames) / (n - 1) for i in range(len(reference)))
        variance /= len(reference)
        for count in counts:
            windows = n // count
            if windows == 0:
                print(f"{name:18s} {count:4d} frames: only {n} frames")
                continue
            squares = 0.0
            for wdx in range(windows):
                part = frames[wdx * count:(wdx + 1) * count]
                squares += sum((sum(f[i] for f in part) / count - reference[i]) ** 2
                               for i in range(len(reference))) / len(reference)
            print(f"{name:18s} {count:4d} frames: windows {math.sqrt(squares / windows) / mean_ref:.4f} "
                  f"[{windows}], variance {math.sqrt(variance / count) / mean_ref:.4f}")


if __name__ == "__main__":
    main()
