"""`neomesh --help`, `--version` and every subcommand's --help: exit 0, every option group
shown, every option with a one-line meaning, and a default where the option has one."""
import os
import re
import subprocess
import sys

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"

# Subcommand -> option groups its help must show.
GROUPS = {
    "generate": ["Positionals:", "Options:"],
    "quality": ["Positionals:", "Options:"],
    "convert": ["Positionals:", "Options:"],
    "smooth": ["Options:", "Energy", "Quasi-Newton method", "Linear solvers"],
    "render": ["Options:"],
    "adapt": ["Options:", "Size field", "Picard iteration", "Energy", "Quasi-Newton method",
              "Linear solvers"],
}
# Options whose value has a default, which the help must show as `=VALUE`.
DEFAULTS = {
    "smooth": ["--sizes", "--lambda", "--mu", "--gauss", "--alpha0", "--eta", "--kmin",
               "--max-iter", "--tol", "--rtol", "--linear-solver", "--riesz", "--hess-rtol"],
    "adapt": ["--lambda", "--mu", "--power", "--floor", "--min-updates", "--eta"],
    "generate": ["--rotate", "--seed"],
    "render": ["--field", "--width"],
}


def run(*args):
    proc = subprocess.run([NEOMESH, *args], capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:
        sys.exit(f"neomesh {' '.join(args)}: exit {proc.returncode}\n{proc.stderr}")
    return proc.stdout


def check(condition, message):
    if not condition:
        sys.exit(message)


def main():
    version = run("--version")
    check(re.fullmatch(r"neomesh \d+\.\d+\.\d+\n", version), f"--version: {version!r}")

    top = run("--help")
    for word in ["Usage: neomesh", "--quiet", "--verbose", "--config", "--version",
                 "-hess_ksp_monitor", "[smooth]", "mpiexec", *GROUPS]:
        check(word in top, f"neomesh --help does not mention {word}:\n{top}")

    for command, groups in GROUPS.items():
        text = run(command, "--help")
        check(f"Usage: neomesh {command}" in text, f"{command} --help: no usage line:\n{text}")
        for group in groups:
            check(group in text, f"{command} --help does not show the group {group}:\n{text}")
        # Every option has a meaning: its line, or the next one, carries text.
        lines = text.splitlines()
        for i, line in enumerate(lines):
            match = re.match(r"\s+(-\S+)", line)
            if not match:
                continue
            rest = re.sub(r"^\s+\S+(\s+[A-Z:{][^ ]*)*(\s+(REQUIRED|Excludes: \S+))*", "", line)
            meaning = rest.strip() or (lines[i + 1].strip() if i + 1 < len(lines) else "")
            check(meaning, f"{command} --help: {match.group(1)} has no meaning:\n{line}")
        for option in DEFAULTS.get(command, []):
            check(re.search(rf"{re.escape(option)} \S+=\S+", text),
                  f"{command} --help: {option} shows no default:\n{text}")
    # -h is the short form everywhere.
    check("Usage: neomesh smooth" in run("smooth", "-h"), "smooth -h")
    print("help and version OK")


if __name__ == "__main__":
    main()
