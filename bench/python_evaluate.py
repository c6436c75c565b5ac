"""Python Filter.evaluate against boxrecon's own evaluation time, in one run (docs/performance.md).

boxrecon bench --filter F --points N times Reconstructor::evaluate alone (fastest of R, 1 thread
and all threads) on a 48^3-per-coset volume of random samples at random points of its default
box. This script times Filter.evaluate (which also converts the arrays, checks the points and
the results for finiteness) on the same geometry and point count, wall and CPU, and prints both.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_evaluate.py [--filter m7] [--points N]
"""
import argparse
import json
import os
import subprocess
import time

import numpy as np

import boxgen


def fastest(repeats, call):
    wall, cpu = [], []
    for _ in range(repeats):
        w, c = time.perf_counter(), time.process_time()
        call()
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
    return min(wall), min(cpu)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--filter", default="m7")
    parser.add_argument("--points", type=int, default=10**6)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--boxrecon", default="build/apps/boxrecon")
    a = parser.parse_args()
    f = boxgen.Filter(a.filter)
    rng = np.random.default_rng(1)
    k = {"bcc": 2, "fcc": 4, "cartesian": 1}[f.lattice]
    v = boxgen.Volume(rng.uniform(-1, 1, (k, 48, 48, 48)), lattice=f.lattice)
    lo, hi = (np.array(b) for b in f.default_box(v))
    points = lo + (hi - lo) * rng.random((a.points, 3))
    all_threads = boxgen.threads()
    rows = []
    for threads in sorted({1, all_threads}):
        cli = json.loads(subprocess.run(
            [a.boxrecon, "--threads", str(threads), "bench", "--filter", a.filter, "--points",
             str(a.points), "--repeats", str(a.repeats), "--json"],
            check=True, capture_output=True, text=True).stdout)
        cli_ns = cli["timings"][0]["value_ns_per_point"]
        cli_gradient_ns = cli["timings"][0]["gradient_ns_per_point"]
        boxgen.set_threads(threads)
        wall, cpu = fastest(a.repeats, lambda: f.evaluate(v, points))
        gwall, gcpu = fastest(a.repeats, lambda: f.evaluate(v, points, gradient=True))
        boxgen.set_threads(0)
        n = a.points
        rows.append((threads, cli_ns, wall / n * 1e9, cpu / n * 1e9, cli_gradient_ns,
                     gwall / n * 1e9, gcpu / n * 1e9))
    print(f"{a.filter}, {a.points} points, fastest of {a.repeats}; ns per point "
          f"(boxrecon bench: evaluation alone, wall; Python evaluate: wall and CPU)")
    print(f"{'threads':>7} {'boxrecon':>9} {'Python':>8} {'ratio':>6} {'CPU':>8}   "
          f"{'+grad CLI':>9} {'Python':>8} {'ratio':>6} {'CPU':>8}")
    for t, c, w, u, cg, gw, gu in rows:
        print(f"{t:>7} {c:>9.1f} {w:>8.1f} {w / c:>6.3f} {u:>8.1f}   {cg:>9.1f} {gw:>8.1f} "
              f"{gw / cg:>6.3f} {gu:>8.1f}")


if __name__ == "__main__":
    main()
