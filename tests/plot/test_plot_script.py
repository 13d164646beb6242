#!/usr/bin/env python3
"""scripts/plot.py on small synthetic inputs: each kind writes its PNGs (a PNG signature, a
header of a plausible size, more than a blank picture's bytes), and bad input (a missing file or
folder, a malformed CSV or JSON) exits 1 with one line naming the file and the problem, leaving
no picture behind.

usage: test_plot_script.py PLOT_SCRIPT WORK_DIR CASE   (CASE: see CASES at the end)
"""

import json
import os
import shutil
import struct
import subprocess
import sys

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# A 960x600 plot with axes, text and lines compresses to tens of kilobytes; an empty canvas to
# a few.
MIN_PNG_BYTES = 12000


class Failed(Exception):
    pass


def run(script, *args):
    done = subprocess.run([sys.executable, script, *args], capture_output=True, text=True, timeout=120)
    return done.returncode, done.stdout, done.stderr


def check_png(path):
    if not os.path.isfile(path):
        raise Failed(f"{path} was not written")
    with open(path, "rb") as f:
        data = f.read()
    if not data.startswith(PNG_SIGNATURE) or data[12:16] != b"IHDR":
        raise Failed(f"{path}: not a PNG (signature or IHDR chunk missing)")
    width, height = struct.unpack(">II", data[16:24])
    if not (300 <= width <= 4000 and 200 <= height <= 4000):
        raise Failed(f"{path}: {width}x{height} pixels, not a plot's size")
    if len(data) < MIN_PNG_BYTES:
        raise Failed(f"{path}: only {len(data)} bytes, a nearly blank picture")


def expect_pictures(script, folder, kind, names, *extra):
    code, out, err = run(script, kind, folder, *extra)
    if code != 0:
        raise Failed(f"plot.py {kind} exited {code}:\n{out}{err}")
    for name in names:
        path = os.path.join(folder, name)
        check_png(path)
        if f"wrote {path}\n" not in out:
            raise Failed(f"plot.py {kind} did not say it wrote {path}:\n{out}")
    leftovers = [f for f in os.listdir(folder) if ".tmp" in f]
    if leftovers:
        raise Failed(f"temporary files left behind: {leftovers}")


def expect_refusal(script, folder, kind, message, *extra):
    before = set(os.listdir(folder)) if os.path.isdir(folder) else set()
    code, out, err = run(script, kind, folder, *extra)
    if code != 1:
        raise Failed(f"plot.py {kind} on bad input exited {code}, expected 1:\n{out}{err}")
    if message not in err or "Traceback" in err:
        raise Failed(f"plot.py {kind}: expected one line with '{message}', got:\n{err}")
    after = set(os.listdir(folder)) if os.path.isdir(folder) else set()
    if after - before:
        raise Failed(f"plot.py {kind} on bad input left {sorted(after - before)}")


def gi_point(method, sweep, spp, frame_ms, rmse, **more):
    point = {"method": method, "sweep": sweep, "label": f"{method} {sweep} {spp}", "spp": spp, "block": 8,
             "vpls": 256, "frame_ms": frame_ms, "gi_ms": frame_ms / 2, "trees_ms": 1.0, "vpls_ms": 2.0,
             "rmse": rmse, "levels_per_traversal": 5.0 + spp / 8}
    point.update(more)
    return point


def bench_gi_run():
    points = [gi_point("rtslc", "spp", s, 10.0 * s, 0.2 / s ** 0.5) for s in (1, 4, 8)]
    points += [gi_point("hybrid", "spp", s, 8.0 * s, 0.18 / s ** 0.5) for s in (1, 4, 8)]
    points += [gi_point("hybrid", "block", 8, 70.0, 0.05, block=4),  # on the front, not on a line
               gi_point("hybrid", "resolution", 4, 20.0, 0.11),
               gi_point("hybrid", "vpls", 8, 90.0, 0.04, vpls=1024),  # another budget: not compared
               gi_point("flc", "navg", 0, 3.0, 0.15),
               gi_point("flc", "navg", 0, 6.0, None)]  # NaN, written as null: left out
    curves = [{"name": "rtslc", "quality_sweep": "spp", "sweeps": ["spp", "block"], "samples": True},
              {"name": "hybrid", "quality_sweep": "spp", "sweeps": ["spp", "block", "resolution", "vpls"],
               "samples": True},
              {"name": "flc", "quality_sweep": "navg", "sweeps": ["navg"], "samples": False}]
    return {"scene": "cornell", "width": 64, "height": 48, "curves": curves, "vpl_count_curve": "hybrid",
            "pareto_front": [9, 7, 4, 5, 6], "points": points,
            "method_fronts": {"rtslc": [0, 1, 2], "hybrid": [3, 7, 4, 5, 6], "flc": [9]}}


def write(folder, name, text):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "w", encoding="utf-8") as f:
        f.write(text)


def case_bench_gi(script, work):
    write(work, "points.json", json.dumps(bench_gi_run()))
    expect_pictures(script, work, "bench-gi", ["rmse_vs_time.png", "rmse_vs_gi_time.png", "levels.png",
                                               "block_size_rmse.png", "block_size_time.png",
                                               "vpl_count_build_time.png"])


def case_bench_direct(script, work):
    rows = ["scene,device,width,height,sampler,spp,direct_ms,relative_rmse"]
    for sampler, cost in [("flat", 1.0), ("tree", 1.5), ("tree2", 1.7)]:
        rows += [f'many-lights,"llvmpipe (CPU)",32,32,{sampler},{s},{cost * s},{0.5 / (cost * s) ** 0.5}'
                 for s in (1, 2, 4, 8)]
    write(work, "points.csv", "\n".join(rows) + "\n")
    expect_pictures(script, work, "bench-direct", ["rmse_vs_time.png", "rmse_vs_spp.png"])


def case_sequence(script, work):
    rows = ["frame,mean_abs_error,mean_abs_error_change", "0,0.031,"]
    rows += [f"{f},{0.03 + 0.002 * (f % 3)},{0.004 + 0.001 * (f % 2)}" for f in range(1, 7)]
    write(work, "metrics.csv", "\n".join(rows) + "\n")
    expect_pictures(script, work, "sequence", ["metrics.png"], "--scene", "/abs/path/to/sponza.gltf")


def case_missing_file(script, work):
    os.makedirs(work, exist_ok=True)
    expect_refusal(script, work, "sequence", "metrics.csv: file not found", "--scene", "cornell")
    expect_refusal(script, work, "bench-gi", "points.json: file not found")
    expect_refusal(script, os.path.join(work, "nosuch"), "bench-direct", "nosuch: no such folder")


def case_malformed_csv(script, work):
    write(work, "metrics.csv", "frame,mean_abs_error,mean_abs_error_change\n0,0.1,\n1,abc,0.01\n")
    expect_refusal(script, work, "sequence", "metrics.csv:3: column mean_abs_error: 'abc' is not a number",
                   "--scene", "cornell")
    write(work, "metrics.csv", "frame,mean_abs_error,mean_abs_error_change\n0,0.1\n")
    expect_refusal(script, work, "sequence", "metrics.csv:2: 3 columns expected", "--scene", "cornell")
    write(work, "metrics.csv", "frame;error\n0;0.1\n")
    expect_refusal(script, work, "sequence", "not the expected CSV: no column", "--scene", "cornell")
    write(work, "points.csv", "scene,device,width,height,sampler,spp,direct_ms,relative_rmse\n")
    expect_refusal(script, work, "bench-direct", "points.csv: no data rows")


def case_malformed_json(script, work):
    text = json.dumps(bench_gi_run())
    write(work, "points.json", text[: len(text) // 2])
    expect_refusal(script, work, "bench-gi", "points.json: not valid JSON")
    broken = bench_gi_run()
    broken["pareto_front"].append(99)
    write(work, "points.json", json.dumps(broken))
    expect_refusal(script, work, "bench-gi", "pareto_front holds 99, not the index of a point")
    broken = bench_gi_run()
    broken["method_fronts"]["hybrid"].append(99)
    write(work, "points.json", json.dumps(broken))
    expect_refusal(script, work, "bench-gi", "method_fronts['hybrid'] is not a list of indices of points")
    broken = bench_gi_run()
    del broken["points"][0]["rmse"]
    write(work, "points.json", json.dumps(broken))
    expect_refusal(script, work, "bench-gi", "point 0 has no rmse")


CASES = {"bench-gi": case_bench_gi, "bench-direct": case_bench_direct, "sequence": case_sequence,
         "missing-file": case_missing_file, "malformed-csv": case_malformed_csv,
         "malformed-json": case_malformed_json}


def main():
    script, work, case = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    try:
        CASES[case](script, work)
    except Failed as e:
        print(f"FAILED: {e}", file=sys.stderr)
        return 1
    print(f"ok: {case}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
