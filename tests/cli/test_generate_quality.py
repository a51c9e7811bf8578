"""neomesh generate + quality as a user runs them: the thesis' Table 5.1 mesh, every case
at a small level, and the errors for inconsistent size options."""
import concurrent.futures
import json
import os

import pytest

from conftest import neomesh, needs_mpi


def output(proc):
    return proc.stdout + proc.stderr


@pytest.fixture(scope="module")
def square(module_tmp):
    """The thesis' Table 5.1 mesh, square-midpoint at level 3: (path, quality's output)."""
    square = os.path.join(module_tmp, "square.msh")
    out = output(neomesh("generate", "square-midpoint", "--level", "3", "-o", square,
                         timeout=120))
    assert "256 quadrilaterals, 289 vertices" in out, f"generate reported: {out}"
    return square


def test_quality_of_the_table_5_1_mesh(square, tmp):
    report = os.path.join(tmp, "quality.json")
    out = output(neomesh("quality", square, "--json", report, timeout=120))
    assert "256 quadrilaterals" in out, f"quality reported: {out}"
    assert "inverted cells: 0," in out, f"quality reported: {out}"
    with open(report) as f:
        summary = json.load(f)
    assert summary["cells"]["total"] == 256, f"json: {summary}"
    assert summary["cells"]["quadrilateral"] == 256, f"json: {summary}"
    assert summary["inverted"] == 0 and summary["degenerate"] == 0, f"json: {summary}"
    assert abs(summary["metrics"]["volume"]["mean"] - 1 / 256) < 1e-12, f"json: {summary}"


@needs_mpi
def test_two_ranks_print_the_summary_of_one(square):
    # The mesh is distributed, the statistics reduced over the ranks.
    one = output(neomesh("quality", square, timeout=120))
    two = neomesh("quality", square, ranks=2, timeout=120)
    assert two.stdout == one, f"2 ranks printed:\n{two.stdout}\n1 rank:\n{one}"


# Every case at a small level: (level, the cell count generate and quality print).
CASES = {
    "square-midpoint": (1, "16 quadrilaterals"),
    "cube-midpoint": (1, "64 hexahedra"),
    "square-random": (3, "64 quadrilaterals"),
    "transition": (2, "80 quadrilaterals"),
    "circle-quad": (2, "80 quadrilaterals"),
    "triangle-equilateral": (3, "64 triangles"),
    "triangle-curved": (2, "128 triangles"),
    "box-quad": (2, "16 quadrilaterals"),
    "box-tri": (2, "32 triangles"),
    "box-hex": (2, "64 hexahedra"),
    "box-tet": (2, "384 tetrahedra"),
}


def generate_and_check(name, directory):
    level, cells = CASES[name]
    path = os.path.join(directory, f"{name}.msh")
    out = output(neomesh("generate", name, "--level", str(level), "--rotate", "27", "-o", path,
                         timeout=120))
    assert cells in out, f"generate {name}: {out}"
    out = output(neomesh("quality", path, timeout=120))
    assert cells in out and "inverted cells: 0," in out, f"quality of {name}: {out}"


@pytest.fixture(scope="module")
def generated(module_tmp):
    """Every case generated and measured, side by side (each run mostly waits for MPI
    start-up): a future per case."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        futures = {name: pool.submit(generate_and_check, name, module_tmp) for name in CASES}
        concurrent.futures.wait(futures.values())
    return futures


@pytest.mark.parametrize("name", CASES)
def test_every_case_has_its_cells_and_none_inverted(generated, name):
    generated[name].result()


def test_inconsistent_size_options(tmp):
    square = os.path.join(tmp, "square.msh")
    out = output(neomesh("generate", "transition", "--cells", "4", "-o", square, expect=1,
                         timeout=120))
    assert "--level" in out, f"transition --cells: {out}"
    neomesh("generate", "box-quad", "-o", square, expect=1, timeout=120)
    neomesh("generate", "no-such-case", "--level", "1", "-o", square, expect=1, timeout=120)
