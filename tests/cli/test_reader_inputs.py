"""The readers' bad inputs as a user meets them: every file of tests/data/fuzz-regressions
(inputs that once crashed, hung or were misread), a FIFO with no writer and /dev/zero, given
to `neomesh convert`. Each must exit 1 within the timeout with exactly one line on stderr,
`neomesh: error: <file>...`, and write nothing; a few also on 2 ranks. Run with
NEOMESH=path/to/neomesh (NEOMESH_MPIEXEC for the 2-rank cases)."""
import concurrent.futures
import os
import subprocess

import pytest

from conftest import DATA, MPIEXEC, NEOMESH, mpiexec, needs_mpi

REGRESSIONS = os.path.join(DATA, "fuzz-regressions")
MPI_CASES = ["nodes_twice_second_smaller.msh", "bin_v41_ends_after_entities.msh",
             "node_tag_wraps_at_2pow32.msh", "feat_deep_nesting.xml", "fifo.msh"]
RAW = ["stoi", "bad_alloc", "max_size()", "basic_string", "std::", "terminate called",
       "MPI_ABORT", "Sanitizer", "Segmentation"]


def run_case(path, directory, ranks):
    command = [*mpiexec(ranks), NEOMESH, "convert", path, "-o",
               os.path.join(directory, "out.vtu")]
    try:
        proc = subprocess.run(command, capture_output=True, text=True, timeout=60,
                              cwd=directory)
    except subprocess.TimeoutExpired:
        return [f"{path} ({ranks} ranks): no answer within 60 s"]
    errors = []
    lines = proc.stderr.splitlines()
    name = os.path.basename(path)
    if proc.returncode != 1:
        errors.append(f"exit {proc.returncode}")
    if len(lines) != 1 or not lines[0].startswith("neomesh: error: ") or name not in lines[0]:
        errors.append(f"stderr is not one error line naming {name}")
    errors += [f"raw text '{raw}'" for raw in RAW if raw in proc.stderr]
    if os.listdir(directory) != []:
        errors.append(f"left {os.listdir(directory)}")
    return [f"{path} ({ranks} ranks): {e}\n{proc.stderr[:2000]}" for e in errors]


# The inputs: the regression files, a FIFO (made in the test's directory) and /dev/zero.
INPUTS = sorted(os.path.join(REGRESSIONS, f) for f in os.listdir(REGRESSIONS)
                if f.endswith((".msh", ".xml", ".vtk"))) + ["{tmp}/fifo.msh", "/dev/zero"]
CASES = [pytest.param(path, 1, id=os.path.basename(path)) for path in INPUTS] + \
        [pytest.param(path, 2, id=f"{os.path.basename(path)} (-n 2)", marks=needs_mpi)
         for path in INPUTS if os.path.basename(path) in MPI_CASES]


def test_every_mpi_case_is_an_input():
    assert set(MPI_CASES) <= {os.path.basename(path) for path in INPUTS}


@pytest.fixture(scope="module")
def failures(module_tmp):
    """Each case's failures, by (input, ranks): the cases run two at a time, each in a
    directory of its own."""
    fifo = os.path.join(module_tmp, "fifo.msh")
    os.mkfifo(fifo)  # nobody writes: opening it for reading would block
    cases = [(path, 1) for path in INPUTS]
    if MPIEXEC:
        cases += [(path, 2) for path in INPUTS if os.path.basename(path) in MPI_CASES]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        jobs = {}
        for i, (path, ranks) in enumerate(cases):
            directory = os.path.join(module_tmp, f"case{i}")
            os.mkdir(directory)
            jobs[(path, ranks)] = pool.submit(run_case, path.format(tmp=module_tmp), directory,
                                              ranks)
        return {case: job.result() for case, job in jobs.items()}


@pytest.mark.parametrize("path, ranks", CASES)
def test_one_error_line_and_nothing_written(failures, path, ranks):
    found = failures[(path, ranks)]
    assert not found, "\n".join(found)
