#!/usr/bin/env python3
"""Reads a Stoss result directory with meshio (Debian's python3-meshio) the two ways its users do,
and compares every value read with the HDF5 datasets (h5py):

  meshio.read(DIR/result_mesh.xdmf)                    the reference mesh, body ids
  meshio.xdmf.TimeSeriesReader(DIR/result.xdmf)        every frame: time, node and cell fields

Exits 1 naming the first difference; else prints a JSON report (counts and a few values, for the
caller to compare with what it wrote).   usage: meshio_check.py DIR
"""
import json
import sys

import h5py
import meshio
import numpy as np


def same(what, a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or not np.array_equal(a, b):
        sys.exit(f"meshio_check: {what} differs: meshio {a.shape} vs HDF5 {b.shape}")
    return a.size


def main(directory):
    h5 = h5py.File(f"{directory}/result.h5", "r")
    nodes, hexes, body = h5["/mesh/nodes"][()], h5["/mesh/hex8"][()], h5["/mesh/body"][()]
    compared = 0

    mesh = meshio.read(f"{directory}/result_mesh.xdmf")
    compared += same("result_mesh.xdmf points", mesh.points, nodes)
    if len(mesh.cells) != 1 or mesh.cells[0].type != "hexahedron":
        sys.exit(f"meshio_check: result_mesh.xdmf cells are {[c.type for c in mesh.cells]}")
    compared += same("result_mesh.xdmf hexahedra", mesh.cells[0].data, hexes)
    compared += same("result_mesh.xdmf body", mesh.cell_data["body"][0], body)
    compared += same("result_mesh.xdmf node_body", mesh.point_data["node_body"], h5["/mesh/node_body"][()])

    times = h5["/frames/time"][()]
    fields = set()
    with meshio.xdmf.TimeSeriesReader(f"{directory}/result.xdmf") as reader:
        points, cells = reader.read_points_cells()
        compared += same("time series points (frame 0 geometry)", points, h5["/frames/0/position"][()])
        compared += same("time series hexahedra", cells[0].data, hexes)
        if reader.num_steps != len(times):
            sys.exit(f"meshio_check: {reader.num_steps} steps in result.xdmf, {len(times)} frames in result.h5")
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            if t != times[k]:
                sys.exit(f"meshio_check: frame {k} time {t!r} in result.xdmf, {times[k]!r} in result.h5")
            group = h5[f"/frames/{k}"]
            for name in group:
                if name == "position":
                    continue  # the frame's geometry: TimeSeriesReader keeps the first grid's points
                data = point_data[name] if name in point_data else cell_data[name][0]
                compared += same(f"frame {k} {name}", data, group[name][()])
                fields.add(name)
        last = reader.read_data(reader.num_steps - 1)
    report = {
        "points": int(len(mesh.points)),
        "cells": int(len(mesh.cells[0].data)),
        "frames": int(reader.num_steps),
        "fields": sorted(fields),
        "values_compared": int(compared),
        "last_time": float(last[0]),
        "last_displacement_x_sum": float(np.sum(last[1]["displacement"][:, 0])),
    }
    if "von_mises" in last[2]:
        report["last_von_mises_max"] = float(np.max(last[2]["von_mises"][0]))
    print(json.dumps(report))


if __name__ == "__main__":
    main(sys.argv[1])
