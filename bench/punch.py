#!/usr/bin/python3
"""The flat punch's force–displacement curve on three meshes of the block, smooth and faceted master
(docs/measurements.md, "A flat punch"): api/examples/punch.json with the block's divisions 8×8×4,
16×16×8 (the example) and 24×24×12. Prints a Markdown table: the punch's force at the full indentation
δ = 0.05, the contact area, |H − W| / H at the end (the trapezoid rule's error, docs/theory.md (5b.7b)),
Newton iterations and wall seconds. A benchmark, not a test.
    /usr/bin/python3 bench/punch.py build/stoss
"""
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py

stoss = sys.argv[1]
example = json.loads((Path(__file__).resolve().parents[1] / "api/examples/punch.json").read_text())
print("| block divisions | master surface | F(δ = 0.05) | F(δ = 0.025) | contact area | \\|H − W\\| / H | Newton its | wall s |")
print("|---|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as work:
    for n in (8, 16, 24):
        for surface in ("smooth", "faceted"):
            scene = json.loads(json.dumps(example))
            scene["bodies"][0]["mesh"]["box"]["divisions"] = [n, n, n // 2]
            scene["contact"][0]["master_surface"] = surface
            path = Path(work) / f"punch_{n}_{surface}.json"
            path.write_text(json.dumps(scene))
            start = time.monotonic()
            subprocess.run([stoss, "run", str(path), "-o", str(Path(work) / "out")], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            wall = time.monotonic() - start
            with h5py.File(Path(work) / "out/result.h5") as result:
                s = result["series"]
                force = -s["contact_force"][:, 0, 2]
                H, W = s["total_energy"][-1], s["external_work"][-1]
                its = int(s["newton_iterations"][:].sum())
                area = s["contact_area"][-1, 0]
            print(f"| {n}×{n}×{n // 2} | {surface} | {force[-1]:.4f} | {force[len(force) // 2]:.4f} | {area:.4f} | "
                  f"{abs(H - W) / H:.1e} | {its} | {wall:.2f} |")
