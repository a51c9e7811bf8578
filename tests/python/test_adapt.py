"""neomesh.adapt with size fields from Python callables (vectorised), expressions and the
built-in shapes; errors in the callable reach the caller."""
import numpy as np
import pytest

import neomesh


def circle(points):
    return np.sqrt(points[:, 0] ** 2 + points[:, 1] ** 2) - 0.5


def test_a_callable_is_evaluated_on_all_centroids_at_once_and_equals_its_expression():
    calls = []

    def field(points):
        calls.append(points.shape)
        return circle(points)

    by_function = neomesh.Mesh.generate("box-quad", size=16)
    r = neomesh.adapt(by_function, field, max_iter=40)
    assert calls and all(shape == (by_function.num_cells, 2) for shape in calls)
    assert len(calls) <= r.iterations + 2  # one call per update of the desired volumes

    by_expression = neomesh.Mesh.generate("box-quad", size=16)
    r2 = neomesh.adapt(by_expression, "sqrt(x^2+y^2)-0.5", max_iter=40)
    assert r.iterations == r2.iterations
    np.testing.assert_allclose(by_function.points, by_expression.points, rtol=0, atol=1e-12)
    assert r2.size_field == "|sqrt(x^2+y^2)-0.5|"
    # cells crowd at the circle
    q = by_expression.quality()["volume"]
    r_cell = np.hypot(*np.stack([by_expression.points[c].mean(axis=0)
                                 for c in by_expression.cells[0][1]]).T)
    assert q[np.abs(r_cell - 0.5) < 0.1].mean() < 0.5 * q[np.abs(r_cell - 0.5) > 0.4].mean()


def test_the_built_in_shapes_equal_their_expressions():
    a = neomesh.Mesh.generate("box-tri", size=8)
    b = neomesh.Mesh.generate("box-tri", size=8)
    neomesh.adapt(a, neomesh.SizeField.circle(0.0, 0.0, 0.5), max_iter=20)
    neomesh.adapt(b, neomesh.SizeField.level_set("sqrt(x^2+y^2)-0.5"), max_iter=20)
    np.testing.assert_allclose(a.points, b.points, rtol=0, atol=1e-12)


def test_a_failing_callable_raises_its_exception_and_leaves_the_mesh():
    mesh = neomesh.Mesh.generate("box-quad", size=8)
    before = mesh.points.copy()

    def broken(points):
        raise ZeroDivisionError("no sizes today")

    with pytest.raises(ZeroDivisionError, match="no sizes"):
        neomesh.adapt(mesh, broken)
    np.testing.assert_array_equal(mesh.points, before)

    with pytest.raises(neomesh.Error, match="returned 3 values for 64 points"):
        neomesh.adapt(mesh, lambda p: np.ones(3))
    with pytest.raises(neomesh.Error, match="size field is negative|desired sizes must be positive"):
        neomesh.adapt(mesh, lambda p: np.full(len(p), np.nan))
    np.testing.assert_array_equal(mesh.points, before)


def test_fit_to_a_level_set():
    mesh = neomesh.Mesh.generate("box-tri", size=16)
    phi = neomesh.LevelSet.circle(0.1, 0.0, 0.45)
    r = neomesh.adapt(mesh, phi, fit=True)
    assert r.fit["facets"] > 10 and r.fit["max_distance"] < 1e-10


def test_an_optimizer_writes_its_fields_and_the_fitted_interface(tmp_path):
    import meshio

    mesh = neomesh.Mesh.generate("box-tri", size=16)
    opt = neomesh.Optimizer(mesh)
    r = opt.adapt(neomesh.LevelSet.circle(0.1, 0.0, 0.45), fit=True)
    opt.write(str(tmp_path / "fit.vtu"))
    m = meshio.read(tmp_path / "fit.vtu")
    assert {"Q", "energy", "desired_volume", "inside"} <= set(m.cell_data)
    assert {"interface", "phi"} <= set(m.point_data)
    on = m.point_data["interface"] == 1
    assert on.sum() == r.fit["vertices"]
    np.testing.assert_allclose(m.point_data["phi"][on], 0, atol=1e-10)


def test_per_cell_values_from_a_file(tmp_path):
    mesh = neomesh.Mesh.generate("box-quad", size=8)
    values = np.where(np.arange(mesh.num_cells) < mesh.num_cells // 2, 1.0, 4.0)
    np.savetxt(tmp_path / "sizes.txt", values)
    r = neomesh.adapt(mesh, neomesh.SizeField.read_cell_values(str(tmp_path / "sizes.txt")))
    assert r.size_field.startswith("per-cell values from")
    v = mesh.quality()["volume"]
    assert v[mesh.num_cells // 2:].mean() > 2 * v[:mesh.num_cells // 2].mean()
