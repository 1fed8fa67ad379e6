#!/usr/bin/python3
"""Where `solver.linear: auto` should switch from UMFPACK to PETSc GMRES + GAMG on a contact scene (issue 26 §3).

The seed example (api/examples/hollow_ball_plate.json) refined by a factor k: the hollow ball's `divisions` 6k and
`layers` 2k, the plate's divisions 16k × 16k × 2k (944 k³ hex8), the ball moved down to touch the plate after two
steps, so that every measured step has contact. Each size runs `--steps` steps with `direct` and with
`petsc_gamg`, alternating, `--rounds` times; the table gives the median CPU seconds per step (user + sys of the
whole process, from getrusage of the child: on a shared machine CPU time is steadier than wall time) and the
Newton iterations of the run.

    /usr/bin/python3 bench/linear_crossover.py [--stoss build/stoss] [--factors 1,1.5,2,2.5] [--steps 8]
                                               [--rounds 3] [--contact-free 8x3,10x3,12x4,14x5,16x5]

--contact-free DxL,... measures the scene without contact instead: api/examples/tumbling_sphere.json with the
hollow sphere's `divisions` D and `layers` L (6 D^2 L hex8), and reports wall as well as CPU seconds per step
(on a quiet machine wall time is what a user waits; docs/measurements.md, "Growth with size").

Needs h5py (Debian's /usr/bin/python3 has it). Times are reported, never asserted.
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "api", "examples", "hollow_ball_plate.json")
TUMBLING = os.path.join(ROOT, "api", "examples", "tumbling_sphere.json")


def refined_scene(factor, steps, linear):
    """The seed example with its meshes refined by `factor`, contact from the third step on, `steps` steps."""
    scene = json.load(open(EXAMPLE))
    ball, plate = scene["bodies"]
    sphere = ball["mesh"]["hollow_sphere"]
    sphere["divisions"] = round(6 * factor)
    sphere["layers"] = round(2 * factor)
    sphere["center"][2] = 1.0 + 0.015  # touches the plate (z = 0) after 1.5 steps at |v_z| = 1
    plate["mesh"]["box"]["divisions"] = [round(16 * factor), round(16 * factor), round(2 * factor)]
    scene["time"]["end"] = steps * scene["time"]["step"]
    scene["solver"]["linear"] = linear
    scene["output"] = {"every": steps}
    return scene


def tumbling_scene(divisions, layers, steps, linear):
    """The tumbling sphere (no contact) with `divisions` and `layers`, `steps` steps."""
    scene = json.load(open(TUMBLING))
    sphere = scene["bodies"][0]["mesh"]["hollow_sphere"]
    sphere["divisions"], sphere["layers"] = divisions, layers
    scene["time"]["end"] = steps * scene["time"]["step"]
    scene["solver"] = dict(scene.get("solver", {}), linear=linear)
    scene["output"] = {"every": steps}
    return scene


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_once(stoss, scene, workdir, name):
    path = os.path.join(workdir, f"{name}.json")
    json.dump(scene, open(path, "w"))
    out = os.path.join(workdir, name)
    before, start = cpu_seconds(), time.monotonic()
    done = subprocess.run([stoss, "run", path, "-o", out], capture_output=True, text=True)
    cpu, wall = cpu_seconds() - before, time.monotonic() - start
    if done.returncode != 0:
        sys.exit(f"{name}: stoss run failed ({done.returncode}):\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    with h5py.File(os.path.join(out, "result.h5"), "r") as f:
        elements = len(f["mesh/hex8"])
        iterations = int(np.sum(f["series/newton_iterations"][1:]))
        active = int(np.max(f["series/active_contacts"][:])) if "active_contacts" in f["series"] else -1
    return dict(cpu=cpu, wall=wall, elements=elements, iterations=iterations, active=active)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--stoss", default=os.path.join(ROOT, "build", "stoss"))
    p.add_argument("--factors", default="1,1.5,2,2.5")
    p.add_argument("--steps", type=int, default=8)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--contact-free", help="DxL,...: the tumbling sphere at these divisions x layers instead")
    args = p.parse_args()
    workdir = tempfile.mkdtemp(prefix="crossover_")
    if args.contact_free:
        return contact_free(args, workdir)
    print(f"{args.steps} steps per run, median of {args.rounds} rounds, CPU seconds per step (user + sys)")
    print("| refinement | hex8 | contacts | direct (UMFPACK) s/step | Newton its | petsc_gamg s/step | Newton its "
          "| ratio gamg/direct |")
    print("|---|---|---|---|---|---|---|---|")
    for factor in [float(f) for f in args.factors.split(",")]:
        runs = {"direct": [], "petsc_gamg": []}
        for r in range(args.rounds):
            for linear in runs:
                scene = refined_scene(factor, args.steps, linear)
                runs[linear].append(run_once(args.stoss, scene, workdir, f"k{factor:g}_{linear}_{r}"))
        d, g = runs["direct"], runs["petsc_gamg"]
        per_step = lambda rs: statistics.median(x["cpu"] for x in rs) / args.steps
        print(f"| {factor:g} | {d[0]['elements']} | {d[0]['active']} | {per_step(d):.3f} | {d[0]['iterations']} | {per_step(g):.3f} | "
              f"{g[0]['iterations']} | {per_step(g) / per_step(d):.2f} |", flush=True)


def contact_free(args, workdir):
    print(f"tumbling sphere, {args.steps} steps per run, median of {args.rounds} rounds, seconds per step")
    print("| hex8 | direct wall | direct CPU | petsc_gamg wall | petsc_gamg CPU | ratio gamg/direct (wall) |")
    print("|---|---|---|---|---|---|")
    for size in args.contact_free.split(","):
        divisions, layers = (int(v) for v in size.split("x"))
        runs = {"direct": [], "petsc_gamg": []}
        for r in range(args.rounds):
            for linear in runs:
                scene = tumbling_scene(divisions, layers, args.steps, linear)
                runs[linear].append(run_once(args.stoss, scene, workdir, f"t{size}_{linear}_{r}"))
        per_step = lambda rs, key: statistics.median(x[key] for x in rs) / args.steps
        d, g = runs["direct"], runs["petsc_gamg"]
        print(f"| {d[0]['elements']} | {per_step(d, 'wall'):.3f} | {per_step(d, 'cpu'):.3f} | {per_step(g, 'wall'):.3f} "
              f"| {per_step(g, 'cpu'):.3f} | {per_step(g, 'wall') / per_step(d, 'wall'):.2f} |", flush=True)


if __name__ == "__main__":
    main()
