#!/usr/bin/python3
"""Where `solver.linear: auto` should switch from UMFPACK to PETSc GMRES + GAMG on a contact scene (issue 26 §3).

The seed example (api/examples/hollow_ball_plate.json) refined by a factor k: the hollow ball's `divisions` 6k and
`layers` 2k, the plate's divisions 16k × 16k × 2k (944 k³ hex8), the ball moved down to touch the plate after two
steps, so that every measured step has contact. Each size runs `--steps` steps with `direct` and with
`petsc_gamg`, alternating, `--rounds` times; the table gives the median CPU seconds per step (user + sys of the
whole process, from getrusage of the child: on a shared machine CPU time is steadier than wall time) and the
Newton iterations of the run.

    /usr/bin/python3 bench/linear_crossover.py [--stoss build/stoss] [--factors 1,1.5,2,2.5] [--steps 8]
                                               [--rounds 3]

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

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "api", "examples", "hollow_ball_plate.json")


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


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_once(stoss, scene, workdir, name):
    path = os.path.join(workdir, f"{name}.json")
    json.dump(scene, open(path, "w"))
    out = os.path.join(workdir, name)
    before = cpu_seconds()
    done = subprocess.run([stoss, "run", path, "-o", out], capture_output=True, text=True)
    cpu = cpu_seconds() - before
    if done.returncode != 0:
        sys.exit(f"{name}: stoss run failed ({done.returncode}):\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    with h5py.File(os.path.join(out, "result.h5"), "r") as f:
        elements = len(f["mesh/hex8"])
        iterations = int(np.sum(f["series/newton_iterations"][1:]))
        active = int(np.max(f["series/active_contacts"][:])) if "active_contacts" in f["series"] else -1
    return dict(cpu=cpu, elements=elements, iterations=iterations, active=active)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--stoss", default=os.path.join(ROOT, "build", "stoss"))
    p.add_argument("--factors", default="1,1.5,2,2.5")
    p.add_argument("--steps", type=int, default=8)
    p.add_argument("--rounds", type=int, default=3)
    args = p.parse_args()
    workdir = tempfile.mkdtemp(prefix="crossover_")
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


if __name__ == "__main__":
    main()
