"""The readers' bad inputs as a user meets them: every file of tests/data/fuzz-regressions
(inputs that once crashed, hung or were misread), a FIFO with no writer and /dev/zero, given
to `neomesh convert`. Each must exit 1 within the timeout with exactly one line on stderr,
`neomesh: error: <file>...`, and write nothing; a few also on 2 ranks. Run with
NEOMESH=path/to/neomesh (NEOMESH_MPIEXEC for the 2-rank cases)."""
import concurrent.futures
import os
import subprocess
import sys
import tempfile

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
REGRESSIONS = os.path.abspath(os.path.join(SOURCE, "tests", "data", "fuzz-regressions"))
MPI_CASES = ["nodes_twice_second_smaller.msh", "bin_v41_ends_after_entities.msh",
             "node_tag_wraps_at_2pow32.msh", "feat_deep_nesting.xml", "fifo.msh"]
RAW = ["stoi", "bad_alloc", "max_size()", "basic_string", "std::", "terminate called",
       "MPI_ABORT", "Sanitizer", "Segmentation"]


def run(path, directory, ranks):
    command = [NEOMESH, "convert", path, "-o", os.path.join(directory, "out.vtu")]
    if ranks > 1:
        command = [os.environ["NEOMESH_MPIEXEC"], "--allow-run-as-root", "--oversubscribe",
                   "-n", str(ranks)] + command
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


def main():
    with tempfile.TemporaryDirectory() as tmp:
        fifo = os.path.join(tmp, "fifo.msh")
        os.mkfifo(fifo)  # nobody writes: opening it for reading would block
        inputs = sorted(os.path.join(REGRESSIONS, f) for f in os.listdir(REGRESSIONS)
                        if f.endswith((".msh", ".xml"))) + [fifo, "/dev/zero"]
        cases = [(path, 1) for path in inputs]
        if os.environ.get("NEOMESH_MPIEXEC"):
            cases += [(path, 2) for path in inputs if os.path.basename(path) in MPI_CASES]
        failures = []
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            jobs = []
            for i, (path, ranks) in enumerate(cases):
                directory = os.path.join(tmp, f"case{i}")
                os.mkdir(directory)
                jobs.append(pool.submit(run, path, directory, ranks))
            for job in jobs:
                failures += job.result()
        if failures:
            sys.exit(f"{len(failures)} failures:\n" + "\n".join(failures))
        print(f"{len(cases)} cases ok")


if __name__ == "__main__":
    main()
