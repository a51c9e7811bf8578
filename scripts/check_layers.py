#!/usr/bin/env python3
"""Fails on an upward include: a file of a layer (src/<layer>/) that includes a header of a layer
above it. The layers, lowest first, are those of CMakeLists.txt's neomesh_layer() calls.

The public headers (include/neomesh, the one home of the API) are layered too: each belongs to
api unless PUBLIC_LAYERS gives it a lower layer, the layer that implements it (defines its
functions) or, for plain types alone, the lowest layer that fills them. A lower layer may use
such a header instead of re-declaring its types; it may include only public headers of its own
layer or below, and only headers of api may include src/ headers (the installed headers are
include/neomesh alone). Functions defined above a layer cannot be called from it: each layer's
tests link that layer and those below only.

usage: scripts/check_layers.py [SOURCE_DIR]"""
import os
import re
import sys

LAYERS = ["core", "mesh", "generate", "formats", "geometry", "energy", "boundary", "solver", "targets", "adapt", "api", "report", "app"]
PUBLIC_LAYERS = {
    "error.hpp": "core",         # the one exception type every layer throws
    "cell_type.hpp": "mesh",     # the cell types; plural_name() in src/mesh/cell_type.cpp
    "field.hpp": "mesh",         # fields and facet groups the writers write
    "quality.hpp": "geometry",   # computed by src/geometry/quality.cpp
    "options.hpp": "energy",     # plain option structs; ranges checked in api (option table)
    "result.hpp": "boundary",    # filled by boundary, solver and adapt; describe() in solver
    "size_field.hpp": "targets", # src/targets/size_field.cpp; from a Mesh: src/api/vertex_metric.cpp
}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def public_layer(header):
    return PUBLIC_LAYERS.get(header, "api")


def included_layer(quote, path):
    if quote == "<" and path.startswith("neomesh/"):
        return public_layer(path[len("neomesh/"):])
    head = path.split("/")[0]
    return head if quote == '"' and head in LAYERS else None


def check(path, rel, layer, bad):
    with open(path, encoding="utf-8") as f:
        for quote, header in INCLUDE.findall(f.read()):
            other = included_layer(quote, header)
            if other and LAYERS.index(other) > LAYERS.index(layer):
                bad.append(f"{rel} ({layer}) includes {header} ({other})")
            elif quote == '"' and other and rel.startswith("include/"):
                bad.append(f"{rel} (public) includes {header}, which is not installed")


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    bad = []
    public = os.path.join(root, "include", "neomesh")
    for name in sorted(os.listdir(public)):
        if name.endswith(".hpp"):
            check(os.path.join(public, name), f"include/neomesh/{name}", public_layer(name), bad)
    for name in sorted(set(PUBLIC_LAYERS) - set(os.listdir(public))):
        bad.append(f"PUBLIC_LAYERS names include/neomesh/{name}, which does not exist")
    for layer in LAYERS:
        for folder, _, files in os.walk(os.path.join(root, "src", layer)):
            for name in sorted(files):
                if name.endswith((".hpp", ".cpp")):
                    path = os.path.join(folder, name)
                    check(path, os.path.relpath(path, root), layer, bad)
    for line in bad:
        print(line)
    print(f"{len(bad)} layering violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
