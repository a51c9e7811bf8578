"""neomesh.smooth from Python: the mesh moves in place, the Result is the report, options are
the command line's and refused with its messages, errors are neomesh.Error."""
import os
import re
import signal
import threading
import time

import numpy as np
import pytest

import neomesh
from conftest import DATA


def test_import_gives_the_version():
    assert neomesh.__version__.count(".") == 2


def test_read_gives_points_and_cells_and_smooth_moves_them_in_place():
    mesh = neomesh.Mesh.read(os.path.join(DATA, "square_quad_v41.msh"))
    before = mesh.points.copy()
    assert before.shape == (mesh.num_vertices, 2)
    [(cell_type, cells)] = mesh.cells
    assert cell_type == "quad" and cells.shape == (mesh.num_cells, 4)
    q0 = mesh.quality()
    assert set(q0) >= {"scaled_jacobian", "volume", "inverted"}
    assert len(q0["scaled_jacobian"]) == mesh.num_cells

    result = neomesh.smooth(mesh, boundary="fixed")
    after = mesh.points
    assert np.abs(after - before).max() > 1e-3  # moved
    assert result.iterations == len(result.history) > 0
    assert result.history[0]["k"] >= 0 and "defect" in result.history[0]
    q1 = mesh.quality()
    assert q1["scaled_jacobian"].min() > q0["scaled_jacobian"].min()
    assert result.quality_after["metrics"]["scaled_jacobian"]["min"] == pytest.approx(
        q1["scaled_jacobian"].min(), rel=1e-12)
    # Fixed boundary: the boundary vertices (on the unit square's sides) stayed.
    on_boundary = np.any((np.abs(before) < 1e-12) | (np.abs(before - 1) < 1e-12), axis=1)
    assert on_boundary.sum() > 4
    np.testing.assert_array_equal(after[on_boundary], before[on_boundary])
    assert result.boundary == "fixed"


def test_options_are_the_command_lines_and_the_thesis_preset_yields_to_them():
    mesh = neomesh.Mesh.generate("square-midpoint", size=8)
    r = neomesh.smooth(mesh, thesis=True, max_iter=3, eta=0.5, targets="ideal")
    d = r.to_dict()
    assert d["solver_options"]["max_iterations"] == 3
    assert d["solver_options"]["eta"] == 0.5
    assert d["boundary"] == "fixed"  # the thesis'
    assert d["smooth_options"]["sizes"] == "uniform"
    assert r.iterations <= 3


@pytest.mark.parametrize("options, words", [
    ({"eta": 2.0}, ["eta must be in (0, 1) (got 2)"]),
    ({"lambda": -1}, ["lambda must be positive (got -1)"]),
    ({"boundary": "glued"}, ["boundary:", "unknown boundary mode 'glued'", "fixed or slide"]),
    ({"max_iter": 2.5}, ["max_iter: expected an integer (got 2.5)"]),
    ({"no_such_thing": 1}, ["no_such_thing: no such option of smooth"]),
    ({"shape": {"hole": "circle:0,0,1"}, "boundary": "fixed"}, ["shape needs boundary='slide'"]),
])
def test_a_bad_option_is_refused_naming_it_and_the_mesh_stays(options, words):
    mesh = neomesh.Mesh.generate("square-midpoint", size=4)
    before = mesh.points.copy()
    with pytest.raises(neomesh.OptionError) as e:
        neomesh.smooth(mesh, **options)
    for w in words:
        assert w in str(e.value)
    assert isinstance(e.value, neomesh.Error)
    np.testing.assert_array_equal(mesh.points, before)


def test_library_failures_are_neomesh_errors_with_one_line():
    with pytest.raises(neomesh.Error) as e:
        neomesh.Mesh.read(os.path.join(DATA, "no_such_file.msh"))
    assert "no_such_file.msh" in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(neomesh.Error):
        neomesh.Mesh.read(os.path.join(DATA, "bad_garbage.msh"))


def test_help_lists_every_option_with_its_default():
    doc = neomesh.smooth.__doc__
    words = " ".join(doc.split())
    options = neomesh._neomesh._options("smooth")
    assert len(options) > 30
    for o in options:
        assert f" {o['name']}: {o['type']}" in doc
        assert f"= {o['default']}" in doc
        # the table's help, its flags spelled as keywords
        assert " ".join(re.sub(r"--([a-z-]+)", lambda m: m.group(1).replace("-", "_"),
                               o["help"]).split()) in words
    assert "max_iter: int = 200" in doc and "boundary: str ('fixed' | 'slide') = slide" in doc
    assert "no_guard: bool = False; thesis=True sets True" in doc
    assert "power: float = " in neomesh.adapt.__doc__


def test_a_tangled_mesh_is_untangled():
    mesh = neomesh.Mesh.generate("box-quad", size=12, jitter=0.5)
    assert mesh.quality()["inverted"].sum() > 0
    r = neomesh.smooth(mesh)
    assert r.untangling["inverted_before"] > 0 and r.untangling["inverted_after"] == 0
    assert mesh.quality()["inverted"].sum() == 0


def test_a_progress_callback_sees_every_row_and_its_exception_reaches_the_caller():
    mesh = neomesh.Mesh.generate("square-midpoint", size=8)
    rows = []
    r = neomesh.smooth(mesh, progress=rows.append)
    assert [row["k"] for row in rows] == [row["k"] for row in r.history]
    assert rows == r.history

    mesh = neomesh.Mesh.generate("square-midpoint", size=8)
    before = mesh.points.copy()

    class Stop(Exception):
        pass

    def stop_at_second(row):
        if row["k"] >= 1:
            raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        neomesh.smooth(mesh, progress=stop_at_second)
    np.testing.assert_array_equal(mesh.points, before)
    # and the mesh is usable afterwards
    assert neomesh.smooth(mesh).iterations > 0


def test_optimizer_warm_starts_adapt_over_time_steps():
    mesh = neomesh.Mesh.generate("box-quad", size=16)
    opt = neomesh.Optimizer(mesh)
    field = neomesh.SizeField.level_set("sqrt(x^2+(y+0.5-0.25*t)^2)-0.3")
    iterations = []
    for t in range(3):
        field.set_time(t)
        iterations.append(opt.adapt(field, max_iter=60).iterations)
    assert iterations[1] < iterations[0] and iterations[2] < iterations[0]
    assert set(opt.cell_fields()) >= {"Q", "energy", "desired_volume"}


def test_ctrl_c_raises_keyboard_interrupt_and_leaves_the_mesh():
    mesh = neomesh.Mesh.generate("square-random", size=128)
    before = mesh.points.copy()
    first_row = threading.Event()

    def interrupt():  # Ctrl-C while the C++ code runs, the GIL released
        first_row.wait(60)
        time.sleep(0.05)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt, daemon=True).start()
    rows = []
    with pytest.raises(KeyboardInterrupt):
        neomesh.smooth(mesh, progress=lambda row: (rows.append(row), first_row.set()),
                       thesis=True)  # the thesis' criterion: many iterations
    np.testing.assert_array_equal(mesh.points, before)
    assert len(rows) >= 1


def test_assigning_points_moves_the_vertices_and_the_next_call_starts_there():
    mesh = neomesh.Mesh.generate("box-quad", size=4)
    points = mesh.points
    points[mesh.num_vertices // 2] += [0.1, 0.05]  # the centre vertex (0, 0)
    mesh.points = points
    np.testing.assert_array_equal(mesh.points, points)
    assert mesh.quality()["scaled_jacobian"].min() < 0.99
    neomesh.smooth(mesh, boundary="fixed", targets="ideal", sizes="uniform")
    assert mesh.quality()["scaled_jacobian"].min() > 0.999
    with pytest.raises(neomesh.Error, match="25 × 2"):
        mesh.points = points[:3]
