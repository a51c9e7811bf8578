#!/usr/bin/python3
"""Acceptance of anisotropic adaptation: interpolation error of a front, uniform/iso/aniso.

Does `adapt --stretch HN,HT,W` (cells of size HN across the circle/sphere and HT along it,
within W of it) interpolate a steep front better than isotropic adaptation with the same cells?

Three meshes with the same cells, all on [0,1]^d:
  (a) uniform: `neomesh generate box-quad|box-tri|box-hex|box-tet --cells N`, whose [-1,1]^d is
      mapped onto [0,1]^d (written back with meshio as Gmsh 2.2, physical groups kept);
  (b) isotropic: `neomesh adapt sq.msh --circle 0.5,0.5,0.3 -o iso.vtu --quiet --report iso.json`
      (3D: cube.msh, --sphere 0.5,0.5,0.5,0.3);
  (c) anisotropic: the same with `--stretch HN,HT,W` (default 0.005,0.05,0.02); skipped, with a
      message, while the binary does not know --stretch.
For each: the max and L2 error of the P1 (triangles, tetrahedra) or multilinear Q1 (quads,
hexahedra, through the reference map) interpolant of f = tanh((r - 0.3)/0.005), r the distance
to the centre, from its vertex values, against f itself at a k^d grid of reference points per
cell, edges included (simplices: the grid's points inside the reference simplex); the report's
cells, iterations, seconds and min scaled Jacobian; the aspect ratio along the circle/sphere of
the cells whose centroid is within --band of it (see aspect_ratios); and the two verdicts
"anisotropic max error <= 1/2 isotropic" and "<= 1/4 uniform" (exit status 1 if one is "no").

    bench/anisotropic_adapt.py build/neomesh --cells 100                 # 2D quads (default)
    bench/anisotropic_adapt.py build/neomesh --cells 40 --cell-type tri
    bench/anisotropic_adapt.py build/neomesh --dim 3 --cells 16          # hexahedra, k = 4
    bench/anisotropic_adapt.py build/neomesh --cells 100 --keep build/aniso -- --no-guard

After an isotropic adaptation the quality guard pulls back the vertices of cells that ended
below scaled Jacobian 0.2 and the input's worst cell; after a metric adaptation it does not run.
The script says when the guard moved vertices of (b); `-- --no-guard` measures the adaptation
itself.
Options after `--` go to both `neomesh adapt` runs. The binary: the first argument, else
NEOMESH, else build/neomesh next to this script's parent. Needs numpy and meshio 5.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
CENTRE, RADIUS = 0.5, 0.3
# --cell-type -> (generate case, meshio cell type); the dimension follows from the type.
CELL_TYPES = {"quad": ("box-quad", "quad"), "tri": ("box-tri", "triangle"),
              "hex": ("box-hex", "hexahedron"), "tet": ("box-tet", "tetra")}
DIM_OF = {"quad": 2, "tri": 2, "hex": 3, "tet": 3}
# Corners of the tensor-product reference cells [0,1]^d in meshio's (= VTK's, = Gmsh's) order.
TENSOR_CORNERS = {
    "quad": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float),
    "hexahedron": np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                            [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float),
}


def neomesh_binary(given):
    if given:
        return given
    return os.environ.get("NEOMESH") or os.path.join(HERE, "..", "build", "neomesh")


# ---------------------------------------------------------------------------------------------
# Interpolation error

def reference_rule(kind, k):
    """Sample points of the reference cell, the shape functions and their gradients there, and
    quadrature weights. Tensor cells: the k^d grid on [0,1]^d with composite-trapezoid weights
    (sum 1). Simplices: the lattice points i/(k-1) of the same grid inside the unit simplex,
    equal weights summing to its volume (1/2, 1/6); det J is constant there, so this is the mean
    of the samples times the cell's volume. Returns xi (s,d), N (s,n), dN (s,n,d), w (s)."""
    t = np.linspace(0.0, 1.0, k)
    if kind in TENSOR_CORNERS:
        corners = TENSOR_CORNERS[kind]
        d = corners.shape[1]
        xi = np.stack(np.meshgrid(*[t] * d, indexing="ij"), axis=-1).reshape(-1, d)
        w1 = np.full(k, 1.0 / (k - 1))
        w1[[0, -1]] *= 0.5
        w = np.prod(np.stack(np.meshgrid(*[w1] * d, indexing="ij"), axis=-1).reshape(-1, d), 1)
        # N_i(xi) = prod_a l_ia(xi_a), l = xi_a at a corner coordinate 1, 1 - xi_a at 0.
        factors = np.where(corners[None] == 1.0, xi[:, None, :], 1.0 - xi[:, None, :])  # s,n,d
        sign = 2.0 * corners - 1.0
        N = np.prod(factors, axis=2)
        dN = np.empty(factors.shape)
        for b in range(d):
            others = np.prod(np.delete(factors, b, axis=2), axis=2)
            dN[:, :, b] = sign[None, :, b] * others
        return xi, N, dN, w
    d = {"triangle": 2, "tetra": 3}[kind]
    grid = np.stack(np.meshgrid(*[np.arange(k)] * d, indexing="ij"), axis=-1).reshape(-1, d)
    xi = grid[grid.sum(axis=1) <= k - 1] / (k - 1.0)
    N = np.hstack([1.0 - xi.sum(axis=1, keepdims=True), xi])
    dN = np.broadcast_to(np.vstack([-np.ones(d), np.eye(d)]), (len(xi), d + 1, d))
    w = np.full(len(xi), (0.5 if d == 2 else 1.0 / 6.0) / len(xi))
    return xi, N, dN, w


def interpolation_error(points, cells, kind, f, k):
    """Max and L2 error of the vertex interpolant of f against f at the samples of
    reference_rule in every cell (L2 by that quadrature, sum_s w_s det J(xi_s) e(xi_s)^2).
    Also returns the quadrature's total volume and the smallest det J at a sample (checks)."""
    _, N, dN, w = reference_rule(kind, k)
    values = f(points)
    chunk = max(1, 2_000_000 // len(w))   # bounds memory: ~2e6 samples at a time
    max_err, l2_squared, volume, min_det = 0.0, 0.0, 0.0, np.inf
    for start in range(0, len(cells), chunk):
        c = cells[start:start + chunk]
        x = points[c]                                             # cells, n, d
        samples = np.einsum("sn,cnd->csd", N, x)
        jacobian = np.einsum("snb,cnd->csdb", dN, x)              # dx_d / dxi_b
        det = np.linalg.det(jacobian)
        exact = f(samples.reshape(-1, samples.shape[-1])).reshape(samples.shape[:2])
        err = np.einsum("sn,cn->cs", N, values[c]) - exact
        max_err = max(max_err, float(np.abs(err).max()))
        l2_squared += float(np.sum(w * det * err ** 2))
        volume += float(np.sum(w * det))
        min_det = min(min_det, float(det.min()))
    return max_err, np.sqrt(l2_squared), volume, min_det


def front(dim, delta):
    """f(x) = tanh((r - RADIUS)/delta), r the distance of x to the centre (CENTRE, ...)."""
    return lambda x: np.tanh((np.linalg.norm(x - CENTRE, axis=1) - RADIUS) / delta)


# ---------------------------------------------------------------------------------------------
# Meshes

def read(path):
    # Naming the format: for .msh meshio tries ANSYS first and prints its failure.
    return meshio.read(path, file_format="gmsh" if path.endswith(".msh") else None)


def read_mesh(path, dim, kind):
    """Points (first dim coordinates) and the cells of the given type (all blocks)."""
    mesh = read(path)
    blocks = [b.data for b in mesh.cells if b.type == kind]
    if not blocks:
        sys.exit(f"{path}: no {kind} cells (has {sorted({b.type for b in mesh.cells})})")
    return np.ascontiguousarray(mesh.points[:, :dim], dtype=float), np.vstack(blocks)


def generate_unit_box(neomesh, case, cells, dim, path, jitter=0.0):
    """`neomesh generate CASE --cells N`, its bounding box mapped onto [0,1]^dim. neomesh's box
    cases span [-1,1]^d; the mesh is rewritten with meshio (Gmsh 2.2 keeps the physical groups)
    so that the circle/sphere and the widths given in absolute units mean what they say."""
    raw = path[:-4] + "-generated.msh"
    command = [neomesh, "generate", case, "--cells", str(cells), "-o", raw]
    if jitter:
        command += ["--jitter", str(jitter)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    mesh = read(raw)
    lo, hi = mesh.points[:, :dim].min(axis=0), mesh.points[:, :dim].max(axis=0)
    if not (np.allclose(lo, 0.0) and np.allclose(hi, 1.0)):
        mesh.points[:, :dim] = (mesh.points[:, :dim] - lo) / (hi - lo)
    meshio.write(path, mesh, file_format="gmsh22", binary=False)
    return lo, hi


def aspect_ratios(points, cells, kind, dim, band):
    """Aspect of the cells whose centroid lies within band of the circle/sphere, in the frame of
    the centroid: n = radial unit vector, tangents perpendicular to it.
      2D (quads, triangles): extent of the vertices along the tangent over their extent along n
             (a quad's edges would not do: where the grid crosses the circle diagonally a cell
             stretched along it is a rhombus, whose four edges are equally long);
      3D (hexahedra, tetrahedra): largest over smallest extent of the vertices along n, t1, t2,
             t1 = n x (the axis least aligned with n) normalized, t2 = n x t1 (so >= 1, and
             blind to which direction is long: a plain shape measure).
    Returns the array of ratios (may be empty)."""
    x = points[cells]                                        # cells, n, d
    centroid = x.mean(axis=1)
    radial = centroid - CENTRE
    distance = np.linalg.norm(radial, axis=1)
    near = np.abs(distance - RADIUS) <= band
    x, n = x[near], radial[near] / distance[near, None]
    if dim == 2:
        frame = [np.stack([-n[:, 1], n[:, 0]], axis=1), n]  # tangent, normal
    else:
        axis = np.eye(3)[np.argmin(np.abs(n), axis=1)]
        t1 = np.cross(n, axis)
        t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
        frame = [n, t1, np.cross(n, t1)]
    extent = np.stack([np.ptp(np.einsum("cvd,cd->cv", x, e), axis=1) for e in frame], axis=1)
    if dim == 2:
        return extent[:, 0] / extent[:, 1]
    return extent.max(axis=1) / extent.min(axis=1)


# ---------------------------------------------------------------------------------------------
# Runs

def adapt(neomesh, mesh, out, report, surface, extra, log):
    """Runs neomesh adapt; returns None, or the message of a failure to report instead of
    raising (an unknown option), re-raising any other failure with its output shown."""
    command = [neomesh, "adapt", mesh, *surface, "-o", out, "--quiet", "--report", report,
               *extra]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(log, "w") as f:
        f.write(" ".join(command) + "\n" + done.stdout)
    if done.returncode == 0:
        return None
    if "--stretch" in done.stdout and "unknown" in done.stdout:
        return done.stdout.strip().splitlines()[-1]
    sys.exit(f"failed ({done.returncode}): {' '.join(command)}\n{done.stdout}")


def self_test(neomesh, work, cells, k):
    """Hidden --self-test: on generated meshes of every cell type (axis-aligned, and jittered
    so that quads/hexes are not parallelograms), a linear f is interpolated to round-off and
    the quadrature's volume is 1; on the axis-aligned quads/hexes the multilinear x*y(*z), which
    Q1 contains, is too. The trapezoid rule integrates det J exactly on quads and affine cells,
    not on a jittered hexahedron (det J of degree 2 per direction): a looser volume check there.
    Returns the number of failed checks."""
    failures = 0
    for name, (case, kind) in CELL_TYPES.items():
        dim = DIM_OF[name]
        linear = lambda x: 1.0 + x @ np.array([2.0, -3.0, 0.5])[:x.shape[1]]
        multilinear = lambda x: np.prod(x, axis=1)
        n = min(cells, 12)
        for jitter in (0.0, 0.2):
            path = os.path.join(work, f"self-test-{name}-{jitter}.msh")
            generate_unit_box(neomesh, case, n, dim, path, jitter)
            points, cell_nodes = read_mesh(path, dim, kind)
            tests = [("linear", linear)]
            if kind in TENSOR_CORNERS and not jitter:
                tests.append(("x*y" + ("*z" if dim == 3 else ""), multilinear))
            for label, f in tests:
                max_err, l2, volume, min_det = interpolation_error(points, cell_nodes, kind, f, k)
                volume_tol = 1e-4 if kind == "hexahedron" and jitter else 1e-12
                ok = (max_err < 1e-13 and l2 < 1e-13 and abs(volume - 1.0) < volume_tol
                      and min_det > 0)
                failures += not ok
                print(f"{'ok  ' if ok else 'FAIL'} {case:8} --cells {n} jitter {jitter}: {label:7} "
                      f"max {max_err:.1e}, L2 {l2:.1e}, volume - 1 {volume - 1.0:+.1e}, "
                      f"min det J {min_det:.2e}")
        # The check can fail: P1 does not contain x*y.
        if kind == "triangle":
            max_err = interpolation_error(points, cell_nodes, kind, multilinear, k)[0]
            print(f"     (P1 on triangles misses x*y by {max_err:.1e}, as it should)")
    return failures


def main():
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     epilog="Options after -- go to both neomesh adapt runs.")
    parser.add_argument("neomesh", nargs="?", help="the binary (default: NEOMESH, build/neomesh)")
    parser.add_argument("--dim", type=int, choices=(2, 3), help="default 2, or that of --cell-type")
    parser.add_argument("--cell-type", choices=sorted(CELL_TYPES),
                        help="2D: quad (default) or tri; 3D: hex (default) or tet")
    parser.add_argument("--cells", type=int, help="cells per direction (default 2D 100, 3D 16)")
    parser.add_argument("--stretch", default="0.005,0.05,0.02",
                        help="HN,HT,W for the anisotropic run (default %(default)s)")
    parser.add_argument("--delta", type=float, default=0.005,
                        help="width of the front in f = tanh((r - 0.3)/delta) (default 0.005)")
    parser.add_argument("--samples", type=int,
                        help="k: reference points per direction per cell (default 2D 8, 3D 4)")
    parser.add_argument("--band", type=float,
                        help="aspect of the cells with centroid within this of the circle/sphere "
                             "(default 2D 0.01, 3D 0.02)")
    parser.add_argument("--keep", metavar="DIR", help="write the meshes and reports here")
    parser.add_argument("--self-test", action="store_true", help=argparse.SUPPRESS)
    a = parser.parse_args(argv)
    dim = DIM_OF[a.cell_type] if a.cell_type else (a.dim or 2)
    if a.dim and a.dim != dim:
        parser.error(f"--cell-type {a.cell_type} is not a {a.dim}D cell")
    cell_type = a.cell_type or ("quad" if dim == 2 else "hex")
    case, kind = CELL_TYPES[cell_type]
    cells = a.cells or (100 if dim == 2 else 16)
    k = a.samples or (8 if dim == 2 else 4)
    band = a.band if a.band is not None else (0.01 if dim == 2 else 0.02)
    neomesh = neomesh_binary(a.neomesh)

    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or tmp
        os.makedirs(work, exist_ok=True)
        if a.self_test:
            return 1 if self_test(neomesh, work, cells, k) else 0

        stem = "sq" if dim == 2 else "cube"
        mesh = os.path.join(work, stem + ".msh")
        lo, hi = generate_unit_box(neomesh, case, cells, dim, mesh)
        if dim == 2:
            surface = ["--circle", f"{CENTRE},{CENTRE},{RADIUS}"]
        else:
            surface = ["--sphere", f"{CENTRE},{CENTRE},{CENTRE},{RADIUS}"]
        runs = [("uniform (a)", mesh, None)]
        skipped = None
        for label, name, more in [("isotropic (b)", "iso", []),
                                  ("anisotropic (c)", "aniso", ["--stretch", a.stretch])]:
            out, report = os.path.join(work, name + ".vtu"), os.path.join(work, name + ".json")
            failure = adapt(neomesh, mesh, out, report, surface + more, extra,
                            os.path.join(work, name + ".log"))
            if failure:
                skipped = failure
                continue
            with open(report) as f:
                runs.append((label, out, json.load(f)))

        f = front(dim, a.delta)
        box = "×".join(["[0,1]"] * dim)
        where = (f"circle ({CENTRE}, {CENTRE}) r {RADIUS}" if dim == 2
                 else f"sphere ({CENTRE}, {CENTRE}, {CENTRE}) r {RADIUS}")
        sampling = (f"{k}^{dim} grid" if kind in TENSOR_CORNERS
                    else f"{len(reference_rule(kind, k)[0])} lattice points of the {k}^{dim} grid")
        print(f"{case} --cells {cells} ({'×'.join([str(cells)] * dim)} cells; generated on "
              f"[{lo[0]:g},{hi[0]:g}]^{dim}, mapped onto {box}), {where}, "
              f"f = tanh((r − {RADIUS})/{a.delta:g}), samples per cell: {sampling}, "
              f"--stretch {a.stretch}, adapt options: {' '.join(extra) or '(defaults)'}\n")
        print("| mesh | cells | max error | L2 error | ratio max error to uniform | iterations "
              "| seconds | min SJ |")
        print("|---|---|---|---|---|---|---|---|")
        input_points = read_mesh(mesh, dim, kind)[0]
        errors, aspects, notes = {}, [], []
        for label, path, report in runs:
            points, cell_nodes = read_mesh(path, dim, kind)
            max_err, l2, volume, min_det = interpolation_error(points, cell_nodes, kind, f, k)
            if min_det <= 0 or abs(volume - 1.0) > 1e-3:
                notes.append(f"{label}: det J ≤ 0 at a sample ({min_det:.2e}) or volume "
                             f"{volume:.6f} ≠ 1: the errors are not trustworthy")
            errors[label] = max_err
            ratio = max_err / errors["uniform (a)"]
            if report is None:
                # The input's quality is in either report ("quality_before").
                before = runs[1][2]["quality_before"] if len(runs) > 1 else None
                min_sj = (f"{before['metrics']['scaled_jacobian']['min']:.3f}" if before
                          else "—")
                print(f"| {label} | {len(cell_nodes):,} | {max_err:.3g} | {l2:.3g} "
                      f"| {ratio:.3f} | — | — | {min_sj} |")
            else:
                sj = report["quality_after"]["metrics"]["scaled_jacobian"]["min"]
                print(f"| {label} | {report['cells']:,} | {max_err:.3g} | {l2:.3g} "
                      f"| {ratio:.3f} | {report['result']['iterations']} "
                      f"| {report['seconds']:.2f} | {sj:.3f} |")
                moved = np.abs(points - input_points).max() if len(points) == len(input_points) \
                    else np.inf
                if moved == 0.0:
                    guard = report.get("quality_guard") or {}
                    notes.append(f"{label}: the output is the input mesh, no vertex moved (the "
                                 f"quality guard pulled back {guard.get('vertices_moved', '?')} "
                                 f"of {report['vertices']} vertices; try `-- --no-guard`)")
            r = aspect_ratios(points, cell_nodes, kind, dim, band)
            short = label.split(" ")[0]
            aspects.append(f"{short} median {np.median(r):.2f}, min {r.min():.2f} ({len(r)} cells)"
                           if len(r) else f"{short}: no cells")
        if skipped:
            print(f"| anisotropic (c) | skipped: {skipped} | | | | | | |")
        for label, _, report in runs[1:]:
            moved = (report.get("quality_guard") or {}).get("vertices_moved", 0)
            if moved:
                notes.append(f"{label}: the quality guard pulled back {moved} vertices "
                             f"(`-- --no-guard` measures the adaptation alone)")

        what = ("tangential / normal extent" if dim == 2 else
                "largest / smallest extent along normal and tangents")
        print(f"\naspect along the {'circle' if dim == 2 else 'sphere'}, cells with centroid "
              f"within {band:g} ({what}): " + "; ".join(aspects))
        for note in notes:
            print(f"warning: {note}")
        if "anisotropic (c)" not in errors:
            print("anisotropic max error ≤ ½ isotropic: n/a (anisotropic run skipped)")
            print("anisotropic max error ≤ ¼ uniform: n/a (anisotropic run skipped)")
            return 0
        to_iso = errors["anisotropic (c)"] / errors["isotropic (b)"]
        to_uniform = errors["anisotropic (c)"] / errors["uniform (a)"]
        print(f"anisotropic max error ≤ ½ isotropic: {'yes' if to_iso <= 0.5 else 'no'} "
              f"({to_iso:.2f})")
        print(f"anisotropic max error ≤ ¼ uniform: {'yes' if to_uniform <= 0.25 else 'no'} "
              f"({to_uniform:.2f})")
        return 0 if to_iso <= 0.5 and to_uniform <= 0.25 else 1


if __name__ == "__main__":
    sys.exit(main())
