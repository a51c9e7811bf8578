"""Mirrored meshes (every cell negatively oriented, as FEAT3 writes some) load and smooth to
the same quality as their unmirrored twins: a ring of 32 clockwise quadrilaterals and 27
left-handed hexahedra, each the mirror image (x -> -x) of its twin in tests/data. Run with
NEOMESH=path/to/neomesh."""
import json
import math
import os
import subprocess
import sys
import tempfile

NEOMESH = os.environ.get("NEOMESH", "neomesh")
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DATA = os.path.join(SOURCE, "tests", "data")
PAIRS = [("feat_ring_quad.xml", "feat_ring_quad_mirrored.xml"),
         ("feat_cube_hex_jitter.xml", "feat_cube_hex_jitter_mirrored.xml")]


def smooth(name, tmp):
    report = os.path.join(tmp, name + ".json")
    out = os.path.join(tmp, name + ".msh")
    proc = subprocess.run([NEOMESH, "smooth", os.path.join(DATA, name), "-o", out, "--quiet",
                           "--report", report], capture_output=True, text=True, timeout=300)
    if proc.returncode != 0:
        sys.exit(f"smooth {name}: exit {proc.returncode}\n{proc.stdout}\n{proc.stderr}")
    with open(report) as f:
        return json.load(f)


def differences(a, b, path=""):
    """Numbers that differ by more than rounding between two JSON values of the same shape."""
    if isinstance(a, dict):
        return [d for k in a if k in b for d in differences(a[k], b[k], f"{path}.{k}")]
    if isinstance(a, list):
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}[{i}]")]
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return [] if math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9) else [f"{path}: {a} vs {b}"]
    return []


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for twin, mirrored in PAIRS:
            a, b = smooth(twin, tmp), smooth(mirrored, tmp)
            for key in ("quality_before", "quality_after"):
                diff = differences(a[key], b[key])
                if diff:
                    sys.exit(f"{mirrored} vs {twin}, {key}:\n" + "\n".join(diff[:10]))
            after = a["quality_after"]
            text = json.dumps(after)
            if '"inverted": 0' not in text:
                sys.exit(f"{twin}: inverted cells after smoothing: {text}")
    print("ok")


if __name__ == "__main__":
    main()
