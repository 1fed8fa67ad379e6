#!/usr/bin/python3
"""Stoss and CalculiX side by side on the same scene (issue 26 §4): a benchmark, not a test.

Writes a CalculiX deck of the scene on Stoss's own mesh (bench/calculix/write_deck.py), then runs
`stoss run SCENE -o DIR` and `ccx -i JOB` alternately, --rounds times each, and prints every round's
whole-process wall time (time.monotonic around subprocess.run) and CPU time (user + system, from
resource.getrusage(RUSAGE_CHILDREN) deltas), the medians and the ratio CalculiX / Stoss.

CalculiX is optional (Debian: apt-get install calculix-ccx; it is not in deploy/packages.txt): without
`ccx` on PATH the script says "CalculiX not installed: Stoss only", times Stoss alone and exits 0.

Both codes get the same thread count, --threads (default: the machine's cores): STOSS_THREADS for
Stoss's element loops; OMP_NUM_THREADS and CCX_NPROC_EQUATION_SOLVER for ccx (its element loops and
SPOOLES). Nothing else in the environment is changed.

Usage:
    bench/side_by_side.py [--rounds 5] [--scene api/examples/hollow_ball_plate.json] [--stoss build/stoss]
                          [--ccx ccx] [--alpha -0.05] [--threads N] [--keep DIR]
"""
import argparse
import os
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

BENCH = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(BENCH)
WRITE_DECK = os.path.join(BENCH, "calculix", "write_deck.py")


def children_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed_run(command, env, cwd, log_path):
    """Runs one whole process; returns (wall s, CPU s, its output). Exits if the process fails."""
    cpu_before = children_cpu_seconds()
    start = time.monotonic()
    with open(log_path, "w") as log:
        result = subprocess.run(command, env=env, cwd=cwd, stdout=log, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    cpu = children_cpu_seconds() - cpu_before
    output = open(log_path, errors="replace").read()
    if result.returncode != 0:
        sys.exit(f"side_by_side: {shlex.join(command)} failed (exit {result.returncode}); log {log_path}")
    return wall, cpu, output


def environment_with(settings):
    env = dict(os.environ)
    env.update(settings)
    return env


def shown(command, settings, cwd):
    assignments = " ".join(f"{k}={v}" for k, v in settings.items())
    return f"(cd {cwd} && {assignments} {shlex.join(command)})"


def write_deck(args, work):
    deck = os.path.join(work, "hollow_ball_plate.inp")
    command = [sys.executable, WRITE_DECK, "--scene", args.scene, "--stoss", args.stoss,
               "--alpha", str(args.alpha), "-o", deck]
    print("deck:     " + shlex.join(command))
    subprocess.run(command, check=True)
    return deck


def median_line(name, walls, cpus):
    return f"{name:<9} wall median {statistics.median(walls):7.2f} s   CPU median {statistics.median(cpus):7.2f} s"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--scene", default=os.path.join(REPO, "api", "examples", "hollow_ball_plate.json"))
    parser.add_argument("--stoss", default=os.path.join(REPO, "build", "stoss"))
    parser.add_argument("--ccx", default="ccx")
    parser.add_argument("--alpha", type=float, default=-0.05, help="ccx HHT alpha (write_deck.py)")
    parser.add_argument("--threads", type=int, default=os.cpu_count())
    parser.add_argument("--keep", help="work directory to keep (default: a temporary one, removed)")
    args = parser.parse_args()
    args.scene, args.stoss = os.path.abspath(args.scene), os.path.abspath(args.stoss)

    ccx = shutil.which(args.ccx)
    work = args.keep or tempfile.mkdtemp(prefix="side_by_side_")
    os.makedirs(work, exist_ok=True)
    stoss_settings = {"STOSS_THREADS": str(args.threads)}
    ccx_settings = {"OMP_NUM_THREADS": str(args.threads), "CCX_NPROC_EQUATION_SOLVER": str(args.threads)}
    stoss_out = os.path.join(work, "stoss_out")
    stoss_command = [args.stoss, "run", args.scene, "-o", stoss_out]

    print(f"{args.rounds} rounds, {args.threads} threads each, machine: {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.2f} at the start")
    if ccx is None:
        print("CalculiX not installed: Stoss only")
    else:
        deck = write_deck(args, work)
        ccx_command = [ccx, "-i", os.path.splitext(os.path.basename(deck))[0]]
        print("ccx:      " + shown(ccx_command, ccx_settings, work))
    print("stoss:    " + shown(stoss_command, stoss_settings, work))

    times = {"Stoss": ([], []), "CalculiX": ([], [])}
    for round_number in range(1, args.rounds + 1):
        shutil.rmtree(stoss_out, ignore_errors=True)
        wall, cpu, _ = timed_run(stoss_command, environment_with(stoss_settings), work,
                                 os.path.join(work, "stoss.log"))
        times["Stoss"][0].append(wall)
        times["Stoss"][1].append(cpu)
        line = f"round {round_number}: Stoss {wall:6.2f} s wall {cpu:6.2f} s CPU"
        if ccx is not None:
            wall, cpu, output = timed_run(ccx_command, environment_with(ccx_settings), work,
                                          os.path.join(work, "ccx.log"))
            if "Job finished" not in output:
                sys.exit(f"side_by_side: ccx did not finish the job; log {os.path.join(work, 'ccx.log')}")
            times["CalculiX"][0].append(wall)
            times["CalculiX"][1].append(cpu)
            line += f"   CalculiX {wall:6.2f} s wall {cpu:6.2f} s CPU"
        print(line, flush=True)

    print(median_line("Stoss", *times["Stoss"]))
    if ccx is not None:
        print(median_line("CalculiX", *times["CalculiX"]))
        wall_ratio = statistics.median(times["CalculiX"][0]) / statistics.median(times["Stoss"][0])
        cpu_ratio = statistics.median(times["CalculiX"][1]) / statistics.median(times["Stoss"][1])
        print(f"CalculiX / Stoss: {wall_ratio:.1f}x wall, {cpu_ratio:.1f}x CPU "
              f"(load average {os.getloadavg()[0]:.2f} at the end)")
    if not args.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
