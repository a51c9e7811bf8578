#!/usr/bin/python3
"""Curved (second-order) meshes smoothed on 1 and on 2 MPI processes, side by side: Gmsh's
meshes of tests/cli/test_curved.py (a ring of triangle6, quadrilateral8 and quadrilateral9, a
ball of tetrahedron10, a cylinder of hexahedron20 and hexahedron27), finer, every node inside
jittered (a fixed seed), and Mesquite's quadratic meshes (../shared/corpus). Per mesh: the largest
distance between the two runs' nodes over the mesh's size, the energies' relative difference, the
iteration counts, and whether each run returned the input (the certificate's or the guard's
verdict). One Markdown table; the runs are tests/cli/test_mpi_curved.py's.

    bench/mpi_curved.py
    bench/mpi_curved.py --only tet10-folded

Needs python3-gmsh, meshio and pytest. Environment: NEOMESH (default build/neomesh),
NEOMESH_MPIEXEC (default mpiexec).
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
os.environ.setdefault("NEOMESH", os.path.join(HERE, "..", "build", "neomesh"))
os.environ.setdefault("NEOMESH_MPIEXEC", "mpiexec")
sys.path.insert(0, os.path.join(HERE, "..", "tests", "cli"))
from test_mpi_curved import QUADRATIC, compare, jittered  # noqa: E402

# name: (test_curved's case, cell size, jitter (of the size), smooth options)
GMSH = {
    "tri6": ("tri6", 0.3, 0.05, []),
    "quad8": ("quad8", 0.3, 0.05, []),
    "quad9": ("quad9", 0.3, 0.05, []),
    # With the guard the optimum's worst cell is below the input's: the input comes back.
    "tet10": ("tet10", 0.4, 0.02, ["--no-guard"]),
    "tet10-guarded": ("tet10", 0.4, 0.02, []),
    "tet10-folded": ("tet10", 0.4, 0.05, []),  # 4 cells folded: untangled first
    "hex20": ("hex20", 0.4, 0.02, []),
    "hex27": ("hex27", 0.4, 0.02, []),
}
MESQUITE = [(2, "horseShoe0"), (2, "horseShoe1"), (2, "triPart"), (2, "quadPart"),
            (2, "homogeneousPart"), (3, "hex3Dpart"), (3, "6x6x6-hex20"), (3, "hexCyl"),
            (3, "cutCube")]


def row(tmp, name, mesh, options):
    c = compare(tmp, mesh, options)
    serial, parallel = c["reports"]
    return (f"| {name} | {serial['cells']} | {c['apart']:.1e} | {c['energies']:.1e} | "
            f"{serial['result']['iterations']}, {parallel['result']['iterations']} | "
            f"{serial['curved']['input_returned']}, {parallel['curved']['input_returned']} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", help="one mesh, by its name in the table")
    args = parser.parse_args()
    print("| mesh | cells | nodes apart / size | energies apart | iterations (1, 2) "
          "| input returned (1, 2) |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, (case, size, amount, options) in GMSH.items():
            if args.only in (None, name):
                print(row(tmp, name, jittered(tmp, case, amount, size), options), flush=True)
        for dim, name in MESQUITE:
            if args.only in (None, name):
                print(row(tmp, name, QUADRATIC.format(dim, name), []), flush=True)


if __name__ == "__main__":
    main()
