#!/usr/bin/python3
"""Sanity check that Stoss and CalculiX solve the same impact: kinetic energy and the first body's mean
node height z(t) from a Stoss result.h5 and a ccx .dat written from a write_deck.py deck.

The mean is the plain mean over the body's nodes (not mass-weighted), the same definition on both
sides, on the same mesh. Prints both series at the common output times, then the impact's landmarks:
the time of least kinetic energy and of lowest mean height (parabola through the lowest three
samples), the kinetic energy at the end, and the mean vertical velocity of the body after the bounce.

Usage:
    bench/calculix/compare.py STOSS_DIR/result.h5 CCX_JOB.dat
"""
import argparse
import re

import h5py
import numpy as np


class Series:
    def __init__(self, label, time, kinetic, mean_z):
        self.label, self.time, self.kinetic, self.mean_z = label, time, kinetic, mean_z


def read_stoss(result_h5):
    with h5py.File(result_h5, "r") as f:
        first_body = f["mesh/node_body"][:] == 0
        frames = sorted((k for k in f["frames"] if k.isdigit()), key=int)
        frame_time = np.array([f["frames"][k].attrs["time"] for k in frames])
        mean_z = np.array([f["frames"][k]["position"][:, 2][first_body].mean() for k in frames])
        series_time = f["series/time"][:]
        kinetic = np.interp(frame_time, series_time, f["series/kinetic_energy"][:])
        reference_z = f["mesh/nodes"][:, 2][first_body].mean()
    return Series("Stoss", frame_time, kinetic, mean_z), reference_z


def read_ccx_dat(dat_path, reference_mean_z):
    """Blocks 'total kinetic energy ... time t' and 'displacements ... time t' of the .dat file.

    ccx prints nothing at t = 0; the row t = 0 gets the reference height and the first printed kinetic
    energy (the bodies fly free until the first contact, so it has not changed)."""
    kinetic, mean_uz = {}, {}
    block, time = None, None
    for line in open(dat_path):
        header = re.search(r"(total kinetic energy|displacements).*time\s+(\S+)", line)
        if header:
            block, time = header.group(1), float(header.group(2))
            continue
        fields = line.split()
        if not fields:
            continue
        if block == "total kinetic energy":
            kinetic[time] = float(fields[0])
        elif block == "displacements":
            mean_uz.setdefault(time, []).append(float(fields[3]))
    times = np.array([0.0] + sorted(kinetic))
    kinetic_series = np.array([kinetic[times[1]]] + [kinetic[t] for t in times[1:]])
    mean_z = np.array([reference_mean_z] + [reference_mean_z + np.mean(mean_uz[t]) for t in times[1:]])
    return Series("CalculiX", times, kinetic_series, mean_z)


def vertex_of_lowest(time, values):
    """Time of the minimum: parabola through the lowest sample and its neighbours."""
    i = int(np.clip(np.argmin(values), 1, len(values) - 2))
    a, b, _ = np.polyfit(time[i - 1:i + 2], values[i - 1:i + 2], 2)
    return -b / (2 * a)


def rebound_velocity(s):
    """Mean vertical velocity of the body over the last quarter of the run (it flies free then)."""
    last = s.time >= s.time[-1] - 0.25 * (s.time[-1] - s.time[0])
    return np.polyfit(s.time[last], s.mean_z[last], 1)[0]


def print_table(stoss, ccx):
    common = [t for t in ccx.time if np.min(np.abs(stoss.time - t)) < 1e-9]
    print(f"{'t':>6} {'K Stoss':>10} {'K ccx':>10} {'z Stoss':>10} {'z ccx':>10}")
    for t in common:
        i, j = np.argmin(np.abs(stoss.time - t)), np.argmin(np.abs(ccx.time - t))
        print(f"{t:6.2f} {stoss.kinetic[i]:10.5f} {ccx.kinetic[j]:10.5f} {stoss.mean_z[i]:10.5f} {ccx.mean_z[j]:10.5f}")


def print_landmarks(stoss, ccx):
    rows = [("time of least kinetic energy", lambda s: vertex_of_lowest(s.time, s.kinetic)),
            ("time of lowest mean height", lambda s: vertex_of_lowest(s.time, s.mean_z)),
            ("lowest mean height", lambda s: s.mean_z.min()),
            ("least kinetic energy / initial", lambda s: s.kinetic.min() / s.kinetic[0]),
            ("kinetic energy at the end / initial", lambda s: s.kinetic[-1] / s.kinetic[0]),
            ("mean vertical velocity after the bounce", rebound_velocity)]
    print(f"\n{'landmark':<42} {'Stoss':>10} {'CalculiX':>10} {'ccx/Stoss-1':>12}")
    for name, value in rows:
        a, b = value(stoss), value(ccx)
        print(f"{name:<42} {a:10.5f} {b:10.5f} {b / a - 1:+12.2%}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stoss_result")
    parser.add_argument("ccx_dat")
    args = parser.parse_args()
    stoss, reference_z = read_stoss(args.stoss_result)
    ccx = read_ccx_dat(args.ccx_dat, reference_z)
    print_table(stoss, ccx)
    print_landmarks(stoss, ccx)


if __name__ == "__main__":
    main()
