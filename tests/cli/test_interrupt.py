"""Ctrl-C tells the truth and leaves no partial output. SIGINT arrives while neomesh writes:

1. the output mesh: its temporary file is removed, an existing output file keeps its old
   content, and neomesh says that no output file was written;
2. the JSON report, after the mesh was renamed into place: the new mesh stays, no report or
   temporary file is left, and neomesh says which file was written.

To catch neomesh in the middle of a write, the test puts a FIFO where neomesh's temporary
file will be (`.NAME.tmp-PID` beside the target, see src/core/atomic_file.cpp): opening it
blocks until the signal comes, and only neomesh's clean-up removes it. Both cases run
serially and, with NEOMESH_MPIEXEC, under `mpiexec -n 2` (the signal goes to mpiexec; rank
0 writes the files).
"""
import os
import signal
import stat
import subprocess
import time

import pytest

from conftest import NEOMESH, RANKS, mpiexec, neomesh


def rank_zero(launcher_pid):
    """The process of rank 0 among mpiexec's children (the one that writes the outputs)."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                parent = int(f.read().rsplit(")", 1)[1].split()[1])
            with open(f"/proc/{entry}/environ", "rb") as f:
                environment = f.read().split(b"\0")
        except (OSError, IndexError, ValueError):
            continue
        if parent == launcher_pid and (b"OMPI_COMM_WORLD_RANK=0" in environment
                                       or b"PMI_RANK=0" in environment):
            return int(entry)
    pytest.fail(f"no rank 0 among the children of mpiexec (pid {launcher_pid})")


def wait_until_blocked_on_fifo(pid, timeout=60.0):
    """Waits until `pid` sleeps in open() on a FIFO with no reader (the kernel's
    wait_for_partner, fifo_open in older kernels): a fixed pause was not enough on a loaded
    machine, where the signal then came before the write and the FIFO stayed behind."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            with open(f"/proc/{pid}/wchan") as f:
                if f.read().strip() in ("wait_for_partner", "fifo_open"):
                    return
        except OSError:
            return  # no /proc: fall back on the time it already took
        time.sleep(0.05)
    pytest.fail(f"neomesh (pid {pid}) did not reach the write within {timeout:.0f} s")


def interrupt_while_writing(tmp, mesh, blocked, ranks):
    """Runs a short smooth that writes out.vtu, then report.json; SIGINT while it blocks on
    opening the temporary file of `blocked`. Returns stderr."""
    out = os.path.join(tmp, "out.vtu")
    report = os.path.join(tmp, "report.json")
    # Open MPI's mpiexec forwards the signal, then SIGKILLs the ranks 1 s later; under CI's
    # load that came once before rank 0 had printed its message (stderr empty). 10 s makes the
    # test check neomesh's handler rather than the machine's load.
    launcher = mpiexec(ranks, "--mca", "odls_base_sigkill_timeout", "10")
    proc = subprocess.Popen(
        [*launcher, NEOMESH, "smooth", mesh, "-o", out, "--no-table", "--no-practical",
         "--tol", "0", "--rtol", "0", "--max-iter", "3", "--report", report],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # The outputs were checked (and their probe files removed) before iteration 1.
        for line in proc.stdout:
            if line.startswith("iteration 1:"):
                break
        writer = proc.pid if ranks == 1 else rank_zero(proc.pid)
        fifo = os.path.join(tmp, f".{blocked}.tmp-{writer}")
        os.mkfifo(fifo)
        # The run ends after 3 iterations; then the write blocks on the FIFO.
        for line in proc.stdout:
            if line.startswith("stopped after"):
                break
        wait_until_blocked_on_fifo(writer)
        assert proc.poll() is None, f"neomesh ended before the interrupt: {proc.returncode}"
        # There is a temporary file to remove: neomesh's clean-up, not the test, must do it.
        assert stat.S_ISFIFO(os.stat(fifo).st_mode), f"{fifo} is not the test's FIFO"
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        pytest.fail("neomesh did not stop within 30 s of SIGINT")
    finally:
        if proc.poll() is None:  # a failed check: no neomesh left blocked on the FIFO
            proc.kill()
            proc.communicate()
    assert proc.returncode != 0, f"exit code 0 after SIGINT; stderr {err!r}"
    assert not os.path.exists(fifo), f"the temporary file was not removed: {fifo}"
    return err


@pytest.fixture
def inputs(tmp):
    """A mesh to smooth, and an existing out.vtu holding "the old output\n"."""
    neomesh("generate", "square-random", "--level", "6", "-o", os.path.join(tmp, "random.msh"),
            timeout=60)
    with open(os.path.join(tmp, "out.vtu"), "w") as f:
        f.write("the old output\n")
    return tmp


@pytest.mark.parametrize("ranks", RANKS)
def test_interrupted_in_the_mesh_write(inputs, ranks):
    tmp = inputs
    err = interrupt_while_writing(tmp, os.path.join(tmp, "random.msh"), "out.vtu", ranks)
    assert "interrupted; no output file was written" in err, \
        f"{ranks} rank(s), interrupted in the mesh write: stderr {err!r}"
    with open(os.path.join(tmp, "out.vtu")) as f:
        assert f.read() == "the old output\n", "the old output file was changed"
    assert sorted(os.listdir(tmp)) == ["out.vtu", "random.msh"], \
        f"files left behind: {sorted(os.listdir(tmp))}"


@pytest.mark.parametrize("ranks", RANKS)
def test_interrupted_in_the_report_write(inputs, ranks):
    tmp = inputs
    err = interrupt_while_writing(tmp, os.path.join(tmp, "random.msh"), "report.json", ranks)
    assert "interrupted; written completely before the interrupt: " in err \
        and "out.vtu; no other output file was written" in err, \
        f"{ranks} rank(s), interrupted in the report write: stderr {err!r}"
    with open(os.path.join(tmp, "out.vtu"), "rb") as f:  # binary: the arrays are raw bytes
        assert b"<VTKFile" in f.read(), "out.vtu is not the new output"
    assert sorted(os.listdir(tmp)) == ["out.vtu", "random.msh"], \
        f"files left behind: {sorted(os.listdir(tmp))}"
