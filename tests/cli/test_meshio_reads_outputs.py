"""Every kind of file the CLI writes is read by meshio (an independent reader) and, when it is
installed, by Gmsh: .msh from generate, smooth, adapt and convert (inputs with physical groups
on cells and facets, on facets only, and FEAT3 files) and .vtu. meshio must find the cells
neomesh reports, with a physical group for every cell block of a .msh file (meshio refuses a
file whose cells lack one while its facets have one).

meshio is the system's python3-meshio (scripts/setup.sh); a virtualenv's python3 may lack
it, so the script re-runs itself with /usr/bin/python3 then.
"""
import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile

try:
    import meshio
except ImportError:
    if sys.executable != "/usr/bin/python3" and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3", *sys.argv])
    print("meshio is not installed (scripts/setup.sh installs python3-meshio): skipped")
    sys.exit(0)

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DATA = os.path.abspath(os.path.join(SOURCE, "tests", "data"))
CELLS_3D, CELLS_2D = {"tetra", "hexahedron"}, {"triangle", "quad"}


def run(args):
    proc = subprocess.run([NEOMESH, *args], capture_output=True, text=True, timeout=300)
    if proc.returncode != 0:
        sys.exit(f"neomesh {' '.join(args)}: exit {proc.returncode}\n{proc.stderr}")


def cells_of(path):
    """Number of cells (elements of the mesh's dimension) meshio reads from `path`."""
    with contextlib.redirect_stdout(io.StringIO()):  # meshio's progress and warnings
        mesh = meshio.read(path)
    types = CELLS_3D if any(block.type in CELLS_3D for block in mesh.cells) else CELLS_2D
    return sum(len(block.data) for block in mesh.cells if block.type in types), mesh


def main():
    with tempfile.TemporaryDirectory() as tmp:
        def out(name):
            return os.path.join(tmp, name)

        # (what wrote it, file, the input it came from, or None when generated)
        written = []
        for case, level in [("square-midpoint", "2"), ("cube-midpoint", "1"), ("box-tri", "2")]:
            for ext in (".msh", ".vtu"):
                path = out(f"{case}{ext}")
                run(["generate", case, "--level", level, "-o", path])
                written.append(("generate", path, out(f"{case}.msh")))
        inputs = [out("square-midpoint.msh"), out("cube-midpoint.msh"),  # facet groups only
                  os.path.join(DATA, "mixed_tri_quad_v41.msh"),           # cell groups too
                  os.path.join(DATA, "cube_hex_v22.msh"),
                  os.path.join(DATA, "feat_square_quad.xml")]
        for i, source in enumerate(inputs):
            for ext in (".msh", ".vtu"):
                path = out(f"smooth-{i}{ext}")
                run(["smooth", source, "-o", path, "--quiet"])
                written.append(("smooth", path, source))
                path = out(f"convert-{i}{ext}")
                run(["convert", source, "-o", path])
                written.append(("convert", path, source))
        path = out("adapt.msh")
        run(["adapt", out("square-midpoint.msh"), "-o", path, "--circle", "0.5,0.5,0.25",
             "--quiet", "--max-iter", "5"])
        written.append(("adapt", path, out("square-midpoint.msh")))

        gmsh = shutil.which("gmsh")
        failures = []
        for command, path, source in written:
            name = os.path.basename(path)
            failed_before = len(failures)
            try:
                count, mesh = cells_of(path)
            except Exception as e:  # meshio's own exception types vary by version
                failures.append(f"{command} -> {name}: meshio cannot read it: {e}")
                continue
            if source.endswith(".msh") and os.path.exists(source):
                expected, _ = cells_of(source)
                if count != expected:
                    failures.append(f"{command} -> {name}: {count} cells, the input has {expected}")
            if path.endswith(".msh") and "gmsh:physical" in mesh.cell_data:
                blocks = len(mesh.cells)
                if len(mesh.cell_data["gmsh:physical"]) != blocks:
                    failures.append(f"{command} -> {name}: physical groups on some blocks only")
            if gmsh and path.endswith(".msh"):
                again = path + ".again.msh"
                proc = subprocess.run([gmsh, "-0", path, "-format", "msh41", "-o", again],
                                      capture_output=True, text=True, timeout=120)
                if proc.returncode != 0 or "Error" in proc.stdout + proc.stderr:
                    failures.append(f"{command} -> {name}: gmsh: {proc.stdout[-500:]}")
                else:
                    count_again, _ = cells_of(again)
                    if count_again != count:
                        failures.append(f"{command} -> {name}: Gmsh keeps {count_again} of "
                                        f"{count} cells")
            status = "FAIL" if len(failures) > failed_before else "ok  "
            print(f"{status} {command:9} {name:24} {count} cells")
        if failures:
            sys.exit("\n".join(failures))
        print(f"meshio{' and Gmsh' if gmsh else ''} read all {len(written)} files neomesh wrote")


if __name__ == "__main__":
    main()
