#!/usr/bin/python3
"""Writes a CalculiX (ccx 2.20) deck of a Stoss contact scene, on Stoss's own mesh.

Default scene: api/examples/hollow_ball_plate.json (hollow St. Venant-Kirchhoff ball hits a free plate,
944 hex8, h = 0.01, t in [0, 1]). Stoss has no mesh export, so the mesh is read from a one-step run
(time.end = time.step) of the scene: result.h5 holds /mesh/nodes, /mesh/hex8, /mesh/body and the
named surfaces /mesh/surfaces/<body>/<surface> (attribute `name`, e.g. "ball/outer").

What the deck holds, and why:
- *NODE, *ELEMENT TYPE=C3D8 with Stoss's node order: Stoss's hex8 order (VTK_HEXAHEDRON) is the Abaqus
  C3D8 order; checked here by a positive Jacobian at every Gauss point of every element.
- one *ELSET per body (E<BODY>) and one *NSET per body (N<BODY>).
- *SURFACE (element faces S1..S6) for the contact pair's slave and master, each Stoss quad mapped to
  the element face with the same four nodes.
- *MATERIAL per body: *ELASTIC (E, nu) and *DENSITY. With NLGEOM, CalculiX's linear *ELASTIC is a
  St. Venant-Kirchhoff material (2nd Piola-Kirchhoff stress linear in the Green-Lagrange strain),
  the scene's `saint_venant_kirchhoff`.
- *INITIAL CONDITIONS, TYPE=VELOCITY on each moving body's nodes.
- face-to-face penalty contact: *SURFACE INTERACTION, *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
  with slope K = 10 E / l (pressure per overclosure), l the mean edge of the master faces. That is
  Stoss's own penalty default (docs/scene.md: normal_stiffness 10 E l, a force per length at a node)
  spread over a node's tributary area l^2; for this scene K = 4e5 = 40 E per unit length, inside the
  5-50 E the CalculiX manual recommends. (The Stoss scene itself uses Lagrange multipliers, which ccx
  has only in its mortar contact; penalty is CalculiX's usual road.) Frictionless, no ADJUST.
- *STEP, NLGEOM, INC=...; *DYNAMIC, DIRECT, ALPHA=a: implicit HHT with a fixed step h (DIRECT: ccx
  stops rather than cut the step). a = -0.05 is ccx's default; a = 0 is the trapezoidal rule
  (Newmark beta = 1/4, gamma = 1/2), the non-dissipative scheme nearest Stoss's energy_momentum.
- output every `output.every`-th increment (FREQUENCY=every), as Stoss writes frames: *NODE FILE U, V
  and *EL FILE S to the .frd (Stoss's frames: position, velocity, stress), *EL PRINT ELKE totals (the
  kinetic energy, for the sanity comparison) and *NODE PRINT U of the first body (its mean height).

Usage:
    bench/calculix/write_deck.py [--scene S] [--stoss BIN] [--alpha A] [--every N] [-o DECK.inp]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_SCENE = os.path.join(REPO, "api", "examples", "hollow_ball_plate.json")
DEFAULT_STOSS = os.path.join(REPO, "build", "stoss")

# C3D8 faces S1..S6 as 0-based local node indices (CalculiX manual, *SURFACE).
C3D8_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]
PENALTY_FACTOR = 10.0  # Stoss's default normal_stiffness is 10 E l (docs/scene.md)


class Mesh:
    """Stoss's mesh as result.h5 stores it: 0-based node indices."""

    def __init__(self, nodes, hexes, element_body, body_names, node_body, surfaces):
        self.nodes = nodes                # [N,3] reference coordinates
        self.hexes = hexes                # [E,8] node indices, VTK_HEXAHEDRON order
        self.element_body = element_body  # [E] body index
        self.body_names = body_names      # body names in scene order
        self.node_body = node_body        # [N] body index
        self.surfaces = surfaces          # "body/surface" -> [F,4] quads


def read_mesh_from_one_step_run(scene_path, stoss):
    """Runs the scene for one step into a temporary directory and reads the mesh from its result.h5."""
    with open(scene_path) as f:
        scene = json.load(f)
    one_step_scene = json.loads(json.dumps(scene))
    one_step_scene["time"]["end"] = scene["time"]["step"]
    with tempfile.TemporaryDirectory(prefix="stoss_mesh_") as tmp:
        # Next to the original scene, so that relative mesh file paths still resolve.
        one_step = os.path.join(os.path.dirname(os.path.abspath(scene_path)), f".one_step_{os.getpid()}.json")
        try:
            with open(one_step, "w") as f:
                json.dump(one_step_scene, f)
            subprocess.run([stoss, "run", one_step, "-o", tmp], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        finally:
            os.remove(one_step)
        return read_mesh(os.path.join(tmp, "result.h5")), scene


def read_mesh(result_h5):
    with h5py.File(result_h5, "r") as f:
        surfaces = {d.attrs["name"]: d[:] for g in f["mesh/surfaces"].values() for d in g.values()}
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["mesh/body"].attrs["names"]]
        return Mesh(f["mesh/nodes"][:], f["mesh/hex8"][:], f["mesh/body"][:], names,
                    f["mesh/node_body"][:], surfaces)


def smallest_gauss_jacobian(corners):
    """min det(dx/dxi) over the 2x2x2 Gauss points of one hex8 in C3D8 order."""
    signs = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                      [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    g = 1 / np.sqrt(3)
    smallest = np.inf
    for point in signs * g:
        # dN_a/dxi_k = s_ak / 8 * prod_{j != k} (1 + s_aj xi_j)
        factors = 1 + signs * point
        dN = np.empty((8, 3))
        for k in range(3):
            others = [j for j in range(3) if j != k]
            dN[:, k] = signs[:, k] / 8 * factors[:, others[0]] * factors[:, others[1]]
        smallest = min(smallest, np.linalg.det(corners.T @ dN))
    return smallest


def check_c3d8_order(mesh):
    """Stoss's hex8 must be valid C3D8 elements: det J > 0 at every Gauss point."""
    worst = min(smallest_gauss_jacobian(mesh.nodes[h]) for h in mesh.hexes)
    if worst <= 0:
        sys.exit(f"write_deck: an element has det J = {worst:g} <= 0 in C3D8 order; node orders differ")
    return worst


def element_faces_of(mesh, quads):
    """Maps each quad (4 node indices) to (element index, face number 1..6) with the same nodes."""
    face_of = {}
    for e, h in enumerate(mesh.hexes):
        for number, local in enumerate(C3D8_FACES, 1):
            face_of.setdefault(frozenset(h[list(local)]), (e, number))
    faces = []
    for q in quads:
        key = frozenset(q)
        if key not in face_of:
            sys.exit(f"write_deck: quad {list(q)} is no element face")
        faces.append(face_of[key])
    return faces


def mean_edge(mesh, quads):
    corners = mesh.nodes[quads]
    return float(np.mean(np.linalg.norm(corners - np.roll(corners, -1, axis=1), axis=2)))


def set_name(prefix, body):
    return prefix + body.upper()


def surface_name(stoss_name):
    return "S" + stoss_name.upper().replace("/", "_")


def data_lines(values, per_line=8):
    values = list(values)
    return [", ".join(map(str, values[i:i + per_line])) for i in range(0, len(values), per_line)]


def mesh_cards(mesh):
    lines = ["*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {x:.15g}, {y:.15g}, {z:.15g}" for i, (x, y, z) in enumerate(mesh.nodes)]
    for b, body in enumerate(mesh.body_names):
        elements = np.flatnonzero(mesh.element_body == b)
        lines.append(f"*ELEMENT, TYPE=C3D8, ELSET={set_name('E', body)}")
        lines += [f"{e + 1}, " + ", ".join(str(n + 1) for n in mesh.hexes[e]) for e in elements]
    for b, body in enumerate(mesh.body_names):
        lines.append(f"*NSET, NSET={set_name('N', body)}")
        lines += data_lines(np.flatnonzero(mesh.node_body == b) + 1)
    lines.append("*ELSET, ELSET=EALL")
    lines += [set_name("E", body) for body in mesh.body_names]
    return lines


def surface_cards(mesh, stoss_surface):
    lines = [f"*SURFACE, NAME={surface_name(stoss_surface)}, TYPE=ELEMENT"]
    lines += [f"{e + 1}, S{face}" for e, face in element_faces_of(mesh, mesh.surfaces[stoss_surface])]
    return lines


def material_cards(mesh, scene):
    lines = []
    for body in scene["bodies"]:
        material = body["material"]
        if material.get("model") != "saint_venant_kirchhoff":
            sys.exit(f"write_deck: body {body['name']}: only saint_venant_kirchhoff maps to *ELASTIC")
        name = set_name("M", body["name"])
        lines += [f"*MATERIAL, NAME={name}", "*ELASTIC",
                  f"{material['youngs_modulus']:.15g}, {material['poisson_ratio']:.15g}",
                  "*DENSITY", f"{material['density']:.15g}",
                  f"*SOLID SECTION, ELSET={set_name('E', body['name'])}, MATERIAL={name}"]
    return lines


def initial_velocity_cards(scene):
    lines = ["*INITIAL CONDITIONS, TYPE=VELOCITY"]
    for body in scene["bodies"]:
        for dof, v in enumerate(body.get("initial_velocity", [0, 0, 0]), 1):
            if v != 0:
                lines.append(f"{set_name('N', body['name'])}, {dof}, {v:.15g}")
    return lines


def contact_stiffness(mesh, scene, pair):
    """Stoss's default penalty 10 E l (force per length at a node) over a node's area l^2: 10 E / l."""
    master_body = pair["master"].split("/")[0]
    youngs = next(b["material"]["youngs_modulus"] for b in scene["bodies"] if b["name"] == master_body)
    return PENALTY_FACTOR * youngs / mean_edge(mesh, mesh.surfaces[pair["master"]])


def contact_cards(mesh, scene):
    lines = []
    for i, pair in enumerate(scene.get("contact", []), 1):
        if pair.get("friction", 0) != 0:
            sys.exit("write_deck: frictional pairs are not written (the benchmark scene is frictionless)")
        lines += surface_cards(mesh, pair["slave"]) + surface_cards(mesh, pair["master"])
        interaction = f"CONTACT{i}"
        lines += [f"*SURFACE INTERACTION, NAME={interaction}",
                  "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                  f"{contact_stiffness(mesh, scene, pair):.6g}",
                  f"*CONTACT PAIR, INTERACTION={interaction}, TYPE=SURFACE TO SURFACE",
                  f"{surface_name(pair['slave'])}, {surface_name(pair['master'])}"]
    return lines


def step_cards(mesh, scene, alpha, every):
    step, end = scene["time"]["step"], scene["time"]["end"]
    increments = int(round(end / step))
    first_body = set_name("N", mesh.body_names[0])
    return [f"*STEP, NLGEOM, INC={increments + 10}",
            f"*DYNAMIC, DIRECT, ALPHA={alpha:g}",
            f"{step:.15g}, {end:.15g}",
            f"*NODE FILE, FREQUENCY={every}", "U, V",
            f"*EL FILE, FREQUENCY={every}", "S",
            f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, FREQUENCY={every}", "ELKE",
            f"*NODE PRINT, NSET={first_body}, FREQUENCY={every}", "U",
            "*END STEP"]


def deck(mesh, scene, alpha, every):
    title = scene.get("name", "Stoss scene").encode("ascii", "ignore").decode()
    lines = ["*HEADING", f"{title} (bench/calculix/write_deck.py, Stoss's mesh)"]
    lines += mesh_cards(mesh) + material_cards(mesh, scene) + contact_cards(mesh, scene)
    lines += initial_velocity_cards(scene) + step_cards(mesh, scene, alpha, every)
    return "\n".join(lines) + "\n"


def check_scene(scene):
    if scene["time"].get("scheme") not in (None, "energy_momentum", "hht", "newmark"):
        print(f"write_deck: note: Stoss scheme {scene['time']['scheme']} becomes ccx HHT", file=sys.stderr)
    if scene.get("gravity") or scene.get("boundary") or any(b.get("boundary") for b in scene["bodies"]):
        sys.exit("write_deck: gravity and boundary conditions are not written (the benchmark scene has none)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=DEFAULT_SCENE)
    parser.add_argument("--stoss", default=DEFAULT_STOSS)
    parser.add_argument("--alpha", type=float, default=-0.05, help="HHT alpha in [-1/3, 0] (ccx default -0.05)")
    parser.add_argument("--every", type=int, help="output every N-th increment (default: the scene's output.every)")
    parser.add_argument("-o", "--output", default="hollow_ball_plate.inp", help="deck path (ccx job = its stem)")
    args = parser.parse_args()

    mesh, scene = read_mesh_from_one_step_run(args.scene, args.stoss)
    check_scene(scene)
    worst = check_c3d8_order(mesh)
    every = args.every or scene.get("output", {}).get("every", 1)
    with open(args.output, "w") as f:
        f.write(deck(mesh, scene, args.alpha, every))
    print(f"wrote {args.output}: {len(mesh.nodes)} nodes, {len(mesh.hexes)} C3D8 (min det J {worst:.3g} > 0), "
          f"alpha {args.alpha:g}, output every {every}", file=sys.stderr)


if __name__ == "__main__":
    main()
