"""scripts/check_layers.py fails where a layer includes a header above it: a lower layer that
includes a public header of api, a public header that includes one of a higher layer or a src/
header (only include/neomesh is installed); the tree as it is passes (ctest's `layering`)."""
import os
import shutil
import subprocess
import sys

import pytest

SOURCE = os.environ.get("NEOMESH_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))


def check(root):
    return subprocess.run([sys.executable, os.path.join(root, "scripts", "check_layers.py"), root],
                          capture_output=True, text=True)


@pytest.fixture
def tree(tmp_path):
    for part in ["include", "src", "scripts"]:
        shutil.copytree(os.path.join(SOURCE, part), tmp_path / part,
                        ignore=shutil.ignore_patterns("*.msh", "*.vtu", "*.xml", "*.cgns"))
    return tmp_path


@pytest.mark.parametrize("file, line, message", [
    ("src/targets/input_targets.hpp", "#include <neomesh/mesh.hpp>",
     "src/targets/input_targets.hpp (targets) includes neomesh/mesh.hpp (api)"),
    ("src/energy/functional.hpp", '#include "adapt/fit.hpp"',
     "src/energy/functional.hpp (energy) includes adapt/fit.hpp (adapt)"),
    ("include/neomesh/result.hpp", "#include <neomesh/optimizer.hpp>",
     "include/neomesh/result.hpp (boundary) includes neomesh/optimizer.hpp (api)"),
    ("include/neomesh/error.hpp", '#include "core/error.hpp"',
     "include/neomesh/error.hpp (public) includes core/error.hpp, which is not installed"),
])
def test_an_upward_include_fails(tree, file, line, message):
    assert check(str(tree)).returncode == 0
    with open(tree / file, "a", encoding="utf-8") as f:
        f.write(line + "\n")
    run = check(str(tree))
    assert run.returncode == 1
    assert message in run.stdout
