#!/usr/bin/env python3
"""Job-queue benchmark of the two stores (issue 15): submit-to-start latency and throughput.

One API process (`stoss serve --workers 0`) and 1, 2 or 4 worker processes (`stoss worker --workers 1`)
share a store: SQLite (sqlite:DATA/jobs.db, one host) or PostgreSQL (a throwaway cluster started by
tests/server/pg_cluster.sh with fsync and synchronous commit on). Jobs are one step of a one-element box.

- latency: one job at a time into an idle queue, `started - created` as the store stamped them (the same
  host's clock), 30 jobs: median and 90th percentile.
- throughput: 200 jobs submitted at once (4 client threads), jobs finished per second from the first
  submission to the last job succeeded.

usage: bench/store_queue.py [STOSS_BINARY]   (default build/stoss)
"""
import concurrent.futures
import datetime
import json
import os
import re
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STOSS = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "stoss")
CLUSTER = os.path.join(ROOT, "tests", "server", "pg_cluster.sh")
SCENE = json.dumps({
    "format": "stoss-scene/1", "name": "tiny",
    "bodies": [{"name": "box",
                "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "divisions": [1, 1, 1]}},
                "material": {"model": "saint_venant_kirchhoff", "youngs_modulus": 1000,
                             "poisson_ratio": 0.3, "density": 2},
                "initial_velocity": [1, 0.5, 0]}],
    "time": {"scheme": "energy_momentum", "step": 0.01, "end": 0.01},
    "output": {"every": 1}}).encode()


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stamp(text):
    return datetime.datetime.fromisoformat(text.replace("Z", "+00:00")).timestamp()


def request(url, data=None):
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.loads(r.read())


class Processes:
    """The API and the workers on one store; stopped (SIGTERM) on exit."""

    def __init__(self, store, data, workers):
        self.procs = []
        log = open(os.path.join(data, "serve.log"), "w")
        self.procs.append(subprocess.Popen([STOSS, "serve", "--listen", "127.0.0.1:0", "--data", data,
                                            "--store", store, "--workers", "0"], stdout=log, stderr=log))
        for _ in range(400):
            m = re.search(r"http://127\.0\.0\.1:(\d+)", open(os.path.join(data, "serve.log")).read())
            if m:
                break
            time.sleep(0.05)
        self.base = "http://127.0.0.1:%s" % m.group(1)
        for i in range(workers):
            wlog = open(os.path.join(data, "worker-%d.log" % i), "w")
            self.procs.append(subprocess.Popen([STOSS, "worker", "--store", store, "--data", data,
                                                "--workers", "1"], stdout=wlog, stderr=wlog))
        time.sleep(1.0)  # workers connected and idle

    def __enter__(self):
        return self

    def __exit__(self, *args):
        for p in self.procs:
            p.terminate()
        for p in self.procs:
            p.wait()


def wait_done(base, job_id):
    while True:
        job = request(base + "/v1/jobs/" + job_id)
        if job["status"] in ("succeeded", "failed", "canceled"):
            return job
        time.sleep(0.005)


def latency(base, samples=30):
    waits = []
    for _ in range(samples):
        job = wait_done(base, request(base + "/v1/jobs", SCENE)["id"])
        waits.append(1000 * (stamp(job["started"]) - stamp(job["created"])))
        time.sleep(0.2)  # the workers are idle again (waiting for a notification or their poll)
    waits.sort()
    return statistics.median(waits), waits[int(0.9 * len(waits)) - 1]


def throughput(base, jobs=200):
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        ids = list(pool.map(lambda _: request(base + "/v1/jobs", SCENE)["id"], range(jobs)))
    for job_id in ids:
        wait_done(base, job_id)
    return jobs / (time.monotonic() - start)


def run(kind, store, data, workers):
    with Processes(store, data, workers) as p:
        med, p90 = latency(p.base)
        rate = throughput(p.base)
    print("| %s | %d | %.0f | %.0f | %.1f |" % (kind, workers, med, p90, rate), flush=True)


def main():
    work = tempfile.mkdtemp(prefix="stoss-bench-")
    cluster = tempfile.mkdtemp(prefix="stoss-pg-", dir="/tmp")
    try:
        env = dict(os.environ, STOSS_PG_DURABLE="1")
        url = subprocess.check_output([CLUSTER, "start", cluster, str(free_port())], env=env, text=True).strip()
        print("| store | worker processes | submit-to-start median (ms) | p90 (ms) | throughput (jobs/s) |")
        print("|---|---|---|---|---|")
        for workers in (1, 2, 4):
            for kind in ("SQLite", "PostgreSQL"):
                data = os.path.join(work, "%s-%d" % (kind, workers))
                os.makedirs(data)
                if kind == "SQLite":
                    store = "sqlite:" + os.path.join(data, "jobs.db")
                else:
                    db = "bench_%d" % workers
                    subprocess.check_call(["psql", "-q", url, "-c", "CREATE DATABASE " + db])
                    store = url.rsplit("/", 1)[0] + "/" + db
                run(kind, store, data, workers)
    finally:
        subprocess.call([CLUSTER, "remove", cluster])
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
