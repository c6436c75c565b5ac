"""Python Filter.evaluate against boxrecon's own evaluation time, in one run (docs/performance.md).

boxrecon bench --filter F --points N times Reconstructor::evaluate alone (fastest of R, 1 thread
and all threads) on a 48^3-per-coset volume of random samples at random points of its default
box. This script times Filter.evaluate (which also converts the arrays, checks the points and
the results for finiteness) on the same geometry and point count, wall and CPU, and prints both.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_evaluate.py [--filter m7] [--points N]
"""
import argparse
import json
import resource
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


def cli_bench(boxrecon, threads, name, points, repeats):
    """boxrecon bench --filter at this thread count: (value, value + gradient) ns per point
    (fastest of `repeats`, wall) and the child's CPU seconds for the whole run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([boxrecon, "--threads", str(threads), "bench", "--filter", name,
                          "--points", str(points), "--repeats", str(repeats), "--json"],
                         check=True, capture_output=True, text=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    timing = next(t for t in json.loads(out)["timings"] if t["threads"] == threads)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return timing["value_ns_per_point"], timing["gradient_ns_per_point"], cpu


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
    n = a.points
    print(f"{a.filter} on {f.lattice}, {k} x 48^3 random samples, {n} random points")
    print("wall, ns per point, fastest of", a.repeats, "(boxrecon bench times the evaluation "
          "alone; Python evaluate also converts and checks)")
    print(f"{'threads':>7} {'value: CLI':>10} {'Python':>8} {'ratio':>6}   "
          f"{'+gradient: CLI':>14} {'Python':>8} {'ratio':>6}")
    for threads in sorted({1, boxgen.threads()}):
        cv, cg, _ = cli_bench(a.boxrecon, threads, a.filter, n, a.repeats)
        boxgen.set_threads(threads)
        pv = fastest(a.repeats, lambda: f.evaluate(v, points))[0] / n * 1e9
        pg = fastest(a.repeats, lambda: f.evaluate(v, points, gradient=True))[0] / n * 1e9
        boxgen.set_threads(0)
        print(f"{threads:>7} {cv:>10.1f} {pv:>8.1f} {pv / cv:>6.3f}   {cg:>14.1f} {pg:>8.1f} "
              f"{pg / cg:>6.3f}")
    # CPU time, one thread: what R more repeats of value + value-and-gradient cost the CLI (its
    # set-up cancels in the difference) against the same evaluations from Python.
    extra = a.repeats
    _, _, cpu1 = cli_bench(a.boxrecon, 1, a.filter, n, 1)
    _, _, cpu2 = cli_bench(a.boxrecon, 1, a.filter, n, 1 + extra)
    boxgen.set_threads(1)
    start = time.process_time()
    for _ in range(extra):
        f.evaluate(v, points)
        f.evaluate(v, points, gradient=True)
    py_cpu = time.process_time() - start
    boxgen.set_threads(0)
    cli_ns, py_ns = (cpu2 - cpu1) / (extra * n) * 1e9, py_cpu / (extra * n) * 1e9
    print(f"CPU, 1 thread, value + value-and-gradient, ns per point: CLI {cli_ns:.1f}, Python "
          f"{py_ns:.1f}, ratio {py_ns / cli_ns:.3f}")


if __name__ == "__main__":
    main()
