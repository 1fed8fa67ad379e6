#!/usr/bin/python3
"""Mortar contact's cost (docs/measurements.md, "Mortar contact's cost"): CPU and wall seconds of `stoss run` on
scenes whose contact pair is switched to `"discretization": "mortar"`, and the Hertz rows of the mortar runs.

    /usr/bin/python3 bench/mortar_cost.py [--stoss build/stoss] [--cases patch,patch_dynamic,seed,hertz2,hertz]
                                          [--repeat 3] [--hertz-meshes medium] [--out DIR]

Cases (one run at a time):
  patch          tests/physics/test_mortar_scenes.cpp's stacked blocks, static (2 steps), written out here
  patch_dynamic  the same under energy_momentum, t in [0, 0.2] (10 steps)
  seed           api/examples/hollow_ball_plate.json with the pair mortar, t in [0, 0.4] (40 steps; contact from 0.3)
  hertz2         api/examples/hertz_indentation.json (coarse mesh) with the pair mortar, its first 2 load steps
  hertz          the same, all 8 load steps
CPU = user + sys of the child (os.wait4), wall = the child's elapsed time; the median of --repeat runs.
--hertz-meshes also runs the Hertz example with mortar on those meshes (bench/hertz_indentation.py makes the
medium, fine and graded ones with Gmsh) and prints F against Hertz (H2) at delta/R = 0.5, 1, 1.5, 2 %, the contact
radius error in element edges, as bench/hertz_indentation.py does, and the peak nodal contact_pressure at 2 %
against Hertz's p0 = 2 E* a / (pi R).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import hertz_indentation as hertz  # noqa: E402  (mesh_file, effective_modulus, top_edge)

EXAMPLES = os.path.join(ROOT, "api", "examples")


def patch_scene(scheme):
    """The stacked blocks of tests/physics/test_mortar_scenes.cpp (mortar_scene(scheme, ""))."""
    statics = scheme == "static"
    material = {"youngs_modulus": 1000, "poisson_ratio": 0.3, "density": 1}

    def block(name, low, high, n, layers):
        return {"name": name, "mesh": {"box": {"min": low, "max": high, "divisions": [n, n, layers]}},
                "material": material}
    return {"format": "stoss-scene/1",
            "bodies": [block("lower", [0, 0, 0], [1, 1, 0.5], 3, 1), block("upper", [0.2, 0.2, 0.5], [0.8, 0.8, 1], 2, 2)],
            "boundary": [{"surface": "lower/bottom"}, {"surface": "upper/xmin", "fix": "x"},
                         {"surface": "upper/ymin", "fix": "y"}],
            "loads": [{"surface": "upper/top", "pressure": 10, "amplitude": [[0, 0], [1 if statics else 0.1, 1]]}],
            "contact": [{"slave": "upper/boundary", "master": ["lower/top", "lower/xmax"], "discretization": "mortar"}],
            "time": {"scheme": scheme, "step": 0.5 if statics else 0.02, "end": 1.0 if statics else 0.2}}


def example(name, end=None, mesh=None, workdir=None):
    scene = json.load(open(os.path.join(EXAMPLES, name)))
    for body in scene["bodies"]:
        if "file" in body["mesh"]:
            body["mesh"]["file"] = mesh or os.path.join(EXAMPLES, body["mesh"]["file"])
    scene["contact"][0]["discretization"] = "mortar"
    if end is not None:
        scene["time"]["end"] = end
    if mesh is not None:
        scene["solver"] = {"linear": "direct"}  # as bench/hertz_indentation.py
    return scene


def run(stoss, scene, workdir, name):
    path = os.path.join(workdir, f"{name}.json")
    json.dump(scene, open(path, "w"), indent=1)
    out = os.path.join(workdir, name)
    start = time.monotonic()
    child = subprocess.Popen([stoss, "run", path, "-o", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        sys.exit(f"{name}: stoss run failed ({status}): {child.stderr.read().decode()}")
    return usage.ru_utime + usage.ru_stime, wall, out


def hertz_rows(scene, out):
    """F / F_Hertz - 1 at 0.5, 1, 1.5, 2 % and max |a - sqrt(R delta)| / h0 over 0.5 ... 2 %."""
    f = h5py.File(os.path.join(out, "result.h5"), "r")
    s, depth, e_star = f["series"], -scene["boundary"][0]["displacement"][2], hertz.effective_modulus(scene)
    h0, rows, a_error = hertz.top_edge(f), {}, 0
    for n in range(1, len(s["time"])):
        delta = depth * s["time"][n]
        force = -4 * s["contact_force"][n, 0, 2]
        a = (4 * s["contact_area"][n, 0] / 3.141592653589793) ** 0.5
        rows[round(100 * delta, 2)] = force / (4 / 3 * e_star * delta ** 1.5) - 1
        if delta >= 0.005 - 1e-12:
            a_error = max(a_error, abs(a - delta ** 0.5) / h0)
    iterations = int(sum(s["newton_iterations"][1:]))
    # the largest nodal contact_pressure of the last frame against Hertz's p0 = 2 E* a / (pi R) there (R = 1)
    last = f["frames"][max((k for k in f["frames"] if k.isdigit()), key=int)]
    peak = last["contact_pressure"][:].max() / (2 * e_star * depth ** 0.5 / 3.141592653589793) - 1
    return (" | ".join(f"{100 * rows[d]:+.2f} %" for d in (0.5, 1.0, 1.5, 2.0))
            + f" | {a_error:.2f} | {100 * peak:+.2f} % | {iterations} | {len(f['mesh/hex8'])} hex8")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--stoss", default=os.path.join(ROOT, "build", "stoss"))
    p.add_argument("--cases", default="patch,patch_dynamic,seed,hertz2,hertz")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--hertz-meshes", default="", help="e.g. medium: the Hertz example with mortar on these meshes")
    p.add_argument("--out", help="keep the runs here (default: a temporary directory)")
    args = p.parse_args()
    workdir = args.out or tempfile.mkdtemp(prefix="mortar_cost_")
    os.makedirs(workdir, exist_ok=True)
    scenes = {"patch": patch_scene("static"), "patch_dynamic": patch_scene("energy_momentum"), "seed": example("hollow_ball_plate.json", end=0.4),
              "hertz2": example("hertz_indentation.json", end=0.25), "hertz": example("hertz_indentation.json")}
    print("| case | CPU s (median) | wall s (median) | runs |")
    print("|---|---|---|---|")
    for case in filter(None, args.cases.split(",")):
        runs = [run(args.stoss, scenes[case], workdir, case)[:2] for _ in range(args.repeat)]
        print(f"| {case} | {statistics.median(r[0] for r in runs):.2f} | {statistics.median(r[1] for r in runs):.2f} "
              f"| {args.repeat} |", flush=True)
    for mesh in filter(None, args.hertz_meshes.split(",")):
        scene = example("hertz_indentation.json", mesh=hertz.mesh_file(mesh, workdir))
        cpu, wall, out = run(args.stoss, scene, workdir, f"hertz_{mesh}")
        print(f"hertz {mesh}, mortar: F error 0.5 / 1 / 1.5 / 2 % | a error (h0) | peak pressure | Newton its | size: "
              f"{hertz_rows(scene, out)}; {cpu:.1f} s CPU, {wall:.1f} s wall")


if __name__ == "__main__":
    main()
