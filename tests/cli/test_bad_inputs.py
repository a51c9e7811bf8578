"""Bad inputs and options, as a table: every case must exit non-zero with exactly one line
on stderr, `neomesh: error: ...`, that names the file or option at fault, and must leave
no output file (nor a temporary one) behind.

Each case runs in a directory of its own that holds only what the case needs; after the
run that directory must hold exactly what it held before. Run with NEOMESH=path/to/neomesh.
"""
import concurrent.futures
import os
import random
import shutil
import subprocess
import sys
import tempfile

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DATA = os.path.abspath(os.path.join(SOURCE, "tests", "data"))
GOOD = os.path.join(DATA, "square_tri_v41.msh")  # 26 triangles
CUBE = os.path.join(DATA, "cube_tet_v41.msh")

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
    ("inverted cell", ["smooth", "{data}/bad_inverted.msh", "-o", "out.msh"],
     ["bad_inverted.msh", "inverted"]),
    ("repeated vertex", ["convert", "{data}/bad_repeated_vertex.msh", "-o", "out.vtu"],
     ["bad_repeated_vertex.msh", "repeated vertex"]),
    ("unsupported cell type", ["smooth", "{data}/bad_prism.msh", "-o", "out.msh"],
     ["bad_prism.msh", "prism"]),
    ("second-order cells", ["smooth", "{data}/bad_second_order.msh", "-o", "out.msh"],
     ["bad_second_order.msh", "second-order"]),
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
    ("size field NaN (sizes file)", ["adapt", GOOD, "-o", "out.msh", "--sizes", "sizes.txt"],
     ["NaN", "sizes.txt"]),
    ("radius zero", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5,0"],
     ["--circle", "radius"]),
    ("circle with two numbers", ["adapt", GOOD, "-o", "out.msh", "--circle", "0.5,0.5"],
     ["--circle", "3"]),
    ("unparsable expression", ["adapt", GOOD, "-o", "out.msh", "--levelset", "x+*"],
     ["x+*", "cannot parse"]),
    ("no size field", ["adapt", GOOD, "-o", "out.msh"], ["--circle", "--levelset"]),
    ("unknown generate case", ["generate", "hexagon", "--level", "2", "-o", "out.msh"],
     ["hexagon", "square-midpoint"]),
    ("generate without a size", ["generate", "box-quad", "-o", "out.msh"],
     ["--level", "--cells"]),
    ("render a 3D mesh", ["render", CUBE, "-o", "out.png"], ["ParaView"]),
    ("render to an unknown format", ["render", GOOD, "-o", "out.jpg"], ["out.jpg"]),
    ("missing config file", ["--config", "nofile.toml", "smooth", GOOD, "-o", "out.msh"],
     ["nofile.toml"]),
    ("misspelled key in config", ["--config", "typo.toml", "smooth", GOOD, "-o", "out.msh"],
     ["typo.toml", "lamda", "[smooth]"]),
]


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


def run_case(case, base):
    name, args, words = case
    directory = tempfile.mkdtemp(dir=base)
    prepare(directory)
    before = listing(directory)
    args = [a.replace("{data}", DATA) for a in args]
    proc = subprocess.run([NEOMESH, *args], cwd=directory, capture_output=True, text=True,
                          timeout=60)
    problems = []
    if proc.returncode == 0:
        problems.append("exit code 0")
    lines = proc.stderr.splitlines()
    if len(lines) != 1 or not lines[0].startswith("neomesh: error: "):
        problems.append(f"stderr is not one 'neomesh: error:' line: {proc.stderr!r}")
    for word in words:
        if word not in proc.stderr:
            problems.append(f"message does not contain {word!r}")
    after = listing(directory)
    if after != before:
        changed = sorted(set(after.items()) ^ set(before.items()))
        problems.append(f"files appeared or changed: {changed}")
    message = lines[0] if lines else ""
    return name, args, message, problems


def main():
    with tempfile.TemporaryDirectory() as base:
        # Each run mostly waits for MPI start-up: run the cases side by side.
        with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
            results = list(pool.map(lambda c: run_case(c, base), CASES))
    failed = 0
    for name, args, message, problems in results:
        status = "FAIL" if problems else "ok  "
        print(f"{status} {name:30} {message}")
        for p in problems:
            print(f"       {p}  (neomesh {' '.join(args)})")
        failed += bool(problems)
    if failed:
        sys.exit(f"{failed} of {len(CASES)} bad-input cases failed")
    print(f"all {len(CASES)} bad-input cases give one clear error line and no output")


if __name__ == "__main__":
    main()
