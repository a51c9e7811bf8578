#!/usr/bin/env python3
"""Q distributions of adapt-circle for the powers p = 1..4 (thesis Figs. 6.4/6.5; issue 5):
[-1,1]² with n×n quads adapted to the circle of radius 0.7, v = floor + d^p. Runs
`neomesh generate box-quad` and `neomesh adapt --power p --report r.json` and prints one
markdown table from the program's own reports (docs/adaptivity.md has the numbers).

    bench/adapt_powers.py                  # 64×64, neomesh's defaults
    bench/adapt_powers.py --cells 32 -- --thesis

Environment: NEOMESH (the binary; default build-adapt3d/neomesh next to this script's parent,
then `neomesh` on PATH). Stdlib only.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def neomesh_binary():
    if os.environ.get("NEOMESH"):
        return os.environ["NEOMESH"]
    local = os.path.join(HERE, "..", "build-adapt3d", "neomesh")
    if os.path.exists(local):
        return local
    found = shutil.which("neomesh")
    if not found:
        sys.exit("neomesh not found: set NEOMESH to the binary")
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=64, help="cells per direction")
    parser.add_argument("--powers", default="1,2,3,4", help="comma-separated powers p")
    parser.add_argument("extra", nargs="*", help="more options for `neomesh adapt` (after --)")
    args = parser.parse_args()
    binary = neomesh_binary()
    with tempfile.TemporaryDirectory() as tmp:
        mesh = os.path.join(tmp, "box.msh")
        subprocess.run([binary, "generate", "box-quad", "--cells", str(args.cells), "-o", mesh],
                       check=True, stdout=subprocess.DEVNULL)
        print(f"quads {args.cells}², options: {' '.join(args.extra) or '(defaults)'}\n")
        print("| p | iterations | updates after | Q in [0.5,2] | Q min / median / max "
              "| min scaled Jac. | inverted | time |")
        print("|---|---|---|---|---|---|---|---|")
        for p in args.powers.split(","):
            report = os.path.join(tmp, f"p{p}.json")
            subprocess.run([binary, "adapt", mesh, "-o", os.path.join(tmp, f"p{p}.vtu"),
                            "--circle", "0,0,0.7", "--power", p, "--no-table",
                            "--report", report] + args.extra, check=True,
                           stdout=subprocess.DEVNULL)
            with open(report) as f:
                r = json.load(f)
            q = r["volume_ratio"]
            after = r["quality_after"]
            updates = ",".join(str(k) for k in r["picard"]["update_iterations"])
            print(f"| {p} | {r['result']['iterations']} | {updates} "
                  f"| {100 * q['fraction_in_0.5_2']:.1f}% "
                  f"| {q['min']:.2f} / {q['median']:.2f} / {q['max']:.3g} "
                  f"| {after['metrics']['scaled_jacobian']['min']:.3f} "
                  f"| {after['inverted']} | {r['seconds']:.1f} s |")


if __name__ == "__main__":
    main()
