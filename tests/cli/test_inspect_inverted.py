"""`quality` and `render` read meshes with inverted cells, as their help says: quality counts
them (table and JSON), render draws them in red, on top of the cells they overlap. Serially
and, with NEOMESH_MPIEXEC, on 2 ranks. smooth --no-untangle refuses such a mesh, naming the
cell by its position and by the element number of the file."""
import json
import os
import re
import subprocess
import sys
import tempfile

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
MPIEXEC = os.environ.get("NEOMESH_MPIEXEC")
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DATA = os.path.abspath(os.path.join(SOURCE, "tests", "data"))
INVERTED = os.path.join(DATA, "bad_inverted.msh")  # 26 triangles, element 13 inverted
RED = "rgb(85%,11%,11%)"  # render.cpp's kInvalidColour in cairo's SVG


def check(condition, message):
    if not condition:
        sys.exit(message)


def run(launcher, args, expect_ok=True):
    proc = subprocess.run([*launcher, NEOMESH, *args], capture_output=True, text=True,
                          timeout=120)
    check((proc.returncode == 0) == expect_ok,
          f"neomesh {' '.join(args)}: exit {proc.returncode}\n{proc.stdout}\n{proc.stderr}")
    return proc


def main():
    launchers = [[]]
    if MPIEXEC:
        launchers.append([MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-n", "2"])
    for launcher in launchers:
        ranks = 1 if not launcher else 2
        with tempfile.TemporaryDirectory() as tmp:
            report = os.path.join(tmp, "q.json")
            proc = run(launcher, ["quality", INVERTED, "--json", report])
            check("inverted cells: 1," in proc.stdout, f"quality says {proc.stdout!r}")
            with open(report) as f:
                check(json.load(f)["inverted"] == 1, "the JSON does not count 1 inverted cell")

            picture = os.path.join(tmp, "inverted.svg")
            run(launcher, ["render", INVERTED, "-o", picture])
            with open(picture) as f:
                svg = f.read()
            # One red cell and the red legend patch; the cell is drawn after every coloured
            # cell, since it overlaps its neighbours, which would hide it.
            check(svg.count(RED) >= 2, f"render did not draw the inverted cell in red ({RED})")
            fills = [(m.start(), m.group(1)) for m in re.finditer(r"fill:(rgb\([^)]*\))", svg)]
            coloured = [at for at, colour in fills  # not red, not a grey of text or frame
                        if colour != RED and len(set(colour[4:-1].split(","))) > 1]
            check(coloured and max(coloured) < svg.find(RED),
                  "the inverted cell is drawn before other cells")

            proc = run(launcher, ["smooth", INVERTED, "-o", os.path.join(tmp, "out.msh"),
                                  "--no-untangle"], expect_ok=False)
            check("cell 0 (0-based; element 13 of the file), a triangle, is inverted"
                  in proc.stderr, f"smooth says {proc.stderr!r}")
            check(len(proc.stderr.splitlines()) == 1, f"not one line: {proc.stderr!r}")
        print(f"quality and render read an inverted mesh on {ranks} rank(s)")


if __name__ == "__main__":
    main()
