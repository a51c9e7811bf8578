"""Adapt a mesh to a circle moving across it, one warm-started adapt() per time step, the
level set a Python function on numpy arrays; write a ParaView series (open moving.pvd).

    python3 moving_level_set.py [STEPS]    # writes moving-0000.vtu ... and moving.pvd
"""
import sys
import time

import numpy as np

import neomesh


def write_pvd(path, files, times):
    """ParaView's collection of the steps' files."""
    entries = "\n".join(f'    <DataSet timestep="{t:g}" file="{f}"/>' for f, t in zip(files, times))
    with open(path, "w") as out:
        out.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                  f"  <Collection>\n{entries}\n  </Collection>\n</VTKFile>\n")


def main(steps=6):
    steps = int(steps)
    mesh = neomesh.Mesh.generate("box-quad", size=32)  # [-1,1]², 1024 quadrilaterals
    optimizer = neomesh.Optimizer(mesh)
    files, times = [], np.linspace(0.0, 1.0, steps)
    for step, t in enumerate(times):
        centre = np.array([-0.5 + t, 0.25 * np.sin(np.pi * t)])

        def distance(points):  # all cell centroids at once: an (n, 2) array
            return np.linalg.norm(points - centre, axis=1) - 0.3

        start = time.perf_counter()
        result = optimizer.adapt(distance)
        q = result.volume_ratio
        sj = result.quality_after["metrics"]["scaled_jacobian"]["min"]
        files.append(f"moving-{step:04d}.vtu")
        mesh.write(files[-1])
        print(f"step {step}, t = {t:.2f}: {result.iterations} iterations, "
              f"Q in [1/2, 2] for {100 * q['fraction_in_0.5_2']:.1f}% of the cells, "
              f"min scaled Jacobian {sj:.3f}, {time.perf_counter() - start:.2f} s; "
              f"wrote {files[-1]}")
    write_pvd("moving.pvd", files, times)
    print("wrote moving.pvd")


if __name__ == "__main__":
    main(*sys.argv[1:])
