"""`neomesh` is a launcher (src/launcher.cpp): it starts neomesh-main, beside it or in
../libexec/neomesh/, with glibc.malloc.hugetlb added to GLIBC_TUNABLES unless that already
names it (=1, or =0 on a virtual machine whose balloon reports free memory to its host) and
OMP_WAIT_POLICY=PASSIVE unless a policy is set, and passes the arguments on unchanged. A
stand-in neomesh-main that prints what it got shows it."""
import glob
import os
import shutil
import subprocess

from conftest import NEOMESH


def reports_free_memory():
    """A virtio balloon (device 0x0005) with feature bit 5, free page reporting, on this
    machine (src/core/huge_pages.hpp reads the same files)."""
    for device in glob.glob("/sys/bus/virtio/devices/*"):
        try:
            with open(os.path.join(device, "device")) as f:
                ident = f.read().strip()
            with open(os.path.join(device, "features")) as f:
                features = f.read().strip()
        except OSError:
            continue
        if ident == "0x0005" and len(features) > 5 and features[5] == "1":
            return True
    return False


HUGETLB = "glibc.malloc.hugetlb=" + ("0" if reports_free_memory() else "1")

STAND_IN = '#!/bin/sh\nprintf "%s\\n" "$GLIBC_TUNABLES" "$0" "$@" "wait:$OMP_WAIT_POLICY"\n'


def launcher_with_stand_in(tmp_path, main_dir):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    launcher = bin_dir / "neomesh"
    shutil.copy(os.path.realpath(shutil.which(NEOMESH) or NEOMESH), launcher)
    main_dir = tmp_path / main_dir
    main_dir.mkdir(parents=True, exist_ok=True)
    stand_in = main_dir / "neomesh-main"
    stand_in.write_text(STAND_IN)
    stand_in.chmod(0o755)
    return launcher


def run(launcher, env_tunables, *args, wait_policy=None):
    env = dict(os.environ)
    env.pop("GLIBC_TUNABLES", None)
    env.pop("OMP_WAIT_POLICY", None)
    if env_tunables is not None:
        env["GLIBC_TUNABLES"] = env_tunables
    if wait_policy is not None:
        env["OMP_WAIT_POLICY"] = wait_policy
    return subprocess.run([str(launcher), *args], env=env, capture_output=True, text=True)


def test_adds_the_huge_pages_setting_and_passes_the_arguments_on(tmp_path):
    launcher = launcher_with_stand_in(tmp_path, "bin")
    out = run(launcher, None, "smooth", "a mesh.msh", "-o", "")
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:1] == [HUGETLB]
    assert out.stdout.split("\n")[2:6] == ["smooth", "a mesh.msh", "-o", ""]
    out = run(launcher, "glibc.malloc.check=0")
    assert out.stdout.split("\n")[0] == "glibc.malloc.check=0:" + HUGETLB


def test_leaves_a_given_hugetlb_setting_alone(tmp_path):
    launcher = launcher_with_stand_in(tmp_path, "bin")
    out = run(launcher, "glibc.malloc.hugetlb=0")
    assert out.stdout.split("\n")[0] == "glibc.malloc.hugetlb=0"


def test_openmp_threads_sleep_while_they_wait_unless_told_otherwise(tmp_path):
    # Spinning threads collapse a run beside another busy process.
    launcher = launcher_with_stand_in(tmp_path, "bin")
    assert run(launcher, None, "quality").stdout.split("\n")[-2] == "wait:PASSIVE"
    assert run(launcher, None, "quality", wait_policy="ACTIVE").stdout.split("\n")[-2] == "wait:ACTIVE"


def test_finds_the_installed_layout(tmp_path):
    launcher = launcher_with_stand_in(tmp_path, "libexec/neomesh")
    out = run(launcher, None, "--version")
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[1].endswith("libexec/neomesh/neomesh-main")


def test_without_neomesh_main_one_line_error(tmp_path):
    lonely = tmp_path / "neomesh"
    shutil.copy(os.path.realpath(shutil.which(NEOMESH) or NEOMESH), lonely)
    out = run(lonely, None, "--version")
    assert out.returncode == 1
    assert out.stdout == ""
    lines = out.stderr.strip().split("\n")
    assert len(lines) == 1 and lines[0].startswith("neomesh: error: cannot start the command line")
