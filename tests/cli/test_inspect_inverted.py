"""`quality` and `render` read meshes with inverted cells, as their help says: quality counts
them (table and JSON), render draws them in red, on top of the cells they overlap. Serially
and, with NEOMESH_MPIEXEC, on 2 ranks. smooth --no-untangle refuses such a mesh, naming the
cell by its position and by the element number of the file."""
import json
import os
import re

import pytest

from conftest import DATA, RANKS, neomesh

INVERTED = os.path.join(DATA, "bad_inverted.msh")  # 26 triangles, element 13 inverted
RED = "rgb(85%,11%,11%)"  # render.cpp's kInvalidColour in cairo's SVG


@pytest.mark.parametrize("ranks", RANKS)
def test_quality_counts_the_inverted_cell(tmp, ranks):
    report = os.path.join(tmp, "q.json")
    proc = neomesh("quality", INVERTED, "--json", report, ranks=ranks, timeout=120)
    assert "inverted cells: 1," in proc.stdout, f"quality says {proc.stdout!r}"
    with open(report) as f:
        assert json.load(f)["inverted"] == 1, "the JSON does not count 1 inverted cell"


@pytest.mark.parametrize("ranks", RANKS)
def test_render_draws_the_inverted_cell_in_red_on_top(tmp, ranks):
    picture = os.path.join(tmp, "inverted.svg")
    neomesh("render", INVERTED, "-o", picture, ranks=ranks, timeout=120)
    with open(picture) as f:
        svg = f.read()
    # One red cell and the red legend patch; the cell is drawn after every coloured
    # cell, since it overlaps its neighbours, which would hide it.
    assert svg.count(RED) >= 2, f"render did not draw the inverted cell in red ({RED})"
    fills = [(m.start(), m.group(1)) for m in re.finditer(r"fill:(rgb\([^)]*\))", svg)]
    coloured = [at for at, colour in fills  # not red, not a grey of text or frame
                if colour != RED and len(set(colour[4:-1].split(","))) > 1]
    assert coloured and max(coloured) < svg.find(RED), \
        "the inverted cell is drawn before other cells"


@pytest.mark.parametrize("ranks", RANKS)
def test_smooth_no_untangle_names_the_cell(tmp, ranks):
    proc = neomesh("smooth", INVERTED, "-o", os.path.join(tmp, "out.msh"), "--no-untangle",
                   ranks=ranks, expect=None, timeout=120)
    assert proc.returncode != 0, f"smooth --no-untangle accepted it: {proc.stdout}"
    assert "cell 0 (0-based; element 13 of the file), a triangle, is inverted" \
        in proc.stderr, f"smooth says {proc.stderr!r}"
    assert len(proc.stderr.splitlines()) == 1, f"not one line: {proc.stderr!r}"
