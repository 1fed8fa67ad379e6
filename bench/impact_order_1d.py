#!/usr/bin/python3
"""The 1D study behind docs/theory.md §4.6.4: a bar (N linear elements, E = rho = 1, L = 1, consistent mass)
moving at -1 hits a rigid wall with node 0 (gap 0.0537), midpoint rule (= energy-momentum for linear
springs), Lagrange constraint on node 0. Final-position error at T against h = coarsest/8, for the impact
modes persist, exact and located (activations and releases end a sub-step at their linear-interpolated time),
with node 0 massive or massless (its mass moved to node 1, M' = P^T M P).
    bench/impact_order_1d.py N T [h1,h2,h3] [MODE]   e.g. bench/impact_order_1d.py 10 2.6
                                                          bench/impact_order_1d.py 160 2.6 0.0016,0.0008,0.0004 located
The reference is h1/8; MODE limits the table to one impact mode with the massless slave node (docs/theory.md
§4.6.5 sweeps N at fixed steps this way).
Needs Debian's python3-numpy."""
import sys

import numpy as np


def bar(N, massless):
    le = 1.0 / N
    M = np.zeros((N + 1, N + 1))
    K = np.zeros((N + 1, N + 1))
    for e in range(N):
        i = [e, e + 1]
        M[np.ix_(i, i)] += le / 6 * np.array([[2, 1], [1, 2]])
        K[np.ix_(i, i)] += 1 / le * np.array([[1, -1], [-1, 1]])
    if massless:  # M' = P^T M P with P copying node 1's velocity to node 0 (4.13)
        P = np.eye(N + 1)
        P[0, 0], P[0, 1] = 0, 1
        M = P.T @ M @ P
    return M, K


def run(N, h, T, mode, massless, g0=0.0537, v0=-1.0):
    M, K = bar(N, massless)
    n = N + 1
    X = np.linspace(0, 1, n)
    x, v, t = X + g0, np.full(n, v0), 0.0
    active, f3, lam_prev, h_prev = False, 0.0, 0.0, h
    H = lambda x, v: 0.5 * v @ M @ v + 0.5 * (x - X) @ K @ (x - X)
    H0, dH = H(x, v), 0.0

    def solve(h, act, f3):
        A = np.zeros((n + 1, n + 1))
        b = np.zeros(n + 1)
        A[:n, :n] = 2 / h * M + h / 2 * K
        b[:n] = 2 / h * M @ x + 2 * M @ v - h * K @ (x / 2 - X)
        if act:
            A[0, n], A[n, 0], b[n] = -h, 1, f3
        else:
            A[n, n] = 1
        s = np.linalg.solve(A, b)
        return s[:n], 2 * (s[:n] - x) / h - v, s[n]

    while t < T - 1e-12:
        hh, cut = min(h, T - t), False
        for _ in range(40):
            x1, v1, lam = solve(hh, active, f3)
            if not active and x1[0] < -1e-13:
                if mode == "located" and x[0] > 1e-12 and not cut:
                    hh, cut = hh * x[0] / (x[0] - x1[0]), True  # (4.14)
                    continue
                active, f3 = True, (max(x[0], 0) if mode != "exact" else 0.0)
                continue
            if active and lam < 0:  # tensile
                if mode == "located" and lam_prev > 0 and not cut:
                    s = (h_prev / 2 + hh / 2) * lam_prev / (lam_prev - lam) - h_prev / 2  # (4.15)
                    if 1e-12 * h < s < hh:
                        hh, cut = s, True
                        continue
                active, f3 = False, 0.0
                continue
            break
        x, v, t, h_prev = x1, v1, t + hh, hh
        lam_prev = lam if active else 0.0
        dH = max(dH, abs(H(x, v) - H0) / H0)
    return x, dH


if __name__ == "__main__":
    N, T = int(sys.argv[1]), float(sys.argv[2])
    steps = [float(h) for h in sys.argv[3].split(",")] if len(sys.argv) > 3 else [0.02, 0.01, 0.005]
    only = sys.argv[4] if len(sys.argv) > 4 else None
    for massless in (False, True) if only is None else (True,):
        for mode in ("persist", "exact", "located") if only is None else (only,):
            ref, _ = run(N, steps[0] / 8, T, mode, massless)
            errors, drift = [], 0.0
            for h in steps:
                x, dH = run(N, h, T, mode, massless)
                errors.append(np.abs(x - ref).max())
                drift = max(drift, dH)
            print("%-8s %-8s" % (mode, "massless" if massless else "massive"),
                  " ".join("%.2e" % e for e in errors),
                  " ratios " + " ".join("%.2f" % (errors[i] / errors[i + 1]) for i in range(len(steps) - 1)),
                  " energy %.1e" % drift)
