#!/usr/bin/env python3
"""The converged residue of a sampled method: the mean of its first N raw frames' indirect light
against the exact indirect light over the same VPLs (DESIGN.md, Tests, Convergence).

usage: scripts/pfm_residue.py --direct DIRECT.pfm --exact EXACT.pfm [--block K] [--frames N,N...]
                              NAME=FRAME_DIR...

Every PFM is linear radiance (`vplkit sequence --pfm`: direct + indirect); the indirect light is
radiance - DIRECT.pfm (a `--method direct` frame: the direct light is the same in every frame).
For each FRAME_DIR (frame_0000.pfm, ...) and each N, prints:
  mean    the image mean of the averaged indirect light / exact's (all pixels and channels);
  block   relative RMSE of K x K block means: sqrt(mean over blocks and channels of
          (block mean - exact's)^2) / exact's image mean (the noise left after N frames plus the
          bias: a bias does not fall with N);
  pixel   the same per pixel;
  noise   the block error that the frames' own spread explains: half the RMS block difference
          between the even and the odd frames' means (each mean of N/2 frames; their difference
          has 4x the variance of the N-frame mean), over exact's image mean;
  bias    sqrt(max(block^2 - noise^2, 0)): what more frames would not remove;
  max     the brightest pixel's luminance / exact's brightest, and where it is.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pfm_error  # noqa: E402


def read_pfm(path):
    """(width, height, RGB values) of a 3-channel PFM (pfm_error.read_pfm, whichever tuple it returns)."""
    r = pfm_error.read_pfm(path)
    if len(r[-1]) != 3 * r[0] * r[1]:
        raise SystemExit(f"{path}: not an RGB PFM")
    return r[0], r[1], r[-1]


def luminance(img, i):
    return 0.2126 * img[3 * i] + 0.7152 * img[3 * i + 1] + 0.0722 * img[3 * i + 2]


def block_means(img, w, h, k):
    bw, bh = (w + k - 1) // k, (h + k - 1) // k
    sums = [0.0] * (bw * bh * 3)
    counts = [0] * (bw * bh)
    for y in range(h):
        for x in range(w):
            b = (y // k) * bw + x // k
            counts[b] += 1
            for c in range(3):
                sums[3 * b + c] += img[3 * (y * w + x) + c]
    return [sums[i] / counts[i // 3] for i in range(len(sums))]


def measure(avg, exact, w, h, k):
    mean_ref = sum(exact) / len(exact)
    mean = sum(avg) / len(avg)
    ba, be = block_means(avg, w, h, k), block_means(exact, w, h, k)
    block = math.sqrt(sum((a - b) ** 2 for a, b in zip(ba, be)) / len(be)) / mean_ref
    pixel = math.sqrt(sum((a - b) ** 2 for a, b in zip(avg, exact)) / len(exact)) / mean_ref
    n = w * h
    brightest = max(range(n), key=lambda i: luminance(avg, i))
    ref_max = max(luminance(exact, i) for i in range(n))
    return mean / mean_ref, block, pixel, luminance(avg, brightest) / ref_max, (brightest % w, brightest // w)


def read_inputs(usage):
    """The command line both this script and block_noise.py take: (w, h, direct, exact's indirect,
    block size, frame counts, NAME=FRAME_DIR entries); `usage` is printed when it is incomplete."""
    args = sys.argv[1:]
    opts = {"--block": "6", "--frames": "64,256"}
    dirs = []
    while args:
        a = args.pop(0)
        if a in ("--direct", "--exact", "--block", "--frames"):
            opts[a] = args.pop(0)
        else:
            dirs.append(a)
    if "--direct" not in opts or "--exact" not in opts or not dirs:
        raise SystemExit(usage)
    w, h, direct = read_pfm(opts["--direct"])
    we, he, exact = read_pfm(opts["--exact"])
    if (we, he) != (w, h):
        raise SystemExit("--exact and --direct differ in size")
    exact = [a - d for a, d in zip(exact, direct)]
    k = int(opts["--block"])
    counts = sorted(int(n) for n in opts["--frames"].split(","))
    return w, h, direct, exact, k, counts, dirs


def main():
    w, h, direct, exact, k, counts, dirs = read_inputs(__doc__)
    print(f"{w}x{h}, {k}x{k} blocks; exact's indirect mean {sum(exact) / len(exact):.5g}")
    for entry in dirs:
        name, _, folder = entry.rpartition("=")
        name = name or folder
        total = [0.0] * len(exact)
        odd = [0.0] * len(exact)
        done = 0
        for n in counts:
            while done < n:
                path = os.path.join(folder, f"frame_{done:04d}.pfm")
                if not os.path.exists(path):
                    break
                fw, fh, img = read_pfm(path)
                if (fw, fh) != (w, h):
                    raise SystemExit(f"{path}: {fw}x{fh}, expected {w}x{h}")
                for i, (a, d) in enumerate(zip(img, direct)):
                    total[i] += a - d
                    if done % 2:
                        odd[i] += a - d
                done += 1
            if done < n:
                print(f"{name}: only {done} frames in {folder}")
                break
            avg = [t / n for t in total]
            mean, block, pixel, bright, where = measure(avg, exact, w, h, k)
            half = n // 2
            odd_mean = block_means([o / half for o in odd], w, h, k)
            even_mean = block_means([(t - o) / (n - half) for t, o in zip(total, odd)], w, h, k)
            mean_ref = sum(exact) / len(exact)
            noise = math.sqrt(sum((a - b) ** 2 for a, b in zip(odd_mean, even_mean)) / len(odd_mean)) / 2 / mean_ref
            bias = math.sqrt(max(block * block - noise * noise, 0.0))
            print(f"{name:18s} {n:4d} frames: mean {mean:.4f}, block {block:.4f} (noise {noise:.4f}, bias {bias:.4f}), "
                  f"pixel {pixel:.4f}, max {bright:.3f}x at {where}")


if __name__ == "__main__":
    main()
