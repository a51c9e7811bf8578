"""smooth/adapt --picture-before/--picture: 2D pictures coloured by a run's own fields (Q needs
the run's desired volumes, which a mesh file does not keep)."""
import os
import struct
import subprocess
import sys
import tempfile

NEOMESH = os.environ.get("NEOMESH", "neomesh")


def run(*args, expect=0):
    proc = subprocess.run([NEOMESH, *args], capture_output=True, text=True, timeout=120)
    if proc.returncode != expect:
        sys.exit(f"neomesh {' '.join(args)}: exit {proc.returncode}, expected {expect}\n"
                 f"{proc.stdout}\n{proc.stderr}")
    return proc


def png_size(path):
    with open(path, "rb") as f:
        header = f.read(24)
    if header[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path} is not a PNG")
    return struct.unpack(">II", header[16:24])


with tempfile.TemporaryDirectory() as tmp:
    box = os.path.join(tmp, "box.msh")
    run("generate", "box-quad", "--level", "4", "-o", box)
    before, after = os.path.join(tmp, "before.png"), os.path.join(tmp, "after.svg")
    run("adapt", box, "-o", os.path.join(tmp, "a.msh"), "--circle", "0,0,0.7", "-q",
        "--picture-before", before, "--picture", after)
    width, height = png_size(before)
    if width != 1200 or height < 600:
        sys.exit(f"unexpected picture size {width}x{height}")
    with open(after) as f:
        if "<svg" not in f.read(400):
            sys.exit("the SVG picture has no <svg> element")

    smoothed = os.path.join(tmp, "s.png")
    run("smooth", box, "-o", os.path.join(tmp, "s.msh"), "-q", "--picture", smoothed,
        "--picture-field", "energy")
    png_size(smoothed)

    # A field that does not exist, and an unknown picture format: errors before the run,
    # and no output at all.
    out = os.path.join(tmp, "never.msh")
    proc = subprocess.run([NEOMESH, "smooth", box, "-o", out, "--picture-field", "beauty"],
                          capture_output=True, text=True)
    if proc.returncode == 0 or "picture-field" not in proc.stderr or os.path.exists(out):
        sys.exit(f"bad --picture-field was accepted: {proc.returncode} {proc.stderr}")
    proc = subprocess.run([NEOMESH, "smooth", box, "-o", out, "--picture", "p.jpg"],
                          capture_output=True, text=True)
    if proc.returncode == 0 or ".jpg" not in proc.stderr or os.path.exists(out):
        sys.exit(f"bad --picture format was accepted: {proc.returncode} {proc.stderr}")
print("1 passed, 0 failed")
