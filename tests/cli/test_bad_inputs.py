"""Bad inputs and options, as a table: every case must exit with code 1 and exactly one line
on stderr, `neomesh: error: ...`, that names the file or option at fault and carries no
raw standard-library text ("stoi", "std::bad_alloc", ...), and must leave no output file
(nor a temporary one) behind. The cases of MPI_CASES run again under `mpiexec -n 2`
(NEOMESH_MPIEXEC): still one line (rank 0's), exit code 1 and no Open MPI banner.

Each case runs in a directory of its own that holds only what the case needs; after the
run that directory must hold exactly what it held before. Run with NEOMESH=path/to/neomesh.
"""
import concurrent.futures
import os
import random
import shutil
import subprocess
import tempfile

import pytest

from conftest import DATA, MPIEXEC, NEOMESH, mpiexec, needs_mpi

GOOD = os.path.join(DATA, "square_tri_v41.msh")  # 26 triangles
CUBE = os.path.join(DATA, "cube_tet_v41.msh")
LONG = "x" * 30000

# (name, arguments, words the message must contain). In arguments, {data} is tests/data,
# {dir} the case's own directory; "out.msh" etc. are relative to {dir}.
CASES = [
    ("missing file", ["smooth", "nofile.msh", "-o", "out.msh"], ["nofile.msh", "no such file"]),
    ("directory instead of file", ["smooth", "adir.msh", "-o", "out.msh"],
     ["adir.msh", "directory"]),
    ("empty file", ["smooth", "{data}/bad_empty.msh", "-o", "out.msh"],
     ["bad_empty.msh", "empty"]),
    ("truncated .msh", ["smooth", "{data}/bad_truncated.msh", "-o", "out.msh"],
     ["bad_truncated.msh"]),
    ("binary garbage", ["smooth", "garbage.msh", "-o", "out.msh"],
     ["garbage.msh", "not a valid Gmsh mesh file"]),
    ("text garbage", ["quality", "{data}/bad_garbage.msh"], ["bad_garbage.msh"]),
    ("wrong input extension", ["smooth", "mesh.txt", "-o", "out.msh"],
     ["mesh.txt", "unknown mesh format"]),
    ("wrong output extension", ["smooth", GOOD, "-o", "out.txt"],
     ["out.txt", "unknown output format"]),
    ("NaN coordinate", ["smooth", "{data}/bad_nan.msh", "-o", "out.msh"],
     ["bad_nan.msh", "non-finite"]),
    ("inverted cell", ["smooth", "{data}/bad_inverted.msh", "-o", "out.msh", "--no-untangle"],
     ["bad_inverted.msh", "inverted"]),
    ("repeated vertex", ["convert", "{data}/bad_repeated_vertex.msh", "-o", "out.vtu"],
     ["bad_repeated_vertex.msh", "repeated vertex"]),
    ("unsupported element type", ["smooth", "{data}/bad_element_type.msh", "-o", "out.msh"],
     ["bad_element_type.msh", "Gmsh type 92"]),
    ("second-order cells to adapt", ["adapt", "{data}/bad_second_order.msh", "-o", "out.msh",
                                     "--sphere", "0.5,0.5,0.2,0.05"],
     ["bad_second_order.msh", "second-order", "adapt does not take"]),
    ("mixed dimensions", ["smooth", "{data}/bad_mixed_dim.msh", "-o", "out.msh"],
     ["bad_mixed_dim.msh"]),
    ("only lines", ["smooth", "{data}/bad_lines_only.msh", "-o", "out.msh"],
     ["bad_lines_only.msh", "no 2D or 3D cells"]),
    ("truncated FEAT3 file", ["smooth", "{data}/bad_feat_truncated.xml", "-o", "out.msh"],
     ["bad_feat_truncated.xml"]),
    ("unknown option", ["smooth", GOOD, "-o", "out.msh", "--frobnicate"],
     ["--frobnicate", "neomesh smooth --help"]),
    ("missing output option", ["smooth", GOOD], ["--output"]),
    ("no subcommand", [], ["subcommand"]),
    ("bad number", ["smooth", GOOD, "-o", "out.msh", "--lambda", "abc"],
     ["--lambda", "'abc' is not a number"]),
    ("fraction for an integer", ["smooth", GOOD, "-o", "out.msh", "--kmin", "1.5"],
     ["--kmin", "whole number"]),
    ("negative lambda", ["smooth", GOOD, "-o", "out.msh", "--lambda", "-1"],
     ["--lambda", "positive"]),
    ("zero mu", ["smooth", GOOD, "-o", "out.msh", "--mu", "0"], ["--mu", "positive"]),
    ("eta out of range", ["smooth", GOOD, "-o", "out.msh", "--eta", "1.5"], ["--eta", "(0, 1)"]),
    ("alpha0 out of range", ["smooth", GOOD, "-o", "out.msh", "--alpha0", "0"], ["--alpha0"]),
    ("unknown linear solver", ["smooth", GOOD, "-o", "out.msh", "--linear-solver", "umfpack"],
     ["--linear-solver", "umfpack", "amg"]),
    ("unknown rejected direction", ["smooth", GOOD, "-o", "out.msh", "--rejected-direction",
                                    "sideways"], ["--rejected-direction", "sideways", "blend"]),
    ("unknown sizes mode", ["smooth", GOOD, "-o", "out.msh", "--sizes", "tiny"],
     ["--sizes", "tiny"]),
    ("unknown PETSc type", ["smooth", GOOD, "-o", "out.msh", "-hess_ksp_type", "nosuchksp"],
     ["PETSc", "nosuchksp"]),
    ("unwritable output directory", ["smooth", GOOD, "-o", "nodir/out.msh"],
     ["nodir/out.msh", "does not exist"]),
    ("output is a directory", ["convert", GOOD, "-o", "adir.msh"], ["adir.msh", "directory"]),
    ("unwritable report", ["smooth", GOOD, "-o", "out.msh", "--report", "nodir/r.json"],
     ["nodir/r.json"]),
    ("bad picture extension", ["smooth", GOOD, "-o", "out.msh", "--plot-history", "h.jpg"],
     ["h.jpg", ".png or .svg"]),
    ("output same as input", ["smooth", "input.msh", "-o", "input.msh"],
     ["input.msh", "--force"]),
    ("convert onto its input", ["convert", "input.msh", "-o", "./input.msh"],
     ["input.msh", "--force"]),
    ("size field NaN (level set)", ["adapt", GOOD, "-o", "out.msh", "--levelset", "sqrt(-1)"],
     ["NaN", "sqrt(-1)"]),
    ("size field NaN (volumes file)", ["adapt", GOOD, "-o", "out.msh", "--volumes", "sizes.txt"],
     ["NaN", "sizes.txt"]),
    ("max ratio below 1", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0.2",
                           "--max-ratio", "0.5"], ["--max-ratio", "above 1"]),
    ("NaN max ratio with --fit", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0.2",
                                  "--fit", "--max-ratio", "nan"], ["--max-ratio", "finite"]),
    ("radius zero", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0"],
     ["--circle", "radius"]),
    ("circle with two numbers", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5"],
     ["--circle", "3"]),
    ("unparsable expression", ["adapt", GOOD, "-o", "out.msh", "--levelset", "x+*"],
     ["x+*", "cannot parse"]),
    ("no size field", ["adapt", GOOD, "-o", "out.msh"], ["--circle", "--levelset"]),
    # A geometry that moves, and fitting the mesh to it.
    ("--time malformed", ["adapt", GOOD, "-o", "out.pvd", "--levelset", "x-0.5*t",
                          "--time", "0:1"], ["--time", "START:END:STEPS"]),
    ("--time with no steps", ["adapt", GOOD, "-o", "out.pvd", "--levelset", "x-0.5*t",
                              "--time", "0:1:0"], ["--time", "between 1"]),
    ("--time with negative steps", ["adapt", GOOD, "-o", "out.pvd", "--levelset", "x-0.5*t",
                                    "--time", "0:1:-3"], ["--time", "between 1"]),
    ("level set with an unknown variable", ["adapt", GOOD, "-o", "out.msh", "--levelset",
                                            "x+s*t"], ["x+s*t", "cannot parse"]),
    ("--fit with no interface", ["adapt", GOOD, "-o", "out.msh", "--fit", "--levelset",
                                 "x^2+y^2+1"], ["--fit", "no interface"]),
    ("--fit, interface leaves the domain", ["adapt", GOOD, "-o", "out.pvd", "--fit",
                                            "--levelset", "x-0.5-t", "--time", "0:1:3"],
     ["--fit", "boundary"]),
    ("--fit without a level set", ["adapt", GOOD, "-o", "out.msh", "--fit", "--box",
                                   "0.2,0.2,0.8,0.8"], ["--fit", "--levelset"]),
    ("unknown generate case", ["generate", "hexagon", "--level", "2", "-o", "out.msh"],
     ["hexagon", "square-midpoint"]),
    ("generate without a size", ["generate", "box-quad", "-o", "out.msh"],
     ["--level", "--cells"]),
    ("render --window of a 3D mesh", ["render", CUBE, "-o", "out.png", "--window", "0,1,0,1"],
     ["window", "2D mesh", "in space", "cut"]),
    ("render --cut of a 2D mesh", ["render", GOOD, "-o", "out.png", "--cut", "x"], ["cut", "2D"]),
    ("render --cut on no axis", ["render", CUBE, "-o", "out.png", "--cut", "w=1"],
     ["--cut", "x, y or z"]),
    ("render to an unknown format", ["render", GOOD, "-o", "out.jpg"], ["out.jpg"]),
    ("missing config file", ["--config", "nofile.toml", "smooth", GOOD, "-o", "out.msh"],
     ["nofile.toml"]),
    ("misspelled key in config", ["--config", "typo.toml", "smooth", GOOD, "-o", "out.msh"],
     ["typo.toml", "lamda", "[smooth]"]),
    # A value no option can take, 30,000 characters long: cut in the message, no crash.
    ("30,000-character number", ["smooth", GOOD, "-o", "out.msh", "--lambda", LONG],
     ["--lambda", "is not a number", "(30000 characters)"]),
    ("30,000-character choice", ["smooth", GOOD, "-o", "out.msh", "--sizes", LONG],
     ["--sizes", "(30000 characters)"]),
    ("30,000-character unknown option", ["smooth", GOOD, "-o", "out.msh", "--" + LONG],
     ["unknown option", "(30002 characters)"]),
    ("30,000-character input name", ["smooth", LONG + ".msh", "-o", "out.msh"], ["characters"]),
    # Every numeric option finite and in range, blamed by name (not "inverted cell").
    ("infinite lambda", ["smooth", GOOD, "-o", "out.msh", "--lambda", "inf"],
     ["--lambda", "finite"]),
    ("NaN mu", ["smooth", GOOD, "-o", "out.msh", "--mu", "nan"], ["--mu", "finite"]),
    ("NaN kappa", ["smooth", GOOD, "-o", "out.msh", "--kappa", "nan"], ["--kappa", "finite"]),
    ("NaN alpha0", ["smooth", GOOD, "-o", "out.msh", "--alpha0", "nan"], ["--alpha0"]),
    ("infinite tol", ["smooth", GOOD, "-o", "out.msh", "--tol", "inf"], ["--tol", "finite"]),
    ("negative energy-rtol", ["smooth", GOOD, "-o", "out.msh", "--energy-rtol", "-1"],
     ["--energy-rtol", "0 or more"]),
    ("infinite move-rtol", ["smooth", GOOD, "-o", "out.msh", "--move-rtol", "inf"],
     ["--move-rtol", "finite"]),
    ("negative alpha-start-defect",
     ["smooth", GOOD, "-o", "out.msh", "--alpha-start-defect", "-1"],
     ["--alpha-start-defect", "positive"]),
    ("infinite hess-pc-reuse", ["smooth", GOOD, "-o", "out.msh", "--hess-pc-reuse", "inf"],
     ["--hess-pc-reuse", "finite"]),
    ("riesz-rtol 1", ["smooth", GOOD, "-o", "out.msh", "--riesz-rtol", "1"], ["--riesz-rtol"]),
    ("hess-forcing-max -1",
     ["smooth", GOOD, "-o", "out.msh", "--hess-forcing-max", "-1"], ["--hess-forcing-max"]),
    ("max-trial-move -1",
     ["smooth", GOOD, "-o", "out.msh", "--max-trial-move", "-1"], ["--max-trial-move"]),
    ("adapt: infinite power", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0.2",
                               "--power", "inf"], ["--power", "finite"]),
    ("adapt: NaN relaxation", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0.2",
                               "--relaxation", "nan"], ["--relaxation"]),
    ("adapt: negative update-move", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0.2",
                                     "--update-move", "-1"], ["--update-move"]),
    ("adapt: NaN circle centre", ["adapt", GOOD, "-o", "out.msh", "--circle", "nan,0.5,0.2"],
     ["--circle", "finite"]),
    ("generate: infinite rotation", ["generate", "box-quad", "--level", "2", "--rotate", "inf",
                                     "-o", "out.msh"], ["--rotate", "finite"]),
    # Empty output paths.
    ("smooth -o ''", ["smooth", GOOD, "-o", ""], ["--output", "path is empty"]),
    ("convert -o ''", ["convert", GOOD, "-o", ""], ["--output", "path is empty"]),
    ("generate -o ''", ["generate", "box-quad", "--level", "2", "-o", ""],
     ["--output", "path is empty"]),
    ("render -o ''", ["render", GOOD, "-o", ""], ["--output", "path is empty"]),
    ("empty report path", ["smooth", GOOD, "-o", "out.msh", "--report", ""], ["--report"]),
    # Every output checked before the run: nothing written when a picture cannot be.
    ("unwritable history plot", ["smooth", GOOD, "-o", "out.msh", "--plot-history",
                                 "nodir/h.png"], ["--plot-history", "nodir/h.png"]),
    ("unwritable quality JSON", ["quality", GOOD, "--json", "nodir/q.json"],
     ["--json", "nodir/q.json"]),
]

# Run again on 2 ranks: reading, validating, option and output checks, the command line.
MPI_CASES = ["missing file", "text garbage", "inverted cell", "NaN coordinate", "unknown option",
             "bad number", "30,000-character number", "infinite lambda", "smooth -o ''",
             "unwritable report", "unknown PETSc type",
             "size field NaN (volumes file)", "generate without a size", "render --window of a 3D mesh",
             "convert onto its input", "unwritable quality JSON"]

# Raw text of standard-library exceptions that must never reach the user.
RAW = ["stoi", "stod", "bad_alloc", "max_size()", "basic_string", "std::", "terminate called",
       "MPI_ABORT", "mpiexec", "-------"]


def prepare(directory):
    """The inputs some cases read from their own directory."""
    os.mkdir(os.path.join(directory, "adir.msh"))
    rng = random.Random(7)
    with open(os.path.join(directory, "garbage.msh"), "wb") as f:
        f.write(bytes(rng.randrange(256) for _ in range(4096)))
    shutil.copy(GOOD, os.path.join(directory, "mesh.txt"))
    shutil.copy(GOOD, os.path.join(directory, "input.msh"))
    with open(os.path.join(directory, "sizes.txt"), "w") as f:
        f.write("1\n" * 12 + "nan\n" + "1\n" * 13)
    with open(os.path.join(directory, "typo.toml"), "w") as f:
        f.write("[smooth]\nlamda = 2\n")


def listing(directory):
    result = {}
    for root, dirs, files in os.walk(directory):
        for name in dirs + files:
            path = os.path.join(root, name)
            result[os.path.relpath(path, directory)] = (
                None if os.path.isdir(path) else os.path.getmtime(path))
    return result


def run_case(case, base, ranks=1):
    name, args, words = case
    directory = tempfile.mkdtemp(dir=base)
    prepare(directory)
    before = listing(directory)
    args = [a.replace("{data}", DATA) for a in args]
    launcher = mpiexec(ranks)
    try:
        proc = subprocess.run([*launcher, NEOMESH, *args], cwd=directory, capture_output=True,
                              text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return name, ranks, args, "", ["no exit within 60 s (a hang)"]
    problems = []
    if proc.returncode != 1:
        problems.append(f"exit code {proc.returncode}, not 1")
    lines = proc.stderr.splitlines()
    if len(lines) != 1 or not lines[0].startswith("neomesh: error: "):
        problems.append(f"stderr is not one 'neomesh: error:' line: {proc.stderr[:2000]!r}")
    elif len(lines[0]) > 1100:
        problems.append(f"the message is {len(lines[0])} characters long")
    for word in words:
        if word not in proc.stderr:
            problems.append(f"message does not contain {word!r}")
    for raw in RAW:
        if raw in proc.stderr.replace(LONG, ""):
            problems.append(f"message contains {raw!r}")
    after = listing(directory)
    if after != before:
        changed = sorted(set(after.items()) ^ set(before.items()))
        problems.append(f"files appeared or changed: {changed}")
    message = lines[0] if lines else ""
    return name, ranks, args, message, problems


def test_every_mpi_case_is_a_case():
    names = {case[0] for case in CASES}
    assert set(MPI_CASES) <= names, set(MPI_CASES) - names


@pytest.fixture(scope="module")
def results(module_tmp):
    """Every run's (message, problems), by (name, ranks)."""
    runs = [(case, 1) for case in CASES]
    if MPIEXEC:
        runs += [(case, 2) for case in CASES if case[0] in MPI_CASES]
    # Each run mostly waits for MPI start-up: run the cases side by side.
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        found = list(pool.map(lambda run: run_case(run[0], module_tmp, run[1]), runs))
    return {(name, ranks): (args, message, problems)
            for name, ranks, args, message, problems in found}


@pytest.mark.parametrize("name, ranks", [
    *(pytest.param(case[0], 1, id=case[0]) for case in CASES),
    *(pytest.param(name, 2, id=f"{name} (-n 2)", marks=needs_mpi) for name in MPI_CASES),
])
def test_bad_input(results, name, ranks):
    args, message, problems = results[(name, ranks)]
    shown = " ".join(a if len(a) < 100 else a[:20] + "..." for a in args)
    assert not problems, f"neomesh {shown}: {message[:160]}\n" + "\n".join(problems)
