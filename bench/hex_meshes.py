#!/usr/bin/env python3
"""All-hex meshes that are already good, as hex meshers and users make them: `smooth` with the
defaults must not lower their min or mean scaled Jacobian by more than 0.005 and should take no
more than 10 s each for 10^4-4*10^4 cells. The meshes are made here with Gmsh: a plate with
three holes and a flanged ring (quads recombined by Blossom, extruded or revolved), a CAD part
split into hexahedra (Gmsh's all-hex subdivision of a tetrahedral mesh) and a block graded
towards one face and twisted by 60 degrees. Prints one Markdown table: per mesh, cells, min / mean scaled Jacobian before
and after, iterations, whether the input was returned, whole-program seconds.

    bench/hex_meshes.py build/neomesh [--keep DIR] [--time-limit 120]
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

# Gmsh geometry scripts; each makes hexahedra only.
MESHES = {
    "plate_extruded": """
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 4, 2};
Disk(2) = {1, 1, 0, 0.4};
Disk(3) = {2.6, 0.8, 0, 0.3};
Disk(4) = {3.3, 1.5, 0, 0.2};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2,3,4}; Delete; }
Mesh.CharacteristicLengthMax = 0.06;
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Extrude {0, 0, 0.5} { Surface{1}; Layers{10}; Recombine; }
""",
    "flange_revolved": """
SetFactory("OpenCASCADE");
Rectangle(1) = {0.5, 0, 0, 1.0, 0.25};
Rectangle(2) = {0.5, 0, 0, 0.25, 1.0};
BooleanUnion{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Disk(3) = {1.2, 0.12, 0, 0.06};
BooleanDifference{ Surface{1}; Delete; }{ Surface{3}; Delete; }
Mesh.CharacteristicLengthMax = 0.035;
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Extrude {{0, 1, 0}, {0, 0, 0}, Pi} { Surface{1}; Layers{40}; Recombine; }
""",
    "part_subdivided": """
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.6};
Cylinder(2) = {1, 0.5, -0.1, 0, 0, 0.8, 0.25};
Box(3) = {1.5, -0.1, 0.3, 0.6, 0.5, 0.4};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2,3}; Delete; }
Mesh.CharacteristicLengthMax = 0.11;
Mesh.SubdivisionAlgorithm = 2;
Mesh.Optimize = 1;
""",
    "block_twisted_graded": """
Point(1) = {0, 0, 0};
Extrude {1, 0, 0} { Point{1}; Layers{30}; }
Extrude {0, 1, 0} { Line{1}; Layers{30}; Recombine; }
n = 30; r = 1.12; h[] = {}; ones[] = {}; s = 0; t = 0;
For i In {0:n-1}
  s += r^i;
EndFor
For i In {0:n-1}
  t += r^i / s;
  h[] += t; ones[] += 1;
EndFor
Extrude {{0, 0, 1.5}, {0, 0, 1}, {0.5, 0.5, 0}, Pi/3} { Surface{5}; Layers{ {ones[]}, h[] }; Recombine; }
""",
}


def scaled_jacobian(report, which):
    sj = report[which]["metrics"]["scaled_jacobian"]
    return sj["min"], sj["mean"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("neomesh")
    parser.add_argument("--keep", help="write the meshes and outputs into this folder")
    parser.add_argument("--time-limit", type=float, default=120)
    parser.add_argument("options", nargs="*", help="further smooth options (after --)")
    a = parser.parse_args()
    neomesh = os.path.abspath(a.neomesh)
    print("| mesh | hexahedra | min / mean scaled Jacobian before | after | iterations | "
          "input returned | seconds |")
    print("|---|---:|---|---|---:|---|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        folder = a.keep or tmp
        os.makedirs(folder, exist_ok=True)
        for name, script in MESHES.items():
            geo, mesh = (os.path.join(folder, name + ext) for ext in (".geo", ".msh"))
            with open(geo, "w") as f:
                f.write(script)
            subprocess.run(["gmsh", "-3", geo, "-format", "msh41", "-o", mesh], check=True,
                           stdout=subprocess.DEVNULL)
            out, report = (os.path.join(folder, name + ext) for ext in ("-out.msh", ".json"))
            start = time.monotonic()
            subprocess.run([neomesh, "smooth", mesh, "-o", out, "--quiet", "--report", report,
                            "--time-limit", str(a.time_limit)] + a.options, check=True,
                           stdout=subprocess.DEVNULL)
            seconds = time.monotonic() - start
            with open(report) as f:
                r = json.load(f)
            before, after = scaled_jacobian(r, "quality_before"), scaled_jacobian(r, "quality_after")
            guard = r.get("quality_guard") or {}
            print(f"| {name} | {r['cells']} | {before[0]:.4f} / {before[1]:.4f} | "
                  f"{after[0]:.4f} / {after[1]:.4f} | {len(r['result']['history'])} | "
                  f"{'yes' if guard.get('input_returned') else 'no'} | {seconds:.1f} |")


if __name__ == "__main__":
    main()
