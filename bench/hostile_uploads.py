#!/usr/bin/env python3
"""Hostile uploads against `stoss serve` on loopback (issue 20, "Limits before reading"), two numbers:

 1. chunked flood: POST /v1/validate with a 1 GiB chunked body, generated on the fly, stopping once the
    server answers or stops taking bytes; prints the answer, the MiB sent and how far the server's peak
    resident set (VmHWM, /proc/PID/status) rose above its resident set before (VmRSS);
 2. drip: 64 uploads from 127.0.0.1 (the default --max-connections-per-client) each drip one byte every
    2 s into POST /v1/jobs (Content-Length 1000), while GET /healthz is asked from 127.0.0.1 every
    second; prints what /healthz answered and when and how each upload ended.

usage: bench/hostile_uploads.py [STOSS_BINARY] [--request-timeout S]   (default build/stoss, 60 s)
"""
import os
import re
import select
import socket
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def status_mib(pid, field):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    raise RuntimeError(f"no {field}")


def start_server(stoss, data, extra):
    log = open(os.path.join(data, "serve.log"), "w+")
    proc = subprocess.Popen([stoss, "serve", "--listen", "127.0.0.1:0", "--data", os.path.join(data, "var"),
                             "--workers", "0"] + extra, stdout=log, stderr=subprocess.STDOUT)
    for _ in range(200):
        log.seek(0)
        m = re.search(r"http://127\.0\.0\.1:(\d+)", log.read())
        if m:
            return proc, int(m.group(1))
        time.sleep(0.05)
    raise RuntimeError("the server did not start")


def status_of(reply):
    return reply.split(b" ", 2)[1].decode() if reply.startswith(b"HTTP/1.1 ") else "no answer"


def chunked_flood(port, pid, total=1 << 30, piece=1 << 16):
    before, peak_before = status_mib(pid, "VmRSS"), status_mib(pid, "VmHWM")
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b"POST /v1/validate HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n")
    chunk = b"%x\r\n" % piece + b" " * piece + b"\r\n"
    sent = 0
    started = time.monotonic()
    try:
        while sent < total and not select.select([s], [], [], 0)[0]:
            s.sendall(chunk)
            sent += piece
    except OSError:
        pass  # the server closed the connection
    s.settimeout(10)
    reply = b""
    try:
        while data := s.recv(65536):
            reply += data
    except OSError:
        pass
    seconds = time.monotonic() - started
    peak = status_mib(pid, "VmHWM")
    print(f"chunked flood: answer {status_of(reply)} after {sent >> 20} MiB of 1024 sent ({seconds:.2f} s); "
          f"peak RSS (VmHWM) {peak:.0f} MiB, {peak - before:.0f} MiB above the RSS before ({before:.0f} MiB; "
          f"VmHWM before {peak_before:.0f} MiB)")


def drip(port, uploads=64, every=2.0):
    ends = [None] * uploads
    started = time.monotonic()

    def one(i):
        s = socket.create_connection(("127.0.0.1", port))
        s.sendall(b"POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                  b"Content-Length: 1000\r\n\r\n")
        sent = 0
        try:
            while sent < 1000:
                if select.select([s], [], [], every)[0]:
                    break
                s.sendall(b" ")
                sent += 1
        except OSError:
            pass
        s.settimeout(5)
        try:
            reply = s.recv(4096)
        except OSError:
            reply = b""
        ends[i] = (time.monotonic() - started, status_of(reply), sent)
        s.close()

    threads = [threading.Thread(target=one, args=(i,)) for i in range(uploads)]
    for t in threads:
        t.start()
    health = {}
    while any(t.is_alive() for t in threads):
        time.sleep(1)
        try:
            h = socket.create_connection(("127.0.0.1", port), timeout=5)
            h.sendall(b"GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
            status = status_of(h.recv(4096))
            h.close()
        except OSError as e:
            status = type(e).__name__
        health[status] = health.get(status, 0) + 1
    for t in threads:
        t.join()
    times = sorted(e[0] for e in ends)
    statuses = {}
    for e in ends:
        statuses[e[1]] = statuses.get(e[1], 0) + 1
    print(f"drip: {uploads} uploads ended after {times[0]:.1f}-{times[-1]:.1f} s with {statuses}, "
          f"{min(e[2] for e in ends)}-{max(e[2] for e in ends)} bytes sent each; "
          f"/healthz meanwhile: {health}")


def main():
    args = sys.argv[1:]
    extra = []
    if "--request-timeout" in args:
        i = args.index("--request-timeout")
        extra = args[i:i + 2]
        del args[i:i + 2]
    stoss = args[0] if args else os.path.join(ROOT, "build", "stoss")
    with tempfile.TemporaryDirectory() as data:
        proc, port = start_server(stoss, data, extra)
        time.sleep(1)  # the server's start-up settles (its resident set still grows just after start)
        try:
            print(f"load average before: {os.getloadavg()[0]:.1f}")
            chunked_flood(port, proc.pid)
            drip(port)
            print(f"load average after: {os.getloadavg()[0]:.1f}")
        finally:
            proc.terminate()
            proc.wait()


if __name__ == "__main__":
    main()
