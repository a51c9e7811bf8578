#!/usr/bin/python3
"""The 3D adapt-sphere case of issue 5 as a benchmark: [-1,1]³ hexahedra adapted to the sphere
of radius 0.7 around the origin, checked against the issue's three criteria:
  - at least 90% of the cells with Q = actual/desired volume in [0.5, 2],
  - minimum scaled Jacobian ≥ 0.2,
  - mean volume of the cells within 0.05 of the sphere ≤ 1/4 of that of the cells farther
    than 0.5 (distances of the cell centroids).

    bench/adapt_sphere.py --cells 64            # one line of results, exit 1 if a criterion fails
    bench/adapt_sphere.py --cells 32 --ranks 2

Q and the shape come from neomesh's JSON report, volumes and centroids from the output .vtu
(read with python3-meshio). Environment: NEOMESH, NEOMESH_MPIEXEC as for bench/run.py.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
RADIUS = 0.7


def neomesh_binary():
    if os.environ.get("NEOMESH"):
        return os.environ["NEOMESH"]
    return os.path.join(HERE, "..", "build", "neomesh")


def near_far_ratio(vtu):
    mesh = meshio.read(vtu)
    cells = mesh.cells[0].data
    volume = mesh.cell_data["volume"][0]
    centroid = mesh.points[cells].mean(axis=1)
    distance = np.abs(np.linalg.norm(centroid, axis=1) - RADIUS)
    near, far = volume[distance <= 0.05], volume[distance > 0.5]
    return near.mean() / far.mean()


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cells", type=int, default=32, help="hexahedra per direction")
    p.add_argument("--ranks", type=int, default=1, help="MPI processes")
    p.add_argument("--workdir", default=os.path.join(HERE, "..", "build", "bench"))
    p.add_argument("extra", nargs="*", help="more options for neomesh adapt (after --)")
    a = p.parse_args()

    neomesh = neomesh_binary()
    os.makedirs(a.workdir, exist_ok=True)
    stem = os.path.join(a.workdir, f"adapt-sphere-{a.cells}")
    if not os.path.exists(stem + ".msh"):
        subprocess.run([neomesh, "generate", "box-hex", "--cells", str(a.cells), "-o",
                        stem + ".msh"], check=True, stdout=subprocess.DEVNULL)
    launcher = []
    if a.ranks > 1:
        launcher = [os.environ.get("NEOMESH_MPIEXEC", "mpiexec"), "--allow-run-as-root",
                    "-n", str(a.ranks)]
    start = time.monotonic()
    with open(stem + ".log", "w") as log:
        subprocess.run([*launcher, neomesh, "adapt", stem + ".msh", "-o", stem + ".vtu", "--force",
                        "--no-table", "--sphere", f"0,0,0,{RADIUS}", "--report", stem + ".json",
                        *a.extra], check=True, stdout=log, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    with open(stem + ".json") as f:
        report = json.load(f)
    history = report["result"]["history"]
    within = report["volume_ratio"]["fraction_in_0.5_2"]
    min_sj = report["quality_after"]["metrics"]["scaled_jacobian"]["min"]
    ratio = near_far_ratio(stem + ".vtu")
    passed = within >= 0.9 and min_sj >= 0.2 and ratio <= 0.25
    print(f"adapt-sphere {a.cells}^3 ({report['cells']:,} hexahedra, {a.ranks} rank(s)): "
          f"{len(history)} iterations, {sum(h['armijo_steps'] for h in history)} Armijo steps, "
          f"updates after {report['picard']['update_iterations']}; "
          f"Q in [0.5, 2]: {100 * within:.1f}%; min scaled Jacobian {min_sj:.3f}; "
          f"near/far volume {ratio:.3f}; {wall:.0f} s, peak RSS {report['peak_rss_mib']:.0f} MiB; "
          f"criteria {'met' if passed else 'MISSED'}")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
