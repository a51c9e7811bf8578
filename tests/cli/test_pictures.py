"""smooth/adapt --picture-before/--picture: pictures coloured by a run's own fields (Q needs
the run's desired volumes, which a mesh file does not keep); render's 3D views."""
import os
import struct

import pytest

from conftest import DATA, expect_one_error_line, neomesh


def png_size(path):
    with open(path, "rb") as f:
        header = f.read(24)
    assert header[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", header[16:24])


@pytest.fixture(scope="module")
def box(module_tmp):
    box = os.path.join(module_tmp, "box.msh")
    neomesh("generate", "box-quad", "--level", "4", "-o", box, timeout=120)
    return box


def test_adapt_pictures_before_and_after(box, tmp):
    before, after = os.path.join(tmp, "before.png"), os.path.join(tmp, "after.svg")
    neomesh("adapt", box, "-o", os.path.join(tmp, "a.msh"), "--circle", "0,0,0.7", "-q",
            "--picture-before", before, "--picture", after, timeout=120)
    width, height = png_size(before)
    assert width == 1200 and height >= 600, f"unexpected picture size {width}x{height}"
    with open(after) as f:
        assert "<svg" in f.read(400), "the SVG picture has no <svg> element"


def test_smooth_picture_of_the_energy(box, tmp):
    smoothed = os.path.join(tmp, "s.png")
    neomesh("smooth", box, "-o", os.path.join(tmp, "s.msh"), "-q", "--picture", smoothed,
            "--picture-field", "energy", timeout=120)
    png_size(smoothed)


# A field that does not exist, and an unknown picture format: errors before the run,
# and no output at all.
@pytest.mark.parametrize("option, word", [(["--picture-field", "beauty"], "picture-field"),
                                          (["--picture", "p.jpg"], ".jpg")],
                         ids=["unknown field", "unknown format"])
def test_bad_picture_option(box, tmp, option, word):
    out = os.path.join(tmp, "never.msh")
    proc = neomesh("smooth", box, "-o", out, *option, cwd=tmp, expect=None)
    assert proc.returncode != 0 and word in proc.stderr and not os.path.exists(out), \
        f"bad {option[0]} was accepted: {proc.returncode} {proc.stderr}"


def test_render_window_draws_only_that_part(box, tmp):
    """render --window zooms in: a quarter of the unit square draws the cells reaching into
    it (a sixteenth of the paths and a few more), not the whole mesh."""
    whole, part = os.path.join(tmp, "whole.svg"), os.path.join(tmp, "part.svg")
    neomesh("render", box, "-o", whole)
    neomesh("render", box, "-o", part, "--window", "0,0.25,0,0.25")
    paths = lambda f: open(f).read().count("<path")
    assert paths(part) < paths(whole) / 3, (paths(part), paths(whole))


def test_an_empty_render_window_is_refused_in_one_line(box, tmp):
    out = os.path.join(tmp, "never.png")
    proc = neomesh("render", box, "-o", out, "--window", "0.5,0.2,0,1", expect=None)
    expect_one_error_line(proc, ["window", "x_min < x_max"], [out])


def test_3d_meshes_are_drawn_whole_and_cut_open(tmp):
    """A 3D run's pictures show the mesh's boundary in perspective; render --cut opens it (the
    cut's cells drawn, not only the outer skin: more faces than the whole view's)."""
    cube = os.path.join(DATA, "cube_tet_v41.msh")
    before, after = os.path.join(tmp, "before.png"), os.path.join(tmp, "after.svg")
    neomesh("smooth", cube, "-o", os.path.join(tmp, "s.msh"), "-q", "--picture-before", before,
            "--picture", after, timeout=120)
    assert png_size(before)[0] == 1200
    whole, cut = os.path.join(tmp, "whole.svg"), os.path.join(tmp, "cut.svg")
    neomesh("render", cube, "-o", whole, "--view", "30,40")
    neomesh("render", cube, "-o", cut, "--view", "30,40", "--cut", "z=0.3")
    paths = lambda f: open(f).read().count("<path")
    assert paths(cut) != paths(whole) and paths(after) > 10, (paths(cut), paths(whole))
