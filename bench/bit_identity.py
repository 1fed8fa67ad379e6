#!/usr/bin/python3
"""SHA-256 of every physical series and of the last frame of a result file (bench/check_bit_identity.sh).

usage: bit_identity.py SCENE_LABEL RESULT.h5   prints "<sha256>  <label>:<dataset>" lines, sorted

Each digest covers the dataset's dtype, shape and raw bytes, so a change of type or length shows as well
as a change of one bit. step_seconds (wall time) is left out: it differs between any two runs; so are the
series newer than the baseline (step_size, rejected_steps, contact_force, contact_area).
"""
import hashlib
import sys

import h5py

WALL_TIME_SERIES = {"step_seconds"}
# Series added after the baseline's build (issue 22 §2): absent from it, so not compared.
SERIES_AFTER_BASELINE = {"step_size", "rejected_steps", "contact_force", "contact_area"}


def digest(dataset):
    data = dataset[()]
    h = hashlib.sha256()
    h.update(f"{data.dtype.str} {data.shape}\n".encode())
    h.update(data.tobytes())
    return h.hexdigest()


def main(label, path):
    lines = []
    with h5py.File(path, "r") as f:
        if f.attrs["complete"] != 1:
            sys.exit(f"{path}: the run did not complete")
        for name, dataset in f["series"].items():
            if name not in WALL_TIME_SERIES | SERIES_AFTER_BASELINE:
                lines.append((f"{label}:/series/{name}", digest(dataset)))
        last = len(f["frames/time"]) - 1
        lines.append((f"{label}:/frames/time", digest(f["frames/time"])))
        for name, dataset in f[f"frames/{last}"].items():
            lines.append((f"{label}:/frames/last/{name}", digest(dataset)))
    for key, sha in sorted(lines):
        print(f"{sha}  {key}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
