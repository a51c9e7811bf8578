#!/usr/bin/env python3
"""The target cells (`smooth --targets`, docs/method.md §9) on meshes made with a design: the 2D
boundary layer of examples/cylinder_channel_bl.geo, a 3D prism layer on a sphere, Mesquite's
graded CAD mesh cub_fru and its optimized graded triangles shashkov_opt. Prints one Markdown
table: per mesh and --targets, the change of the layer's first heights and thickness (min..max
over the wall cells / outer vertices), the min and mean scaled Jacobian of the cells outside
the layer (all cells for the Mesquite meshes), iterations and whole-program seconds.

    bench/targets.py build/neomesh [--corpus ../shared/corpus] [--time-limit 60]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "cli"))
import boundary_layers  # noqa: E402


def run(neomesh, mesh, out, targets, time_limit):
    report = out + ".json"
    start = time.monotonic()
    subprocess.run([neomesh, "smooth", mesh, "-o", out, "--quiet", "--report", report,
                    "--targets", targets, "--time-limit", str(time_limit)], check=True,
                   stdout=subprocess.DEVNULL)
    seconds = time.monotonic() - start
    with open(report) as f:
        r = json.load(f)
    return r, seconds


def percent(pair):
    return f"{100 * pair[0]:+.2f} .. {100 * pair[1]:+.2f} %"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("neomesh")
    parser.add_argument("--corpus", default=os.path.join(HERE, "..", "..", "shared", "corpus"))
    parser.add_argument("--time-limit", type=float, default=60)
    a = parser.parse_args()
    neomesh = os.path.abspath(a.neomesh)
    print("| mesh | --targets | first heights | thickness | min / mean scaled Jacobian "
          "(outside the layer) | iterations | seconds |")
    print("|---|---|---|---|---|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        layers = [("channel_bl (2D)", boundary_layers.channel(tmp),
                   boundary_layers.layer_change_2d),
                  ("sphere_bl (3D)", boundary_layers.sphere(tmp), boundary_layers.layer_change_3d)]
        for name, mesh, change in layers:
            for targets in ("input", "ideal", "smoothed"):
                out = os.path.join(tmp, f"{targets}.vtu")
                r, seconds = run(neomesh, mesh, out, targets, a.time_limit)
                c = change(mesh, out)
                worst, mean = boundary_layers.rest_quality(out)
                print(f"| {name} | {targets} | {percent(c['first_height'])} | "
                      f"{percent(c['thickness'])} | {worst:.4f} / {mean:.4f} | "
                      f"{len(r['result']['history'])} | {seconds:.1f} |")
        mesquite = os.path.join(a.corpus, "mesquite")
        for name, path in (("cub_fru", "3D/vtk/hexes/untangled/cub_fru.vtk"),
                           ("shashkov_opt", "2D/vtk/tris/untangled/shashkov_opt.vtk")):
            mesh = os.path.join(mesquite, path)
            if not os.path.exists(mesh):
                continue
            for targets in ("ideal", "smoothed"):
                r, seconds = run(neomesh, mesh, os.path.join(tmp, f"{name}.vtu"), targets,
                                 a.time_limit)
                sj = lambda q: q["metrics"]["scaled_jacobian"]
                before, after = sj(r["quality_before"]), sj(r["quality_after"])
                stop = " (time limit)" if r["result"]["stop_reason"].startswith("time") else ""
                print(f"| {name} | {targets} | | | {before['min']:.4f} / {before['mean']:.4f} → "
                      f"{after['min']:.4f} / {after['mean']:.4f} | "
                      f"{len(r['result']['history'])}{stop} | {seconds:.1f} |")


if __name__ == "__main__":
    main()
