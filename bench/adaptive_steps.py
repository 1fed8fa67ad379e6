#!/usr/bin/python3
"""Steps chosen by a tolerance, measured (issue 22 §2, docs/measurements.md "Steps chosen by a tolerance").

usage: adaptive_steps.py STOSS EXAMPLE [--scheme S] [--ref-step H] [--tol T ...] [--fixed H ...]

Runs api/examples/EXAMPLE.json with `stoss run` at a fixed reference step H (default: one eighth of the
example's time.step), then once per tolerance T (time.tolerance = T, first step the example's time.step)
and once per fixed step, and prints a Markdown row each: the final-position error (largest nodal distance
to the reference at the end time), the steps, the rejected tries, step_size max/min and the wall seconds.
Needs Debian's python3 with python3-h5py (deploy/packages.txt).
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(stoss, scene, work, label):
    path = os.path.join(work, label + ".json")
    with open(path, "w") as f:
        json.dump(scene, f)
    out = os.path.join(work, "out_" + label)
    t0 = time.monotonic()
    p = subprocess.run([stoss, "run", path, "-o", out], capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if p.returncode not in (0, 3):
        raise SystemExit(f"{label}: stoss run failed ({p.returncode}):\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    with h5py.File(os.path.join(out, "result.h5"), "r") as f:
        last = len(f["frames/time"]) - 1
        x = f[f"frames/{last}/position"][()]
        s = f["series"]
        h = s["step_size"][1:] if "step_size" in s else np.array([scene["time"]["step"]])
        rejected = int(s["rejected_steps"][()].sum()) if "rejected_steps" in s else 0
        steps = len(f["series/time"]) - 1
        t_end = f["series/time"][-1]
    return {"x": x, "steps": steps, "rejected": rejected, "ratio": h.max() / h.min(), "seconds": seconds,
            "t_end": t_end, "log": p.stdout}


def largest_distance(a, b):
    return float(np.max(np.linalg.norm((a - b).reshape(-1, 3), axis=1)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("stoss")
    parser.add_argument("example")
    parser.add_argument("--scheme")
    parser.add_argument("--ref-step", type=float)
    parser.add_argument("--tol", type=float, nargs="*", default=[])
    parser.add_argument("--fixed", type=float, nargs="*", default=[])
    a = parser.parse_args()
    base = json.load(open(os.path.join(ROOT, "api/examples", a.example + ".json")))
    if a.scheme:
        base["time"]["scheme"] = a.scheme
    base.setdefault("output", {})["every"] = 1000000  # the first and last frame only
    with tempfile.TemporaryDirectory() as work:
        ref_scene = json.loads(json.dumps(base))
        ref_scene["time"]["step"] = a.ref_step or base["time"]["step"] / 8
        ref = run(a.stoss, ref_scene, work, "reference")
        print(f"| {a.example} | {base['time']['scheme']} | reference h = {ref_scene['time']['step']} | | "
              f"{ref['steps']} | | | {ref['seconds']:.1f} |")
        runs = [(f"TOL = {tol:g}", {"tolerance": tol}, tol) for tol in a.tol]
        runs += [(f"h = {h:g}", {"step": h}, None) for h in a.fixed]
        for label, time_fields, tol in runs:
            scene = json.loads(json.dumps(base))
            scene["time"].update(time_fields)
            r = run(a.stoss, scene, work, label.replace(" ", "").replace("=", ""))
            e = largest_distance(r["x"], ref["x"])
            error = f"{e:.2e} ({e / tol:.2f} TOL)" if tol else f"{e:.2e}"
            print(f"| {a.example} | {base['time']['scheme']} | {label} | {error} | {r['steps']} | {r['rejected']} | "
                  f"{r['ratio']:.1f} | {r['seconds']:.1f} |", flush=True)

if __name__ == "__main__":
    main()
