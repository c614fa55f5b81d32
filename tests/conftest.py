"""Shared test helpers: ``run_vines`` runs the command line of this checkout."""
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
SRC = ROOT / "src"


def run_vines(*args, timeout=600):
    """``python -m vines *args`` with this checkout's sources; the CompletedProcess (text)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return subprocess.run([sys.executable, "-m", "vines", *args], capture_output=True,
                          text=True, env=env, timeout=timeout, cwd=ROOT)
