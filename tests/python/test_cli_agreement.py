"""Python and the command line give the same coordinates (to 1e-12) and the same report on
meshes of different kinds: 2D quadrilaterals sliding on a curved boundary, 3D hexahedra, and a
tangled mesh that is untangled first."""
import json

import numpy as np
import pytest

import neomesh
from conftest import neomesh_cli

CASES = [
    ("annulus-quad", ["--cells", "8", "--jitter", "0.2"], {}),  # slides on the circles
    ("box-hex", ["--cells", "4", "--jitter", "0.2"], {"targets": "ideal"}),
    ("box-quad", ["--cells", "12", "--jitter", "0.5"], {}),  # tangled
]


def without_timings(report):
    """The report without what differs between two runs of the same problem: wall times."""
    if isinstance(report, dict):
        return {k: without_timings(v) for k, v in report.items()
                if k not in ("seconds", "times")}
    if isinstance(report, list):
        return [without_timings(v) for v in report]
    return report


def flags(options):
    return [a for k, v in options.items() for a in (f"--{k.replace('_', '-')}", str(v))]


@pytest.mark.parametrize("case, generate, options", CASES, ids=[c[0] for c in CASES])
def test_python_and_the_command_line_agree(tmp_path, case, generate, options):
    source = tmp_path / "in.msh"
    neomesh_cli("generate", case, *generate, "-o", source)
    neomesh_cli("smooth", source, "-o", tmp_path / "out.msh", "--report", tmp_path / "r.json",
                *flags(options))

    mesh = neomesh.Mesh.read(str(source))
    if case == "box-quad":
        assert mesh.quality()["inverted"].sum() > 0
    result = neomesh.smooth(mesh, **options)
    cli = neomesh.Mesh.read(str(tmp_path / "out.msh"))
    assert np.abs(cli.points - mesh.points).max() <= 1e-12
    assert np.abs(cli.points - neomesh.Mesh.read(str(source)).points).max() > 1e-3

    report = json.loads((tmp_path / "r.json").read_text())
    ours = result.to_dict()
    assert set(ours) <= set(report)
    assert without_timings(ours) == without_timings({k: report[k] for k in ours})
    if case == "box-quad":
        assert ours["untangling"]["inverted_before"] > 0
