"""`adapt --fit` at small sizes, with the checks of bench/adapt_moving.py (the full sizes): the
facet group `interface` of the .msh is a closed chain/surface in one piece, every vertex of it
within 1e-10 of the zero set, no inverted cell. The min scaled Jacobian >= 0.3 is printed, not
required: fitted quads and hexahedra where the interface turns cannot reach it
(docs/adaptivity.md). tests/cli/test_fit_in_time.py: the same with --time."""
import os
import sys
import tempfile

SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(SOURCE, "bench"))
import adapt_moving  # noqa: E402

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
REPORTED_ONLY = {"scaled_jacobian"}


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for cell, cells in [("quad", 16), ("tri", 16), ("hex", 6)]:
            figures, found = adapt_moving.run_fit(NEOMESH, cell, cells, tmp)
            print(f"fit {cell} {cells}: {figures}")
            failures += [m for key, m in found if key not in REPORTED_ONLY]
            for key, m in found:
                if key in REPORTED_ONLY:
                    print("reported: " + m)
    for m in failures:
        print("FAIL " + m)
    if failures:
        sys.exit(f"{len(failures)} checks failed")


if __name__ == "__main__":
    main()
