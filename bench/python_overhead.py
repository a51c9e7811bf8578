"""What the Python package costs over the C++ library (docs/benchmarks.md, "Python"):
1. neomesh.smooth on a 10^4-cell mesh against Optimizer::smooth from C++ (bench/smooth_call),
   each timed alone, best of RUNS runs on a freshly read mesh;
2. adapt with a size field given as a Python function on numpy arrays against the same field as
   an expression, on a mesh of about 10^5 vertices (a fixed number of iterations).

    PYTHONPATH=build/python python3 bench/python_overhead.py build [RUNS]
"""
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import neomesh


def best_of(runs, make, call):
    best = float("inf")
    for _ in range(runs):
        subject = make()
        start = time.perf_counter()
        call(subject)
        best = min(best, time.perf_counter() - start)
    return best


def main(build="build", runs=5):
    runs = int(runs)
    folder = tempfile.mkdtemp(prefix="neomesh-python-bench-")
    path = os.path.join(folder, "quads.msh")
    subprocess.run([os.path.join(build, "neomesh"), "generate", "square-random", "--cells", "100",
                    "-o", path], check=True, capture_output=True)
    # Alternately, as below; the C++ program's best of 3 in one process, whose first run pays
    # the process' first touch of its memory, as Python's first run did.
    cpp_seconds = py_seconds = float("inf")
    neomesh.smooth(neomesh.Mesh.read(path))
    for _ in range(runs):
        cpp = subprocess.run([os.path.join(build, "bench", "smooth_call"), path, "3"],
                             check=True, capture_output=True, text=True,
                             env=dict(os.environ)).stdout
        cpp_seconds = min(cpp_seconds, float(cpp.split()[1]))
        py_seconds = min(py_seconds, best_of(3, lambda: neomesh.Mesh.read(path), neomesh.smooth))
    cells = neomesh.Mesh.read(path).num_cells
    print(f"smooth, {cells} quadrilaterals: C++ {cpp_seconds:.4f} s, Python {py_seconds:.4f} s "
          f"({100 * (py_seconds / cpp_seconds - 1):+.1f}%)")

    size = 316  # 316² quads: 10^5 vertices
    make = lambda: neomesh.Mesh.generate("box-quad", size=size)  # noqa: E731
    vertices = make().num_vertices
    options = dict(max_iter=15, no_practical=True)

    def circle(points):
        return np.sqrt(points[:, 0] ** 2 + points[:, 1] ** 2) - 0.5

    # Alternately, so that a machine whose load changes slows both alike.
    expression = function = float("inf")
    for _ in range(runs):
        expression = min(expression, best_of(
            1, make, lambda m: neomesh.adapt(m, "sqrt(x^2+y^2)-0.5", **options)))
        function = min(function, best_of(1, make, lambda m: neomesh.adapt(m, circle, **options)))
    print(f"adapt, {vertices} vertices, 15 iterations: expression {expression:.3f} s, "
          f"Python function {function:.3f} s ({function / expression:.2f}x)")


if __name__ == "__main__":
    main(*sys.argv[1:])
