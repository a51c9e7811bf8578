"""neomesh smooth on 2 MPI ranks gives the serial result: final coordinates within 1e-8, the
same number of iterations ±1, and an output file with the input's vertices and cells (the
.msh writer keeps the input numbering), for a 2D and a 3D case and a tangled 2D case."""
import json
import os
import subprocess
import sys
import tempfile

NEOMESH = os.environ.get("NEOMESH", "neomesh")
MPIEXEC = os.environ.get("NEOMESH_MPIEXEC")


def run(cmd):
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {proc.returncode}\nstdout:\n{proc.stdout}\n"
                 f"stderr:\n{proc.stderr}")


def read_msh(path):
    """Vertex coordinates (by node tag) and cells (as node tags) of a Gmsh 4.1 ASCII file
    with one node block, as neomesh writes it."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    count = int(lines[i + 1].split()[1])
    tags = [int(t) for t in lines[i + 3:i + 3 + count]]
    coords = [tuple(float(x) for x in line.split())
              for line in lines[i + 3 + count:i + 3 + 2 * count]]
    nodes = dict(zip(tags, coords))
    i = lines.index("$Elements")
    blocks, i = int(lines[i + 1].split()[0]), i + 2
    cells = []
    for _ in range(blocks):
        dim, _, _, n = (int(x) for x in lines[i].split())
        cells += [(dim, tuple(int(v) for v in line.split()[1:]))
                  for line in lines[i + 1:i + 1 + n]]
        i += 1 + n
    return nodes, sorted(cells)


def check(condition, message):
    if not condition:
        sys.exit(message)


def compare(tmp, name, generate, options):
    mesh = os.path.join(tmp, f"{name}.msh")
    run([NEOMESH, "generate", *generate, "-o", mesh])
    results = {}
    for ranks in (1, 2):
        out = os.path.join(tmp, f"{name}-{ranks}.msh")
        report = os.path.join(tmp, f"{name}-{ranks}.json")
        launcher = [] if ranks == 1 else [MPIEXEC, "--allow-run-as-root", "--oversubscribe",
                                          "-n", str(ranks)]
        run([*launcher, NEOMESH, "smooth", mesh, "-o", out, "--report", report, "--quiet",
             *options])
        with open(report) as f:
            results[ranks] = (read_msh(out), json.load(f))
    (serial, serial_cells), serial_report = results[1]
    (parallel, parallel_cells), parallel_report = results[2]
    _, input_cells = read_msh(mesh)
    check(serial_cells == input_cells, f"{name}: the serial output changed the cells")
    check(parallel_cells == input_cells, f"{name}: the 2-rank output changed the cells")
    check(serial.keys() == parallel.keys(), f"{name}: the outputs have different vertices")
    worst = max(abs(a - b) for v in serial for a, b in zip(serial[v], parallel[v]))
    check(worst <= 1e-8, f"{name}: 2 ranks moved a vertex {worst:.2e} away from the serial run")
    its = [r["result"]["iterations"] for r in (serial_report, parallel_report)]
    check(abs(its[0] - its[1]) <= 1, f"{name}: {its[0]} iterations serially, {its[1]} on 2 ranks")
    check(parallel_report["processes"] == 2, f"{name}: the report says {parallel_report}")


def main():
    if not MPIEXEC:
        print("NEOMESH_MPIEXEC is not set: nothing to compare")
        return
    with tempfile.TemporaryDirectory() as tmp:
        # Iterate to a tight defect: the practical criterion stops where 1e-8 is not yet met.
        tight = ["--no-practical", "--tol", "1e-11"]
        compare(tmp, "square", ["square-midpoint", "--level", "4"], ["--sizes", "uniform", *tight])
        compare(tmp, "cube", ["cube-midpoint", "--level", "2"], tight)
        # Untangled first (docs/untangling.md), then smoothed to the same optimum.
        compare(tmp, "tangled", ["box-quad", "--cells", "16", "--jitter", "0.6"], tight)


if __name__ == "__main__":
    main()
