"""Shared test helpers: ``run_vines`` runs the command line of this checkout,
``run_on_terminal`` the same with stderr on a pseudo-terminal, ``json_paths`` the key paths
of a JSON value."""
import fcntl
import os
import pathlib
import pty
import select
import signal
import struct
import subprocess
import sys
import termios
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SRC = ROOT / "src"


def run_vines(*args, timeout=600):
    """``python -m vines *args`` with this checkout's sources; the CompletedProcess (text)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return subprocess.run([sys.executable, "-m", "vines", *args], capture_output=True,
                          text=True, env=env, timeout=timeout, cwd=ROOT)


def run_on_terminal(*args, timeout=600, interrupt_on: str | None = None):
    """``python -m vines *args`` with stderr on a pseudo-terminal (100 columns) and stdout
    on a pipe: (exit status, stdout, everything the terminal received). With
    ``interrupt_on``, SIGINT (Ctrl-C) is sent once the terminal has received that text
    (e.g. a progress bar's description: the command's loop has started). The process is
    killed if it has not ended after ``timeout`` seconds."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(SRC), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep))
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = subprocess.Popen([sys.executable, "-m", "vines", *args], stdout=subprocess.PIPE,
                            stderr=slave, stdin=subprocess.DEVNULL, env=env, cwd=ROOT)
    os.close(slave)
    received, deadline = b"", time.monotonic() + timeout
    marker = None if interrupt_on is None else interrupt_on.encode()
    try:
        while time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 0.2)
            if ready:
                try:
                    data = os.read(master, 65536)
                except OSError:           # the terminal closed: the process has ended
                    break
                if not data:
                    break
                received += data
                if marker is not None and marker in received:
                    proc.send_signal(signal.SIGINT)
                    marker = None
            elif proc.poll() is not None:
                break
        if time.monotonic() >= deadline:
            proc.kill()
        out = proc.stdout.read().decode()
        proc.wait(timeout=60)
    finally:
        os.close(master)
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, out, received.decode(errors="replace")


def json_paths(x, prefix: str = "") -> set:
    """Every key path of a JSON value ("branch.[].dw": list elements share ``[]``)."""
    if isinstance(x, dict):
        return set().union(*({prefix + k} | json_paths(v, prefix + k + ".") for k, v in x.items()))
    if isinstance(x, list):
        return set().union(set(), *(json_paths(v, prefix + "[].") for v in x))
    return set()
