"""Runs every command of examples/README.md (its ```sh blocks), as documented, in a scratch
copy of examples/: gmsh meshes the .geo files, neomesh smooths, adapts and renders. Checks
that each output file exists and, for every `neomesh smooth IN -o OUT.msh`, that the
minimum scaled Jacobian did not fall and no cell is inverted (`neomesh quality --json`).
Prints the before/after numbers. Needs gmsh (scripts/setup.sh installs it)."""
import concurrent.futures
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"
SOURCE = os.environ.get("NEOMESH_SOURCE",
                        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
EXAMPLES = os.path.join(SOURCE, "examples")


def blocks():
    with open(os.path.join(EXAMPLES, "README.md")) as f:
        text = f.read()
    return [[line for line in block.splitlines() if line.strip()]
            for block in re.findall(r"```sh\n(.*?)```", text, re.S)]


def run(args, cwd):
    proc = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)}: exit {proc.returncode}\n{proc.stdout}\n"
                           f"{proc.stderr}")
    return proc.stdout


def quality(path, cwd):
    report = path + ".quality.json"
    run([NEOMESH, "quality", path, "--json", report], cwd)
    with open(os.path.join(cwd, report)) as f:
        return json.load(f)


def output_of(args):
    for flag in ("-o", "--output"):
        if flag in args:
            return args[args.index(flag) + 1]
    return None


def run_block(lines, cwd):
    notes = []
    for line in lines:
        args = shlex.split(line)
        if args[0] == "neomesh":
            args[0] = NEOMESH
        elif args[0] != "gmsh":
            raise RuntimeError(f"unexpected command in examples/README.md: {line}")
        stdout = run(args, cwd)
        out = output_of(args)
        if out and not os.path.isfile(os.path.join(cwd, out)):
            raise RuntimeError(f"{line}: {out} was not written")
        if args[0] == NEOMESH and args[1] in ("smooth", "adapt") and out.endswith(".msh"):
            before, after = quality(args[2], cwd), quality(out, cwd)
            sj = (before["metrics"]["scaled_jacobian"], after["metrics"]["scaled_jacobian"])
            iterations = re.search(r"stopped after (\d+) iterations", stdout).group(1)
            notes.append(f"{args[1]} {args[2]}: {after['cells']['total']} cells, min scaled "
                         f"Jacobian {sj[0]['min']:.3f} -> {sj[1]['min']:.3f}, mean "
                         f"{sj[0]['mean']:.3f} -> {sj[1]['mean']:.3f}, {iterations} iterations")
            if after["inverted"] or after["degenerate"]:
                raise RuntimeError(f"{line}: the output has inverted or degenerate cells")
            if args[1] == "smooth" and sj[1]["min"] < sj[0]["min"] - 1e-9:
                raise RuntimeError(f"{line}: smoothing lowered the minimum scaled Jacobian "
                                   f"({sj[0]['min']} -> {sj[1]['min']})")
    return notes


def main():
    if shutil.which("gmsh") is None:
        sys.exit("gmsh is not installed (scripts/setup.sh installs it)")
    with tempfile.TemporaryDirectory() as tmp:
        cwd = os.path.join(tmp, "examples")
        shutil.copytree(EXAMPLES, cwd)
        with concurrent.futures.ThreadPoolExecutor(max_workers=3) as pool:
            futures = [pool.submit(run_block, b, cwd) for b in blocks()]
            failures = []
            for f in futures:
                try:
                    for note in f.result():
                        print(note)
                except RuntimeError as e:
                    failures.append(str(e))
    if failures:
        sys.exit("\n".join(failures))
    print(f"all {sum(len(b) for b in blocks())} example commands ran")


if __name__ == "__main__":
    main()
