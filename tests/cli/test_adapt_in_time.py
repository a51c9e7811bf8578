"""`adapt --time`: a circle rising through a box of quads, step by step (a geometry that
moves). Each step is warm-started from the one before and prints one summary line; -o OUT.pvd
writes one .vtu per step and ParaView's collection of them (meshio reads every member), and
--picture with a %d pattern draws every step. Warm steps need at most half the iterations of
the cold first step. Bad --time values and patterns: one `neomesh: error:` line, no output."""
import os
import re
import xml.etree.ElementTree as ElementTree

import pytest

from conftest import expect_one_error_line, neomesh, read_mesh

RISING = "sqrt(x^2+(y-0.3*t)^2)-0.2"


@pytest.fixture(scope="module")
def box(module_tmp):
    neomesh("generate", "box-quad", "--level", "5", "-o", "box.msh", cwd=module_tmp)  # 32x32
    return module_tmp


@pytest.fixture(scope="module")
def rising(box):
    """The 4 steps of the rising circle: (stdout, directory)."""
    os.mkdir(os.path.join(box, "frames"))
    proc = neomesh("adapt", "box.msh", "-o", "rise.pvd", "--levelset", RISING,
                   "--time", "0:1:4", "--picture", "frames/%03d.png", cwd=box)
    return proc.stdout, box


def test_warm_steps_need_at_most_half_the_cold_iterations(rising):
    stdout, _ = rising
    steps = [line for line in stdout.splitlines() if line.startswith("step ")]
    assert len(steps) == 4, f"one summary line per step ({len(steps)})"
    iterations = [int(re.search(r": (\d+) iterations", s).group(1)) for s in steps]
    print(f"iterations per step: {iterations}")
    assert all(2 * i <= iterations[0] for i in iterations[1:]), \
        f"warm steps need at most half the cold start's iterations: {iterations}"


def test_meshio_reads_every_member_of_the_collection(rising):
    _, tmp = rising
    collection = ElementTree.parse(os.path.join(tmp, "rise.pvd")).getroot()
    members = [(float(d.get("timestep")), d.get("file")) for d in collection.iter("DataSet")]
    assert [t for t, _ in members] == [0.0, 1 / 3, 2 / 3, 1.0] or \
        all(abs(a - b) < 1e-12 for (a, _), b in zip(members, [0, 1 / 3, 2 / 3, 1])), \
        f"the collection lists the 4 times: {members}"
    for _, name in members:
        mesh = read_mesh(os.path.join(tmp, name))
        assert len(mesh.points) == 33 * 33 and "Q" in mesh.cell_data, \
            f"meshio reads {name} with its Q field"


def test_a_picture_per_step(rising):
    _, tmp = rising
    assert sorted(os.listdir(os.path.join(tmp, "frames"))) == \
        ["000.png", "001.png", "002.png", "003.png"]


@pytest.mark.parametrize("args, words", [
    pytest.param(["--time", "0:1:0"], ["--time", "between 1"], id="no steps"),
    pytest.param(["--time", "0:1"], ["--time", "START:END:STEPS"], id="malformed time"),
    pytest.param(["--time", "0:1:2.5"], ["--time", "whole number"], id="fractional steps"),
    pytest.param(["--time", "0:1:3", "--levelset", "x+s"], ["x+s"], id="unknown variable"),
    pytest.param(["--time", "0:1:3", "--picture", "p.png"], ["%d"],
                 id="picture without a step number"),
    pytest.param([], ["--time"], id=".pvd without --time"),
])
def test_bad_input(box, args, words):
    options = args if "--levelset" in args else ["--levelset", RISING, *args]
    proc = neomesh("adapt", "box.msh", "-o", "bad.pvd", *options, cwd=box, expect=None)
    expect_one_error_line(proc, words)
    left = [f for f in os.listdir(box) if f.startswith("bad")]
    assert not left, f"left behind: {left}"
