#!/usr/bin/env python3
"""Fails on an upward include: a file of a layer (src/<layer>/) that includes a header of a layer
above it. The layers, lowest first, are those of CMakeLists.txt's
neomesh_layer() calls; include/neomesh (the public API) belongs to api. Today the lower layers
still use public types in the headers listed in UPWARD (the one-source-of-truth redesign maps
them at the facade); the list may only shrink: a listed include that is gone fails too, so that
it is taken off.

usage: scripts/check_layers.py [SOURCE_DIR]"""
import os
import re
import sys

LAYERS = ["core", "mesh", "geometry", "energy", "boundary", "solver", "adapt", "api", "report", "app"]
# (file, included layer) pairs that exist and are allowed until the redesign removes them.
UPWARD = {
    ("src/adapt/picard.hpp", "api"), ("src/adapt/size_field.hpp", "api"),
    ("src/adapt/volume_ratio.hpp", "api"), ("src/boundary/boundary.hpp", "api"),
    ("src/core/error.hpp", "api"), ("src/energy/functional.hpp", "api"),
    ("src/geometry/quality.hpp", "api"), ("src/mesh/cell_type.hpp", "api"),
    ("src/mesh/mesh_io.hpp", "api"), ("src/mesh/plex_mesh.hpp", "api"),
    ("src/solver/desired_volumes.hpp", "api"), ("src/solver/linear_solver.hpp", "api"),
    ("src/solver/quality_guard.hpp", "api"), ("src/solver/quasi_newton.hpp", "api"),
    ("src/solver/worst_cells.hpp", "api"),
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def included_layer(quote, path):
    if quote == "<" and path.startswith("neomesh/"):
        return "api"
    head = path.split("/")[0]
    return head if quote == '"' and head in LAYERS else None


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    found, bad = set(), []
    for layer in LAYERS:
        for folder, _, files in os.walk(os.path.join(root, "src", layer)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(folder, name)
                rel = os.path.relpath(path, root)
                with open(path, encoding="utf-8") as f:
                    for quote, header in INCLUDE.findall(f.read()):
                        other = included_layer(quote, header)
                        if other and LAYERS.index(other) > LAYERS.index(layer):
                            found.add((rel, other))
                            if (rel, other) not in UPWARD:
                                bad.append(f"{rel} ({layer}) includes {header} ({other})")
    gone = sorted(f"{f} no longer includes the {l} layer: take it off UPWARD" for f, l in UPWARD - found)
    for line in bad + gone:
        print(line)
    print(f"{len(found)} upward includes, {len(UPWARD)} allowed; {len(bad)} new, {len(gone)} gone")
    return 1 if bad or gone else 0


if __name__ == "__main__":
    sys.exit(main())
