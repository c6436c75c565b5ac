#!/usr/bin/python3
"""The targets of the paper's Table 2 ratio in one run: t7/t8 and t12/t8 (one thread, float and
double, 32^3 x 2 and 96^3 x 2) and the two-thread speedup of the batch API (float, 96^3 x 2,
400,000 points per call), from bench_evaluation's medians with the cases interleaved.

    scripts/table2_ratios.py [build/bench/bench_evaluation] [--repetitions 5]

Prints a Markdown table and the load average before and after (`uptime`): the ratios mean
something only on an idle machine. docs/performance.md, "Ratios and the paper's Table 2".
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile


def load():
    with open("/proc/loadavg", encoding="ascii") as f:
        return " ".join(f.read().split()[:3])


def medians(binary, pattern, repetitions, threads_env):
    """{benchmark name: median real time in ms} of the cases matching pattern."""
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        env = dict(os.environ)
        if threads_env:
            env["BOXGEN_THREADS"] = "1"
        run = subprocess.run(
            [binary, f"--benchmark_filter={pattern}",
             f"--benchmark_repetitions={repetitions}",
             "--benchmark_enable_random_interleaving=true",
             "--benchmark_report_aggregates_only=true",
             f"--benchmark_out={out.name}", "--benchmark_out_format=json"],
            env=env, check=False, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"table2_ratios: {binary} failed:\n{run.stderr}")
        with open(out.name, encoding="utf-8") as f:
            report = json.load(f)
    # One repetition has no aggregates: its single run is the median.
    kind = "median" if repetitions > 1 else None
    times = {}
    for b in report["benchmarks"]:
        if b.get("aggregate_name") == kind:
            assert b["time_unit"] == "ms", b["time_unit"]
            times[b["run_name"]] = b["real_time"]
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary", nargs="?", default="build/bench/bench_evaluation")
    parser.add_argument("--repetitions", type=int, default=5)
    args = parser.parse_args()
    if not os.access(args.binary, os.X_OK):
        sys.exit(f"table2_ratios: no benchmark program at {args.binary} (build bench_evaluation)")
    before = load()
    batch = medians(args.binary, "batch/M(7|8|12)/(float|double)/N:(32|96)$", args.repetitions,
                    True)
    threads = medians(args.binary, "threads/M(7|8|12)/float/N:96/", args.repetitions, False)
    after = load()
    print(f"load average before: {before}; after: {after}")
    print(f"{args.repetitions} repetitions, median, cases interleaved\n")
    print("| case | M12 / M8 / M7 (ms) | t7/t8 | t12/t8 |")
    print("|---|---|---|---|")
    for precision in ("float", "double"):
        for n in (32, 96):
            t = {f: batch[f"batch/{f}/{precision}/N:{n}"] for f in ("M7", "M8", "M12")}
            print(f"| {precision} {n}^3 x 2 | {t['M12']:.3g} / {t['M8']:.3g} / {t['M7']:.3g} "
                  f"| {t['M7'] / t['M8']:.2f} | {t['M12'] / t['M8']:.2f} |")
    print("\n| float 96^3 x 2, 400,000 points | 1 thread (ms) | 2 threads (ms) | speedup |")
    print("|---|---|---|---|")
    for f in ("M7", "M8", "M12"):
        one = threads[f"threads/{f}/float/N:96/threads:1/real_time"]
        two = threads[f"threads/{f}/float/N:96/threads:2/real_time"]
        print(f"| {f} | {one:.3g} | {two:.3g} | {one / two:.2f} |")


if __name__ == "__main__":
    main()
