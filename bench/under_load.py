#!/usr/bin/env python3
"""Whole-program times on a quiet machine and beside busy processes (`sh -c 'while :; do :;
done'`, one per core taken), to check that neomesh does not collapse when it shares the machine
(docs/benchmarks.md, "Threads and a shared machine"). Median of --runs runs per row.

    bench/under_load.py              # the rows below, quiet and with 1 and 2 busy processes
    bench/under_load.py --runs 5 --busy 1

Environment: NEOMESH (default build/neomesh next to this script). Needs gmsh for the channel.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
NEOMESH = os.environ.get("NEOMESH", os.path.join(HERE, "..", "build", "neomesh"))


def meshes(tmp):
    """(name, input, command after `neomesh`) per row."""
    channel = os.path.join(tmp, "channel.msh")
    subprocess.run(["gmsh", "-2", os.path.join(HERE, "..", "examples", "cylinder_channel.geo"),
                    "-setnumber", "Mesh.RecombineAll", "1", "-setnumber", "Mesh.Algorithm", "8",
                    "-setnumber", "Mesh.SubdivisionAlgorithm", "1", "-format", "msh41", "-o",
                    channel], check=True, capture_output=True)
    rows = [("channel quads, adapt", channel, ["adapt", channel, "--circle", "0.2,0.2,0.05"])]
    for name, generate in [("quads 300², smooth", ["box-quad", "--cells", "300", "--jitter", "0.25"]),
                           ("hexes 40³, smooth", ["box-hex", "--cells", "40", "--jitter", "0.12"])]:
        path = os.path.join(tmp, name.split(",")[0].replace(" ", "-") + ".msh")
        subprocess.run([NEOMESH, "generate", *generate, "-o", path], check=True, capture_output=True)
        rows.append((name, path, ["smooth", path, "--boundary", "fixed"]))
    return rows


def timed(command, out, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run([NEOMESH, *command, "-o", out, "--force", "--quiet"], check=True,
                       capture_output=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--busy", type=int, nargs="*", default=[1, 2])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.msh")
        print("| run | cells | quiet s | " + " | ".join(f"{b} busy s (×)" for b in args.busy) + " |")
        print("|---|---:|---:|" + "---:|" * len(args.busy))
        for name, path, command in meshes(tmp):
            quiet = timed(command, out, args.runs)
            cols = []
            for busy in args.busy:
                hogs = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(busy)]
                try:
                    t = timed(command, out, args.runs)
                finally:
                    for h in hogs:
                        h.kill()
                cols.append(f"{t:.2f} ({t / quiet:.2f})")
            cells = subprocess.run([NEOMESH, "quality", path], capture_output=True, text=True
                                   ).stdout.split("cells: ")[1].split(",")[0]
            print(f"| {name} | {cells} | {quiet:.2f} | " + " | ".join(cols) + " |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
