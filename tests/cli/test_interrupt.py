"""Ctrl-C during a run leaves no partial output: SIGINT while `smooth` iterates on a mesh
large enough to take several seconds; the process must end on the signal, say it was
interrupted, and leave neither the output file nor a temporary file behind."""
import os
import signal
import subprocess
import sys
import tempfile
import time

NEOMESH = os.path.abspath(os.environ["NEOMESH"]) if "NEOMESH" in os.environ else "neomesh"


def check(condition, message):
    if not condition:
        sys.exit(message)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        mesh = os.path.join(tmp, "random.msh")
        subprocess.run([NEOMESH, "generate", "square-random", "--level", "7", "-o", mesh],
                       check=True, capture_output=True, timeout=60)
        before = sorted(os.listdir(tmp))
        # Iterates until interrupted: no stopping criterion can be met.
        proc = subprocess.Popen(
            [NEOMESH, "smooth", mesh, "-o", os.path.join(tmp, "out.vtu"), "--no-table",
             "--no-practical", "--tol", "0", "--rtol", "0", "--max-iter", "100000",
             "--report", os.path.join(tmp, "report.json")],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        start = time.monotonic()
        # Wait until it iterates, then about a second more.
        for line in proc.stdout:
            if line.startswith("iteration 1:"):
                break
        time.sleep(max(0.0, 1.0 - (time.monotonic() - start)) + 0.3)
        check(proc.poll() is None, f"smooth ended before the interrupt: {proc.returncode}")
        proc.send_signal(signal.SIGINT)
        try:
            _, err = proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            sys.exit("smooth did not stop within 30 s of SIGINT")
        check(proc.returncode == -signal.SIGINT,
              f"expected death by SIGINT, exit {proc.returncode}; stderr {err!r}")
        check("interrupted" in err, f"stderr does not say it was interrupted: {err!r}")
        after = sorted(os.listdir(tmp))
        check(after == before, f"files left behind: {sorted(set(after) - set(before))}")
    print("Ctrl-C leaves no output")


if __name__ == "__main__":
    main()
