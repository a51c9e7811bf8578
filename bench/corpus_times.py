#!/usr/bin/env python3
"""Whole-program time of `neomesh smooth` with the defaults on every mesh of the shared corpus
(FEAT3's meshes with their chart files, Mesquite's VTK legacy files). Prints a Markdown summary
(how many runs end within 1, 10 and 60 s) and the slowest runs, for docs/benchmarks.md. Time it
on a quiet machine: one run per mesh, one at a time.

    bench/corpus_times.py build/neomesh [--corpus ../shared/corpus] [--time-limit 60] [--slowest 15]

A run that ends with a one-line error (second-order cells, polygons, surface meshes, a
malformed file) counts apart;
`--time-limit` is passed to neomesh, which then ends with the best mesh so far. Stdlib only.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "cli"))
from feat3_charts import CHARTS  # noqa: E402


def meshes(corpus):
    feat3 = os.path.join(corpus, "feat3")
    for path in sorted(glob.glob(os.path.join(feat3, "*.xml"))):
        name = os.path.basename(path)[:-4]
        if "_chart_" in name:
            continue
        charts = [os.path.join(feat3, CHARTS[name])] if name in CHARTS else []
        yield "feat3/" + name, charts + [path]
    mesquite = os.path.join(corpus, "mesquite")
    for path in sorted(glob.glob(os.path.join(mesquite, "**", "*.vtk"), recursive=True)):
        yield "mesquite/" + os.path.relpath(path, mesquite), [path]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("neomesh")
    parser.add_argument("--corpus", default=os.path.join(HERE, "..", "..", "shared", "corpus"))
    parser.add_argument("--time-limit", type=float, default=60)
    parser.add_argument("--slowest", type=int, default=15)
    a = parser.parse_args()
    if not os.path.isdir(a.corpus):
        sys.exit(f"no corpus at {a.corpus}")
    runs, refused, failed = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        out, report = os.path.join(tmp, "out.vtu"), os.path.join(tmp, "r.json")
        for name, inputs in meshes(a.corpus):
            if os.path.exists(report):
                os.remove(report)
            start = time.monotonic()
            p = subprocess.run([a.neomesh, "smooth", *inputs, "-o", out, "--quiet", "--force",
                                "--report", report, "--time-limit", str(a.time_limit)],
                               capture_output=True, text=True)
            seconds = time.monotonic() - start
            if p.returncode == 0 and os.path.exists(report):
                with open(report) as f:
                    r = json.load(f)
                runs.append((seconds, name, r["cells"], r["result"]["iterations"],
                             r["result"]["stop_reason"]))
            elif p.returncode == 1 and p.stderr.count("\n") <= 1:
                refused.append(name)
            else:
                failed.append((name, p.returncode, p.stderr.strip()[-200:]))
    runs.sort(reverse=True)
    within = lambda s: sum(1 for r in runs if r[0] <= s)
    print(f"{len(runs)} runs ended with exit 0, {len(refused)} with a one-line error (cells or "
          f"surfaces neomesh does not optimize, malformed files, an untangling that cannot "
          f"succeed), {len(failed)} otherwise; of the {len(runs)}: {within(1)} within 1 s, "
          f"{within(10)} within 10 s, {within(a.time_limit + 5)} within {a.time_limit + 5:g} s; "
          f"total {sum(r[0] for r in runs):.0f} s.\n")
    print("| mesh | cells | iterations | s | stop |")
    print("|---|---:|---:|---:|---|")
    for seconds, name, cells, iterations, stop in runs[:a.slowest]:
        print(f"| {name} | {cells:,} | {iterations} | {seconds:.2f} | {stop} |")
    for name, code, err in failed:
        print(f"\nfailed: {name} (exit {code}): {err}")


if __name__ == "__main__":
    main()
