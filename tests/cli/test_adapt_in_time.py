"""`adapt --time`: a circle rising through a box of quads, step by step (a geometry that
moves). Each step is warm-started from the one before and prints one summary line; -o OUT.pvd
writes one .vtu per step and ParaView's collection of them (meshio reads every member), and
--picture with a %d pattern draws every step. Warm steps need at most half the iterations of
the cold first step. Bad --time values and patterns: one `neomesh: error:` line, no output."""
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import meshio

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
RISING = "sqrt(x^2+(y-0.3*t)^2)-0.2"
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def run(args, cwd):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=300)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        proc = run([NEOMESH, "generate", "box-quad", "--level", "5", "-o", "box.msh"], tmp)
        check(proc.returncode == 0, "generate box-quad 32x32")
        os.mkdir(os.path.join(tmp, "frames"))
        proc = run([NEOMESH, "adapt", "box.msh", "-o", "rise.pvd", "--levelset", RISING,
                    "--time", "0:1:4", "--picture", "frames/%03d.png"], tmp)
        check(proc.returncode == 0, f"adapt --time ran: {proc.stderr.strip()[:300]}")
        steps = [line for line in proc.stdout.splitlines() if line.startswith("step ")]
        check(len(steps) == 4, f"one summary line per step ({len(steps)})")
        iterations = [int(re.search(r": (\d+) iterations", s).group(1)) for s in steps]
        print(f"iterations per step: {iterations}")
        check(all(2 * i <= iterations[0] for i in iterations[1:]),
              f"warm steps need at most half the cold start's iterations: {iterations}")
        collection = ElementTree.parse(os.path.join(tmp, "rise.pvd")).getroot()
        members = [(float(d.get("timestep")), d.get("file")) for d in collection.iter("DataSet")]
        check([t for t, _ in members] == [0.0, 1 / 3, 2 / 3, 1.0] or
              all(abs(a - b) < 1e-12 for (a, _), b in zip(members, [0, 1 / 3, 2 / 3, 1])),
              f"the collection lists the 4 times: {members}")
        for _, name in members:
            mesh = meshio.read(os.path.join(tmp, name))
            check(len(mesh.points) == 33 * 33 and "Q" in mesh.cell_data,
                  f"meshio reads {name} with its Q field")
        check(sorted(os.listdir(os.path.join(tmp, "frames"))) ==
              ["000.png", "001.png", "002.png", "003.png"], "a picture per step")

        for name, args, words in [
            ("no steps", ["--time", "0:1:0"], ["--time", "between 1"]),
            ("malformed time", ["--time", "0:1"], ["--time", "START:END:STEPS"]),
            ("fractional steps", ["--time", "0:1:2.5"], ["--time", "whole number"]),
            ("unknown variable", ["--time", "0:1:3", "--levelset", "x+s"], ["x+s"]),
            ("picture without a step number", ["--time", "0:1:3", "--picture", "p.png"],
             ["%d"]),
            (".pvd without --time", [], ["--time"]),
        ]:
            options = args if "--levelset" in args else ["--levelset", RISING, *args]
            proc = run([NEOMESH, "adapt", "box.msh", "-o", "bad.pvd", *options], tmp)
            lines = proc.stderr.strip().splitlines()
            left = [f for f in os.listdir(tmp) if f.startswith("bad")]
            check(proc.returncode == 1 and len(lines) == 1 and
                  lines[0].startswith("neomesh: error:") and all(w in lines[0] for w in words)
                  and not left, f"bad input ({name}): {lines[0] if lines else proc.returncode}")
    if failures:
        sys.exit(f"{len(failures)} checks failed")


if __name__ == "__main__":
    main()
