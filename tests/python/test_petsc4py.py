"""A petsc4py DMPlex in (Mesh.from_dm) and out (Mesh.dm), and the moved coordinates back into
the caller's DM by its vertex numbering."""
import numpy as np
import pytest

import neomesh

PETSc = pytest.importorskip("petsc4py.PETSc")


def distorted_box(n=4):
    dm = PETSc.DMPlex().createBoxMesh([n, n], simplex=False, interpolate=True)
    x = dm.getCoordinatesLocal()
    a = x.getArray().reshape(-1, 2)
    centre = np.argmin(np.abs(a - 0.5).sum(axis=1))
    a[centre] = [0.42, 0.45]  # the vertex at (0.5, 0.5) moved
    dm.setCoordinatesLocal(x)
    return dm, centre


def vertex_numbers(dm):
    """Each vertex's number as DMPlexGetVertexNumbering gives it (−(n+1) for ghosts)."""
    numbers = dm.getVertexNumbering().getIndices()
    return np.where(numbers < 0, -(numbers + 1), numbers)


def test_a_dmplex_goes_in_and_the_moved_coordinates_come_back():
    dm, centre = distorted_box()
    mesh = neomesh.Mesh.from_dm(dm)
    assert (mesh.dim, mesh.num_cells, mesh.num_vertices) == (2, 16, 25)
    number = vertex_numbers(dm)
    before = dm.getCoordinatesLocal().getArray().reshape(-1, 2).copy()
    np.testing.assert_array_equal(mesh.points[number], before)

    result = neomesh.smooth(mesh, boundary="fixed", targets="ideal", sizes="uniform")
    assert result.quality_after["metrics"]["scaled_jacobian"]["min"] > 0.999
    x = dm.getCoordinatesLocal()
    x.setArray(mesh.points[number].ravel())
    dm.setCoordinatesLocal(x)
    after = dm.getCoordinatesLocal().getArray().reshape(-1, 2)
    np.testing.assert_allclose(after[centre], [0.5, 0.5], atol=1e-6)
    # the caller's DM was not changed by from_dm or smooth, only by the copy back above
    assert np.abs(before[centre] - [0.42, 0.45]).max() == 0


def test_the_meshs_own_dmplex_comes_out_at_the_current_coordinates():
    mesh = neomesh.Mesh.generate("box-tri", size=4)
    neomesh.smooth(mesh)
    dm = mesh.dm
    assert isinstance(dm, PETSc.DMPlex) and dm.getDimension() == 2
    start, end = dm.getHeightStratum(0)
    assert end - start == mesh.num_cells
    coords = dm.getCoordinatesLocal().getArray().reshape(-1, 2)
    np.testing.assert_array_equal(np.sort(coords, axis=0), np.sort(mesh.points, axis=0))


def test_another_dm_is_refused():
    da = PETSc.DMDA().create([8], dof=1)
    with pytest.raises(neomesh.Error):
        neomesh.Mesh.from_dm(da)
    with pytest.raises(TypeError):
        neomesh.Mesh.from_dm("not a DM")
