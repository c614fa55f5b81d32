"""A damaged, unwritable or missing numba cache (vines._jit): every command still answers,
exactly as with a sound cache, with one warning line naming what was removed; never a
traceback. Each test runs real commands in subprocesses on its own copy of a warm cache
(``NUMBA_CACHE_DIR``), so the checkout's own cache is never touched."""
import json
import os
import pickle
import random
import re
import shutil
import subprocess
import sys

import numba
import pytest
from conftest import ROOT, SRC

SIMULATE = ["-m", "vines", "simulate", "--eta", "0.05", "--omega", "1", "--F", "0.05",
            "--t-end", "200", "--t-transient", "100", "--json", "-q"]
MODEL = {"r": 0.65, "d": 0.011997966952746818}
SIMULATION = {"t_end": 1000.0, "t_transient": 600.0, "v_stick": 1e-6, "max_impacts": 2_000_000,
              "root_tol": 1e-13, "periodic_shortcut": True}
#: the pipeline's warm-up (vines.pipeline.warmup) restricted to the kernels of the core stages
#: (simulate_grid, sweeps, time histories, basin slices), its stamp in a temporary file
WARMUP = ["-c", "import sys; from vines.pipeline import warmup as w; w.STAMP = "
          "w.Path(sys.argv.pop(1)); w.TASKS = {k: w.TASKS[k] for k in ('seeds', 'core')}; "
          "sys.exit(w.main())"]
HEALED = re.compile(r"^vines: removed (\d+) damaged numba cache file\(s\) \((.+)\) in (\S+): "
                    r"(.+); their kernels are compiled again$")


def _run(args, cache, env=None):
    env = {**os.environ, "PYTHONPATH": str(SRC), "NUMBA_CACHE_DIR": str(cache), **(env or {})}
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=600)


def _warmup(cache, stamp):
    return _run([*WARMUP, str(stamp), "--model", json.dumps(MODEL),
                 "--simulation", json.dumps(SIMULATION), "--jobs", "2"], cache)


@pytest.fixture(scope="module")
def warm(tmp_path_factory):
    """(a cache warmed by the core warm-up and the command, the command's answer)."""
    cache = tmp_path_factory.mktemp("warm") / "cache"
    assert _warmup(cache, cache.parent / "stamp").returncode == 0
    r = _run(SIMULATE, cache)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert json.loads(r.stdout)["status"] == "ok"
    return cache, r.stdout


def _copy(warm, tmp_path):
    """A copy of the warm cache and its folder of the core kernels."""
    cache = tmp_path / "cache"
    shutil.copytree(warm[0], cache)
    (core,) = cache.glob("core_*")
    return cache, core


def _truncate(path):
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])


def _empty(path):
    path.write_bytes(b"")


def _garbage(path):
    path.write_bytes(random.Random(path.name).randbytes(path.stat().st_size))


#: the files of the entry kernel (kernel.py) only: what is damaged is compiled again, and
#: the kernel module's files are the ones the command loads first
DAMAGE = {"truncated .nbc": ("kernel.*.nbc", _truncate, "pickle data was truncated"),
          "empty .nbi": ("kernel.*.nbi", _empty, "empty"),
          "garbage .nbc": ("kernel.*.nbc", _garbage, ""),
          "garbage .nbi": ("kernel.*.nbi", _garbage, "")}


def _damage(core, pattern, damage):
    """Damage the files ``pattern`` of ``core``; the names that may be removed: those and the
    data files of a damaged index."""
    damaged = sorted(core.glob(pattern))
    assert damaged
    removable = {p.name for p in damaged}
    removable |= {q.name for p in damaged if p.suffix == ".nbi" for q in core.glob(f"{p.stem}.*")}
    for path in damaged:
        damage(path)
    return removable


def _assert_one_line_naming(stderr, removable, why):
    lines = stderr.splitlines()
    assert len(lines) == 1, stderr
    m = HEALED.match(lines[0])
    assert m, lines[0]
    assert why in m.group(2)
    names = [n.split(" and ")[0] for n in m.group(4).split(", ")]
    assert names and set(names) <= removable
    assert len(names) <= int(m.group(1)) <= len(removable)


@pytest.mark.parametrize("kind", DAMAGE)
def test_damaged_cache_is_removed_and_recompiled(warm, tmp_path, kind):
    """Truncated, empty or garbage files (what a full disk or a crash while numba writes
    leaves): the command answers exactly as before, exit 0, one line naming the removed files;
    the next run loads the rebuilt cache silently."""
    pattern, damage, why = DAMAGE[kind]
    cache, core = _copy(warm, tmp_path)
    removable = _damage(core, pattern, damage)
    r = _run(SIMULATE, cache)
    assert r.returncode == 0, r.stderr
    assert r.stdout == warm[1]
    _assert_one_line_naming(r.stderr, removable, why)
    again = _run(SIMULATE, cache)
    assert (again.returncode, again.stdout, again.stderr) == (0, warm[1], "")


def test_damaged_cache_through_the_api(warm, tmp_path):
    cache, core = _copy(warm, tmp_path)
    removable = _damage(core, "kernel.*.nbc", _truncate)
    code = ("import vines; r = vines.simulate(eta=0.05, omega=1.0, F=0.05, t_end=200.0, "
            "t_transient=100.0); print(repr(r.ke_ratio), r.n_impacts)")
    r = _run(["-c", code], cache)
    assert r.returncode == 0, r.stderr
    expected = json.loads(warm[1])
    assert r.stdout.split() == [repr(expected["ke_ratio"]), str(expected["n_impacts"])]
    _assert_one_line_naming(r.stderr, removable, "truncated")


def test_index_of_another_numba_version_is_replaced_in_one_line(warm, tmp_path):
    """numba itself ignores an index whose version is not its own and writes a new one: no
    damage, the same answer, one line saying so; the next run is silent."""
    cache, core = _copy(warm, tmp_path)
    for path in core.glob("*.nbi"):
        with open(path, "rb") as fh:
            pickle.load(fh)
            rest = fh.read()
        path.write_bytes(pickle.dumps("0.1.0") + rest)
    r = _run(SIMULATE, cache)
    assert (r.returncode, r.stdout) == (0, warm[1]), r.stderr
    (line,) = r.stderr.splitlines()
    assert re.fullmatch(rf"vines: numba cache in \S+ written by numba 0\.1\.0 \(this is "
                        rf"{re.escape(numba.__version__)}\): ignored and replaced; the kernels "
                        r"are compiled again", line), line
    again = _run(SIMULATE, cache)
    assert (again.returncode, again.stdout, again.stderr) == (0, warm[1], "")
    versions = set()
    for path in core.glob("*.nbi"):
        with open(path, "rb") as fh:
            versions.add(pickle.load(fh))
    assert numba.__version__ in versions


def test_warmup_heals_a_damaged_cache(warm, tmp_path):
    """The pipeline's warm-up (onstart hook of every run) on a damaged cache: its usual two
    lines and one naming the removed files; its workers then compile the stages' kernels."""
    cache, core = _copy(warm, tmp_path)
    removable = _damage(core, "*.nbc", _truncate)
    r = _warmup(cache, tmp_path / "stamp")
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    healed = [ln for ln in r.stderr.splitlines() if "damaged" in ln]
    _assert_one_line_naming("\n".join(healed), removable, "truncated")
    assert len(r.stderr.splitlines()) == 3, r.stderr     # compiling ..., removed ..., compiled
    assert (tmp_path / "stamp").exists()
    again = _run(SIMULATE, cache)
    assert (again.returncode, again.stdout, again.stderr) == (0, warm[1], "")


def test_no_writable_cache_folder_compiles_in_memory(warm, tmp_path):
    """A read-only install with no writable cache folder (the package's __pycache__, numba's
    user cache and NUMBA_CACHE_DIR all impossible: each under a file, which root cannot
    override either): the answer, one line, nothing written."""
    src = tmp_path / "src"
    shutil.copytree(SRC / "vines", src / "vines", ignore=shutil.ignore_patterns("__pycache__"))
    for folder in [src / "vines", *(src / "vines").rglob("*")]:
        if folder.is_dir():
            (folder / "__pycache__").write_text("not a folder")
    blocker = tmp_path / "file"
    blocker.write_text("")
    r = _run(SIMULATE, blocker / "numba", env={"PYTHONPATH": str(src),
                                               "XDG_CACHE_HOME": str(blocker / "xdg"),
                                               "HOME": str(blocker / "home")})
    assert r.returncode == 0, r.stderr
    assert r.stdout == warm[1]
    assert len(r.stderr.splitlines()) == 1, r.stderr
    assert r.stderr.startswith("vines: no writable folder for numba's cache")
    assert "NUMBA_CACHE_DIR" in r.stderr
    assert not [p for p in tmp_path.rglob("*") if p.suffix in (".nbi", ".nbc")]


# ------------------------------------------------------------------ a cache that cannot be written

def _unloadable(cache) -> list[str]:
    """Cache files numba could not load, and temporary files left behind."""
    from vines._jit import damaged
    return [str(p) for p in cache.rglob("*") if p.is_file()
            and (".tmp." in p.name or p.suffix in (".nbi", ".nbc") and damaged(p))]


SAVE_FAILED = re.compile(r"^vines: could not write numba's cache in (\S+) \((.+)\); the compiled "
                         r"kernels are kept in memory for this run$")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX resource limits")
def test_cache_write_failing_midway_keeps_the_kernels_in_memory(warm, tmp_path):
    """The cache's files grow past what the file system takes (here the file-size limit,
    RLIMIT_FSIZE: writes past 4 kB fail with EFBIG, as on a full disk with ENOSPC): the
    command answers as before, one line, and no file is left half-written."""
    import resource
    cache, core = _copy(warm, tmp_path)
    for path in core.glob("kernel.*"):            # the event kernel must be compiled and saved
        path.unlink()

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))

    env = {**os.environ, "PYTHONPATH": str(SRC), "NUMBA_CACHE_DIR": str(cache)}
    r = subprocess.run([sys.executable, *SIMULATE], capture_output=True, text=True, env=env,
                       cwd=ROOT, timeout=600, preexec_fn=limit)
    assert r.returncode == 0, r.stderr
    assert r.stdout == warm[1]
    (line,) = r.stderr.splitlines()
    m = SAVE_FAILED.match(line)
    assert m and m.group(1) == str(core) and m.group(2) == "File too large", line
    assert not _unloadable(cache)
    again = _run(SIMULATE, cache)                   # room again: compiled and cached once more
    assert (again.returncode, again.stdout, again.stderr) == (0, warm[1], "")


def _can_mount_tmpfs(folder) -> bool:
    if shutil.which("unshare") is None:
        return False
    r = subprocess.run(["unshare", "-rm", "sh", "-c", f"mount -t tmpfs -o size=64k tmpfs {folder}"],
                       capture_output=True)
    return r.returncode == 0


@pytest.mark.slow   # the same save failure (errno line, nothing half-written) runs in the fast
#                   suite as test_cache_write_failing_midway_keeps_the_kernels_in_memory
def test_full_disk_while_numba_writes_its_cache(warm, tmp_path):
    """A real full disk (a 64 kB tmpfs in a user and mount namespace: no root needed where
    unprivileged namespaces are allowed) as the cache folder, from an empty cache: the command
    answers as before, one line naming ENOSPC, nothing half-written; run twice."""
    disk = tmp_path / "disk"
    disk.mkdir()
    if not _can_mount_tmpfs(disk):
        pytest.skip("no tmpfs in a user namespace here")
    check = ("import pathlib, sys; sys.path.insert(0, 'tests'); from test_cache_faults import "
             f"_unloadable; print('unloadable', _unloadable(pathlib.Path('{disk}')))")
    simulate = " ".join([sys.executable, *SIMULATE])
    script = (f"mount -t tmpfs -o size=64k tmpfs {disk} && {simulate} && {simulate} && "
              f"{sys.executable} -c \"{check}\"")
    env = {**os.environ, "PYTHONPATH": str(SRC), "NUMBA_CACHE_DIR": str(disk)}
    r = subprocess.run(["unshare", "-rm", "sh", "-c", script], capture_output=True, text=True,
                       env=env, cwd=ROOT, timeout=900)
    assert r.returncode == 0, r.stderr
    answers = r.stdout.splitlines()
    assert answers == [warm[1].strip(), warm[1].strip(), "unloadable []"]
    lines = r.stderr.splitlines()
    assert len(lines) == 2, r.stderr                # one line for each of the two commands
    for line in lines:
        m = SAVE_FAILED.match(line)
        assert m and m.group(2) == "No space left on device", line


def test_kernels_run_as_python_with_numba_disabled(warm, tmp_path):
    """``NUMBA_DISABLE_JIT=1`` (numba's switch for debugging a kernel in Python): njit gives
    back the plain function, nothing is cached, and the command answers as compiled: the
    same impacts (the same floating-point operations in the same order, to the root
    tolerance of 1e-13 in time: the loose 1e-9 allows for a libm of another precision)."""
    r = _run(SIMULATE, tmp_path / "unused", env={"NUMBA_DISABLE_JIT": "1"})
    assert r.returncode == 0 and r.stderr == "", r.stderr
    python, compiled = json.loads(r.stdout), json.loads(warm[1])
    assert python["status"] == compiled["status"] == "ok"
    assert python["n_impacts"] == compiled["n_impacts"] > 0
    for key in ("ke_ratio", "xmax", "t_stuck"):
        assert python[key] == pytest.approx(compiled[key], rel=1e-9, abs=1e-12), key
    assert not (tmp_path / "unused").exists()
