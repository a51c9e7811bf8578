"""VTK's own readers (python3-vtk9; the tests are skipped without it) read neomesh's .vtu and
.vtk outputs without an error, with the cells and the facets of the groups, the groups' names
as field data, and the input's point and cell data in their types. Run with
NEOMESH=path/to/neomesh."""
import os

import numpy as np
import pytest

from conftest import neomesh, read_mesh

vtk = pytest.importorskip("vtk", reason="python3-vtk9 is not installed")
meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed")
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402


class Errors:
    """Collects what VTK reports as errors or warnings (instead of printing them)."""

    def __init__(self, reader):
        self.messages = []
        reader.AddObserver("ErrorEvent", self.add)
        reader.AddObserver("WarningEvent", self.add)

    def add(self, _obj, event):
        self.messages.append(event)


def read_with_vtk(path):
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") \
        else vtk.vtkUnstructuredGridReader()
    if path.endswith(".vtk"):
        reader.ReadAllScalarsOn()
        reader.ReadAllFieldsOn()
    errors = Errors(reader)
    reader.SetFileName(path)
    reader.Update()
    assert errors.messages == [], errors.messages
    return reader.GetOutput()


@pytest.mark.parametrize("ext", [".vtu", ".vtk"])
def test_vtk_reads_a_smoothed_mesh_with_its_groups_and_data(tmp, ext):
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-tri", "--level", "2", "--jitter", "0.2", "-o", source)
    m = read_mesh(source)
    triangles = [b.data for b in m.cells if b.type == "triangle"][0]
    n = len(m.points)
    inp = os.path.join(tmp, "in.vtu")
    meshio.write(inp, meshio.Mesh(
        m.points, [("triangle", triangles)],
        point_data={"temperature": m.points[:, 0].copy(),
                    "velocity": np.tile(np.float32([1, 2, 3]), (n, 1))},
        cell_data={"material": [np.arange(len(triangles), dtype=np.int32)]}))
    out = os.path.join(tmp, "out" + ext)
    neomesh("smooth", inp, "-o", out, "--quiet")
    grid = read_with_vtk(out)
    assert grid.GetNumberOfPoints() == n
    assert grid.GetNumberOfCells() == len(triangles)  # no groups in this input
    pd, cd = grid.GetPointData(), grid.GetCellData()
    assert np.array_equal(vtk_to_numpy(pd.GetArray("temperature")), m.points[:, 0])
    velocity = pd.GetArray("velocity")
    assert velocity.GetNumberOfComponents() == 3 and velocity.GetDataTypeAsString() == "float"
    material = cd.GetArray("material")
    assert material.GetDataTypeAsString() == "int"
    assert np.array_equal(vtk_to_numpy(material), np.arange(len(triangles)))
    assert cd.GetArray("scaled_jacobian") is not None

    # The groups of the .msh: facets as lines with their tags, names as field data.
    grouped = os.path.join(tmp, "grouped" + ext)
    neomesh("convert", source, "-o", grouped)
    again = os.path.join(tmp, "again" + ext)
    neomesh("convert", grouped, "-o", again)
    for path in (grouped, again):
        grid = read_with_vtk(path)
        lines = sum(1 for c in range(grid.GetNumberOfCells()) if grid.GetCellType(c) == vtk.VTK_LINE)
        facets = sum(len(b.data) for b in m.cells if b.type == "line")
        assert lines == facets > 0
        fd = grid.GetFieldData()
        names = {fd.GetArrayName(k) for k in range(fd.GetNumberOfArrays())}
        assert set(m.field_data) <= names, names
        physical = vtk_to_numpy(grid.GetCellData().GetArray("physical"))
        assert set(physical[len(triangles):]) == \
            {int(v[0]) for v in m.field_data.values() if v[1] == 1}


@pytest.mark.parametrize("ext", [".vtu", ".vtk"])
def test_vtk_reads_fields_given_for_cells_only(tmp, ext):
    """neomesh's fields have a value per cell; the facets of the groups get NaN (.vtu) or 0
    (.vtk: VTK's legacy reader reads no NaN)."""
    source = os.path.join(tmp, "box.msh")
    neomesh("generate", "box-quad", "--level", "2", "--jitter", "0.2", "-o", source)
    out = os.path.join(tmp, "out" + ext)
    neomesh("smooth", source, "-o", out, "--quiet")
    grid = read_with_vtk(out)
    quads = [c for c in range(grid.GetNumberOfCells()) if grid.GetCellType(c) == vtk.VTK_QUAD]
    assert len(quads) == 16 < grid.GetNumberOfCells()
    values = vtk_to_numpy(grid.GetCellData().GetArray("scaled_jacobian")).ravel()
    assert np.all(values[quads] > 0)
    facets = np.delete(values, quads)
    assert np.all(np.isnan(facets)) if ext == ".vtu" else np.all(facets == 0)
