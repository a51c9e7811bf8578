"""`neomesh --help`, `--version` and every subcommand's --help: exit 0, every option group
shown, every option with a one-line meaning, and a default where the option has one."""
import re

import pytest

from conftest import neomesh

# Subcommand -> option groups its help must show.
GROUPS = {
    "generate": ["Positionals:", "Options:"],
    "quality": ["Positionals:", "Options:"],
    "convert": ["Positionals:", "Options:"],
    "curve": ["Positionals:", "Options:"],
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


def help_of(*args):
    return neomesh(*args, timeout=60).stdout


def test_version():
    version = help_of("--version")
    assert re.fullmatch(r"neomesh \d+\.\d+\.\d+\n", version), f"--version: {version!r}"


def test_top_level_help():
    top = help_of("--help")
    for word in ["Usage: neomesh", "--quiet", "--verbose", "--config", "--version",
                 "-hess_ksp_monitor", "[smooth]", "mpiexec", *GROUPS]:
        assert word in top, f"neomesh --help does not mention {word}:\n{top}"


@pytest.mark.parametrize("command", GROUPS)
def test_subcommand_help(command):
    text = help_of(command, "--help")
    assert f"Usage: neomesh {command}" in text, f"{command} --help: no usage line:\n{text}"
    for group in GROUPS[command]:
        assert group in text, f"{command} --help does not show the group {group}:\n{text}"
    # Every option has a meaning: its line, or the next one, carries text.
    lines = text.splitlines()
    for i, line in enumerate(lines):
        match = re.match(r"\s+(-\S+)", line)
        if not match:
            continue
        rest = re.sub(r"^\s+\S+(\s+[A-Z:{][^ ]*)*(\s+(REQUIRED|Excludes: \S+))*", "", line)
        meaning = rest.strip() or (lines[i + 1].strip() if i + 1 < len(lines) else "")
        assert meaning, f"{command} --help: {match.group(1)} has no meaning:\n{line}"
    for option in DEFAULTS.get(command, []):
        assert re.search(rf"{re.escape(option)} \S+=\S+", text), \
            f"{command} --help: {option} shows no default:\n{text}"


def test_h_is_the_short_form():
    assert "Usage: neomesh smooth" in help_of("smooth", "-h"), "smooth -h"
