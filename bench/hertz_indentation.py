#!/usr/bin/python3
"""Hertz indentation on the three Gmsh meshes, with the smooth and the faceted master surface (issue 23 §6).

Runs api/examples/hertz_indentation.json with its mesh replaced by meshes/hertz_coarse.msh or the medium, fine and
graded meshes Gmsh makes from meshes/hertz_indentation.geo (h0 = 0.03, 0.02, and 0.02 over a wider uniform zone:
MESH_PARAMETERS; Debian's gmsh is deterministic here), and its
pair's master_surface set to each of smooth and faceted, with the `stoss` binary, one run at a time, and prints
the table of docs/measurements.md, "Hertz indentation": the force F = 4 |contact_force_z| (quarter model)
against Hertz's F = (4/3) E* sqrt(R) delta^(3/2) (H2) and the contact radius sqrt(4 contact_area / pi) against
a = sqrt(R delta) (H3), at each load level (every 0.25 % of R with the default 8 steps; the table shows 0.5 to 2 %), E* from both
materials (H1). Wall time: the result's wall_seconds (the run, without process start).

    /usr/bin/python3 bench/hertz_indentation.py [--stoss build/stoss] [--meshes coarse,medium,fine]
                                                [--surfaces smooth,faceted] [--steps 8] [--linear direct]
                                                [--enforcement lagrange|penalty] [--radius R]
                                                [--discretization node_to_segment|mortar] [--out DIR]

--radius R (default 1) makes the meshes with a sphere of radius R (`-setnumber R`) and drives it to
delta = 0.02 / R: the same contact radii a = sqrt(R delta) on the same elements, with strains a/R that are R times
smaller. Against Hertz's small-strain solution that leaves the discretisation error alone (docs/measurements.md).

--discretization mortar runs the pair as mortar contact (docs/scene.md), which integrates on the faceted
surface: use it with --surfaces faceted.

Needs numpy and h5py (Debian's /usr/bin/python3 has both). Wall times are reported, never asserted.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "api", "examples", "hertz_indentation.json")
MESHES = os.path.join(ROOT, "api", "examples", "meshes")


def effective_modulus(scene):
    """(H1): 1/E* = (1 - nu^2)/E + (1 - nu_s^2)/E_s over both bodies."""
    return 1 / sum((1 - b["material"]["poisson_ratio"] ** 2) / b["material"]["youngs_modulus"]
                   for b in scene["bodies"])


def top_edge(f):
    """The shortest edge of block/top: h0, the element edge at the contact."""
    x = f["mesh/nodes"][:]
    for name in f["mesh/surfaces/block"]:
        ds = f["mesh/surfaces/block"][name]
        if ds.attrs["name"] == "block/top":
            q = ds[:]
            return min(np.linalg.norm(x[q[:, k]] - x[q[:, (k + 1) % 4]], axis=1).min() for k in range(4))
    raise KeyError("block/top")


# The parameters of hertz_indentation.geo for each mesh; the coarse one ships with the example, the others are made
# here. "graded" is the fine mesh (h0 = 0.02) with its uniform zone 0.35 wide and deep instead of 0.25: on the fine
# mesh the contact radius (0.14 at delta/R = 2 %) nears the zone's end, past which elements grow by 1.5 each, and
# that part of the error does not fall with h0 (docs/measurements.md, "Hertz indentation").
MESH_PARAMETERS = {"coarse": {"h0": 0.05}, "medium": {"h0": 0.03}, "fine": {"h0": 0.02},
                   "graded": {"h0": 0.02, "fine": 0.35, "zfine": 0.35}}


def mesh_file(mesh, workdir, radius=1.0):
    """meshes/hertz_coarse.msh, or the mesh Gmsh makes from hertz_indentation.geo with the parameters of `mesh`."""
    shipped = os.path.join(MESHES, f"hertz_{mesh}.msh")
    if os.path.exists(shipped) and radius == 1.0:
        return shipped
    made = os.path.join(workdir, f"hertz_{mesh}" + ("" if radius == 1.0 else f"_R{radius:g}") + ".msh")
    if not os.path.exists(made):
        numbers = [a for name, value in MESH_PARAMETERS[mesh].items() for a in ("-setnumber", name, str(value))]
        subprocess.run(["gmsh", "-3", "-format", "msh41", *numbers, "-setnumber", "R", str(radius),
                        os.path.join(MESHES, "hertz_indentation.geo"), "-o", made], check=True, capture_output=True)
    return made


def run(args, mesh, surface, workdir):
    scene = json.load(open(EXAMPLE))
    for body in scene["bodies"]:
        body["mesh"]["file"] = mesh_file(mesh, workdir, args.radius)
    scene["boundary"][0]["displacement"][2] /= args.radius  # delta = 0.02 / R: a = sqrt(R delta) kept
    scene["contact"][0]["master_surface"] = surface
    scene["contact"][0]["enforcement"] = args.enforcement
    scene["contact"][0]["discretization"] = args.discretization
    scene["time"]["step"] = 1.0 / args.steps
    # UMFPACK by default: when "auto" still picked petsc_gamg from 14,000 elements with contact, GMRES needed
    # minutes per step of the fine mesh on this problem (a 1000 times stiffer sphere, flat graded elements).
    scene["solver"] = {"linear": args.linear}
    name = f"{mesh}_{surface}" + ("" if args.enforcement == "lagrange" else f"_{args.enforcement}") + (
        "" if args.discretization == "node_to_segment" else f"_{args.discretization}") + (
        "" if args.radius == 1.0 else f"_R{args.radius:g}")
    path = os.path.join(workdir, f"{name}.json")
    json.dump(scene, open(path, "w"), indent=1)
    out = os.path.join(workdir, name)
    if not (args.reuse and os.path.exists(os.path.join(out, "result.h5"))):
        done = subprocess.run([args.stoss, "run", path, "-o", out], capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"{mesh} {surface}: stoss run failed ({done.returncode}):\n{done.stdout}\n{done.stderr}")
    f = h5py.File(os.path.join(out, "result.h5"), "r")
    wall = f.attrs["wall_seconds"]
    s = f["series"]
    depth = -scene["boundary"][0]["displacement"][2]
    radius = args.radius  # the sphere's radius R in hertz_indentation.geo
    e_star = effective_modulus(scene)
    rows = []
    for n in range(1, len(s["time"])):
        delta = depth * s["time"][n]
        force = -4 * s["contact_force"][n, 0, 2]
        reaction = 4 * s["reaction_force"][n, 0, 2]
        a = math.sqrt(4 * s["contact_area"][n, 0] / math.pi)
        # level: delta/R at R = 1; R delta = a^2 in general, so a level names the same contact radius for every R
        rows.append(dict(delta=delta, level=delta * radius, force=force, reaction=reaction, a=a,
                         hertz=4 / 3 * e_star * math.sqrt(radius) * delta ** 1.5, a_hertz=math.sqrt(radius * delta)))
    iterations = s["newton_iterations"][1:] if "newton_iterations" in s else []
    return dict(mesh=mesh, surface=", ".join([surface] + ([args.enforcement] if args.enforcement != "lagrange" else []) +
                                           ([args.discretization] if args.discretization != "node_to_segment" else [])), elements=len(f["mesh/hex8"]), h0=top_edge(f), rows=rows,
                wall=wall, iterations=int(np.sum(iterations)), e_star=e_star, verdict=f.attrs["verdict"])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--stoss", default=os.path.join(ROOT, "build", "stoss"))
    p.add_argument("--meshes", default="coarse,medium,fine")
    p.add_argument("--surfaces", default="smooth,faceted")
    p.add_argument("--steps", type=int, default=8, help="load steps to delta/R = 2 %% (a multiple of 4)")
    p.add_argument("--linear", default="direct", help="solver.linear of every run")
    p.add_argument("--enforcement", default="lagrange", help="the pair's enforcement: lagrange or penalty")
    p.add_argument("--radius", type=float, default=1.0, help="the sphere's radius R; delta = 0.02 / R")
    p.add_argument("--discretization", default="node_to_segment", help="the pair's discretization")
    p.add_argument("--out", help="keep the runs here (default: a temporary directory)")
    p.add_argument("--reuse", action="store_true", help="tabulate the results already in --out, run only missing ones")
    args = p.parse_args()
    workdir = args.out or tempfile.mkdtemp(prefix="hertz_")
    os.makedirs(workdir, exist_ok=True)
    results = []
    for mesh in args.meshes.split(","):
        for surface in args.surfaces.split(","):
            r = run(args, mesh, surface, workdir)
            results.append(r)
            print(f"{mesh} {surface}: {r['elements']} elements, {r['wall']:.1f} s, verdict {r['verdict']}",
                  file=sys.stderr)
            for row in r["rows"]:
                print(f"  level {100 * row['level']:.2f} %: F {row['force']:.6e} (reaction {row['reaction']:.6e}),"
                      f" Hertz {row['hertz']:.6e}: {100 * (row['force'] / row['hertz'] - 1):+.2f} %;"
                      f" a {row['a']:.4f} vs {row['a_hertz']:.4f}: {(row['a'] - row['a_hertz']) / r['h0']:+.2f} h0",
                      file=sys.stderr)
    print(f"R = {args.radius:g}, E* = {results[0]['e_star']:.6f}; F error at R delta = 0.5 / 1 / 1.5 / 2 % (delta/R at R = 1); a error = max |a - sqrt(R delta)| "
          f"over the levels from 0.5 to 2 %, in element edges h0")
    print("| master | mesh | elements | h0 | edges across a (0.5 / 2 %) | F error 0.5 % | 1 % | 1.5 % | 2 % "
          "| a error (h0) | Newton its | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        by = {round(100 * row["level"], 2): row for row in r["rows"]}
        err = lambda d: (f"{100 * (by[d]['force'] / by[d]['hertz'] - 1):+.1f} %" if d in by else "—")
        a_err = max(abs(row["a"] - row["a_hertz"]) for row in r["rows"] if 0.005 - 1e-12 <= row["level"]) / r["h0"]
        print(f"| {r['surface']} | {r['mesh']} | {r['elements']} | {r['h0']:.4f} | "
              f"{math.sqrt(0.005) / r['h0']:.1f} / {math.sqrt(0.02) / r['h0']:.1f} | {err(0.5)} | {err(1.0)} | "
              f"{err(1.5)} | {err(2.0)} | {a_err:.2f} | {r['iterations']} | {r['wall']:.0f} |")


if __name__ == "__main__":
    main()
