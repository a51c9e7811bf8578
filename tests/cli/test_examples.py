"""Runs every command of examples/README.md (its ```sh blocks), as documented, in a scratch
copy of examples/: gmsh meshes the .geo files, neomesh smooths, adapts and renders. Checks
that each output file exists and, for every `neomesh smooth IN -o OUT.msh`, that the
minimum scaled Jacobian did not fall and no cell is inverted (`neomesh quality --json`).
Prints the before/after numbers. Needs gmsh (scripts/setup.sh installs it)."""
import concurrent.futures
import json
import os
import re
import shlex
import shutil

import pytest

from conftest import EXAMPLES, NEOMESH, run


def blocks():
    with open(os.path.join(EXAMPLES, "README.md")) as f:
        text = f.read()
    return [[line for line in block.splitlines() if line.strip()]
            for block in re.findall(r"```sh\n(.*?)```", text, re.S)]


def quality(path, cwd):
    report = path + ".quality.json"
    run([NEOMESH, "quality", path, "--json", report], cwd, timeout=120)
    with open(os.path.join(cwd, report)) as f:
        return json.load(f)


def output_of(args):
    for flag in ("-o", "--output"):
        if flag in args:
            return args[args.index(flag) + 1]
    return None


def run_block(lines, cwd):
    notes = []
    for line in lines:
        args = shlex.split(line)
        if args[0] == "neomesh":
            args[0] = NEOMESH
        else:
            assert args[0] == "gmsh", f"unexpected command in examples/README.md: {line}"
        stdout = run(args, cwd, timeout=120).stdout
        out = output_of(args)
        assert not out or os.path.isfile(os.path.join(cwd, out)), f"{line}: {out} was not written"
        if args[0] == NEOMESH and args[1] in ("smooth", "adapt") and out.endswith(".msh"):
            before, after = quality(args[2], cwd), quality(out, cwd)
            sj = (before["metrics"]["scaled_jacobian"], after["metrics"]["scaled_jacobian"])
            iterations = re.search(r"stopped after (\d+) iterations", stdout).group(1)
            notes.append(f"{args[1]} {args[2]}: {after['cells']['total']} cells, min scaled "
                         f"Jacobian {sj[0]['min']:.3f} -> {sj[1]['min']:.3f}, mean "
                         f"{sj[0]['mean']:.3f} -> {sj[1]['mean']:.3f}, {iterations} iterations")
            assert not after["inverted"] and not after["degenerate"], \
                f"{line}: the output has inverted or degenerate cells"
            assert args[1] != "smooth" or sj[1]["min"] >= sj[0]["min"] - 1e-9, \
                (f"{line}: smoothing lowered the minimum scaled Jacobian "
                 f"({sj[0]['min']} -> {sj[1]['min']})")
    return notes


BLOCKS = blocks()


def test_gmsh_is_installed():
    assert shutil.which("gmsh"), "gmsh is not installed (scripts/setup.sh installs it)"


@pytest.fixture(scope="module")
def ran(module_tmp):
    """The runs of the blocks, side by side in one scratch copy of examples/ (a block's
    commands run in order): one future a block, whose result is the block's notes."""
    cwd = os.path.join(module_tmp, "examples")
    shutil.copytree(EXAMPLES, cwd)
    with concurrent.futures.ThreadPoolExecutor(max_workers=3) as pool:
        futures = [pool.submit(run_block, b, cwd) for b in BLOCKS]
        concurrent.futures.wait(futures)
    return futures


@pytest.mark.parametrize("index", range(len(BLOCKS)),
                         ids=[f"{i}: {b[0][:50]}" for i, b in enumerate(BLOCKS)])
def test_example_block(ran, index):
    for note in ran[index].result():
        print(note)


def test_there_are_examples():
    assert sum(len(b) for b in BLOCKS) > 0, "examples/README.md has no ```sh block"
