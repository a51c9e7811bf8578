"""`adapt --fit` at small sizes, with the checks of bench/adapt_moving.py (the full sizes): the
facet group `interface` of the .msh is a closed chain/surface in one piece, every vertex of it
within 1e-10 of the zero set, no inverted cell. The min scaled Jacobian >= 0.3 is printed, not
required: fitted quads and hexahedra where the interface turns cannot reach it
(docs/adaptivity.md). tests/cli/test_fit_in_time.py: the same with --time."""
import os
import sys

import pytest

from conftest import NEOMESH, SOURCE

sys.path.insert(0, os.path.join(SOURCE, "bench"))
import adapt_moving  # noqa: E402


@pytest.mark.parametrize("cell, cells", [("quad", 16), ("tri", 16), ("hex", 6)])
def test_fit(tmp, cell, cells):
    figures, failures = adapt_moving.run_fit(NEOMESH, cell, cells, tmp)
    print(f"fit {cell} {cells}: {figures}")
    adapt_moving.report(failures, lambda key: key == "scaled_jacobian")  # exits on a failure
