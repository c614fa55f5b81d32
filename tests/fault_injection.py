"""Random fault injection into the smoke pipeline (`snakemake -c2 all --configfile
config/smoke.yaml`): SIGKILL or SIGTERM at seeded random instants, the README's remedy after
each, and at the end every dataset compared with an uninterrupted run's.

    python tests/fault_injection.py --seed 1 --faults 3 [--reference results/smoke]

The run happens in a copy of the workflow (src/ without its numba cache, so the onstart
warm-up compiles) under --run-dir; the checkout's results/ and cache are never touched.
Each fault draws from the seed an instant, a target among what runs then (Snakemake, one
job process, the whole run) and a signal. Remedy, exactly the README's: the same command;
the unlock the refused run prints first if it says that the directory is locked (`<command>
--unlock`; Snakemake's own `Directory cannot be locked`: `snakemake --unlock --configfile
config/smoke.yaml`); `kill -9` first if Snakemake has not exited after a signal to it.

Findings (printed; exit status 1 if any, 0 if none, 2 for bad arguments): a process of an
interrupted run still running --grace s after its Snakemake; a damaged numba cache file; a
failed attempt without a fault; a final dry-run with jobs left; a dataset or figure that
differs from the reference's (timings and `git_commit` excepted). Details and a long run:
docs/pipeline.md, "Faults". Needs /proc (Linux) to find the processes; elsewhere the script
says so and exits 0 without running (pytest skips).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: what the copy of the checkout holds (src without caches: a cold numba cache)
COPIED = ("Snakefile", "environment.yml", "profiles", "workflow", "config", "src")
CONFIGFILE = "config/smoke.yaml"
RUN = "smoke"
#: wall-clock measurements, which legitimately differ between two runs
TIMING = {"seconds", "run_time", "impacts_per_second", "calls"}
#: folders of the datasets holding TIMING, and the figures drawn from it
TIMED = {"work_precision", "convergence", "model_ladder"}
TIMED_FIGURES = ("workprecision", "convergence", "model_ladder")
#: provenance attributes that differ between a checkout and its copy
PROVENANCE = {"git_commit"}
#: what a run refused by a lock left by a killed run says: the logger plugin's line (the
#: remedy it prints: `<command> --unlock && <command>`), or Snakemake's own paragraph
LOCKED = ("is locked by a run that was stopped", "is locked by another Snakemake run",
          "cannot be locked")
REMEDY = "run the same command again: "          # the plugin's line, before its remedy
#: what a damaged numba cache answers (issue: truncated .nbc, empty .nbi)
CACHE_DAMAGE = ("UnpicklingError", "pickle data was truncated", "EOFError: Ran out of input")
WARMUP = "vines.pipeline.warmup"                # the onstart warm-up's module
SCRIPTS = ".snakemake/scripts/"                  # where Snakemake puts a job's script
WARMUP_WINDOW = 20.0                             # seconds: warm-up fault instants
TARGETS = ("snakemake", "run", "job")
SIGNALS = {"SIGKILL": signal.SIGKILL, "SIGTERM": signal.SIGTERM}


@dataclass
class Fault:
    """One injected fault and what followed it."""
    n: int
    at_s: float                   # seconds after the attempt's start
    signal: str
    target: str                   # snakemake | job | run
    process: str = ""             # the command line of the signalled process
    snakemake_rc: int | None = None   # the exit status of the attempt's Snakemake
    exit_s: float | None = None   # seconds from the signal to that Snakemake's exit
    remedy: list = field(default_factory=list)


@dataclass
class Report:
    seed: int
    faults_asked: int
    faults: list = field(default_factory=list)
    findings: list = field(default_factory=list)
    notes: list = field(default_factory=list)       # seen, not failures
    attempts: int = 0
    unlocks: int = 0
    sigterm_hangs: int = 0     # Snakemake deadlocked by SIGTERM (README), killed
    wall_s: float = 0.0
    datasets: int = 0
    datasets_identical: int = 0
    figures: int = 0
    figures_identical: int = 0
    load_before: str = ""
    load_after: str = ""


# ------------------------------------------------------------------ processes (/proc)

def _stat(pid: int) -> tuple[int, int] | None:
    """(ppid, session id) of a live process, None if it has ended (or is a zombie)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2:].split()
    if fields[0] in ("Z", "X"):
        return None
    return int(fields[1]), int(fields[3])


def _cmdline(pid: int) -> str:
    try:
        raw = Path(f"/proc/{pid}/cmdline").read_bytes()
    except OSError:
        return ""
    return raw.replace(b"\0", b" ").decode(errors="replace").strip()


def _rss_mb(pid: int) -> float:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def session_pids(sid: int) -> list[int]:
    """Live processes of session ``sid`` (each attempt runs in its own session)."""
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            st = _stat(int(entry))
            if st is not None and st[1] == sid:
                out.append(int(entry))
    return sorted(out)


def job_pids(sid: int, snakemake_pid: int) -> list[int]:
    """The run's Python processes other than Snakemake: workflow scripts, the warm-up and
    its pool workers."""
    return [p for p in session_pids(sid)
            if p != snakemake_pid and "python" in _cmdline(p).split(" ")[0]]


# ------------------------------------------------------------------ the run

class Run:
    """The copy of the workflow under ``work`` and its attempts."""

    def __init__(self, work: Path, cores: int, logs: Path):
        self.work, self.cores, self.logs = work, cores, logs
        self.cmd = [shutil.which("snakemake") or "snakemake", f"-c{cores}", "all",
                    "--configfile", CONFIGFILE]
        self.env = dict(os.environ, PYTHONPATH=str(work / "src"))
        self.n = 0
        self.sessions: list[int] = []         # one per attempt (its Snakemake's pid)

    def start(self) -> subprocess.Popen:
        self.n += 1
        with open(self.logs / f"attempt_{self.n:02d}.log", "w") as log:
            proc = subprocess.Popen(self.cmd, cwd=self.work, env=self.env, stdout=log,
                                    stderr=subprocess.STDOUT, start_new_session=True)
        self.sessions.append(proc.pid)
        return proc

    def kill_all(self) -> None:
        """SIGKILL every process still left of any attempt (the script itself stopped)."""
        for sid in self.sessions:
            for pid in session_pids(sid):
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGKILL)

    def log_text(self) -> str:
        return (self.logs / f"attempt_{self.n:02d}.log").read_text(errors="replace")

    def unlock(self, text: str) -> int:
        """The README's unlock: the first half of the remedy the refused run printed
        (`<command> --unlock && <command>`; the second half is the next attempt), else
        `snakemake --unlock` with the same --configfile."""
        cmd = ["snakemake", "--unlock", "--configfile", CONFIGFILE]
        for line in text.splitlines():
            if REMEDY in line and " && " in line:
                cmd = shlex.split(line.split(REMEDY, 1)[1].split(" && ")[0])
        with open(self.logs / f"unlock_{self.n:02d}.log", "w") as log:
            return subprocess.run(cmd, cwd=self.work, env=self.env, stdout=log,
                                  stderr=subprocess.STDOUT, timeout=600).returncode

    def dry_run(self) -> str:
        r = subprocess.run([*self.cmd, "-n"], cwd=self.work, env=self.env,
                           capture_output=True, text=True, timeout=600)
        return r.stdout + r.stderr


def copy_workflow(dst: Path) -> None:
    dst.mkdir(parents=True)
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info", ".snakemake", "results")
    for name in COPIED:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, dst / name, ignore=ignore)
        else:
            shutil.copy2(src, dst / name)


def output_files(res: Path) -> set[str]:
    """Datasets and figures of a results folder (not logs, benchmarks or temporary files)."""
    if not res.is_dir():
        return set()
    return {str(p.relative_to(res)) for p in res.rglob("*")
            if p.is_file() and p.suffix in (".nc", ".pdf", ".png")
            and not p.name.startswith(".")                # temporary files of writes
            and p.relative_to(res).parts[0] not in ("logs", "benchmarks")}


class Orphans:
    """Sessions of ended Snakemakes: every process left in one must end within ``grace``."""

    def __init__(self, grace: float, report: Report):
        self.grace, self.report, self.ended = grace, report, {}

    def add(self, sid: int) -> None:
        self.ended[sid] = time.monotonic()

    def check(self, final: bool = False) -> None:
        """Report (and kill) processes alive past the grace; with ``final`` wait for it."""
        for sid, t_end in list(self.ended.items()):
            while final and session_pids(sid) and time.monotonic() - t_end < self.grace:
                time.sleep(0.5)
            left = session_pids(sid)
            if not left:
                del self.ended[sid]
            elif time.monotonic() - t_end >= self.grace:
                for pid in left:
                    self.report.findings.append(
                        f"leftover process {pid} ({_rss_mb(pid):.0f} MB) still running "
                        f"{self.grace:.0f} s after its Snakemake ended: {_cmdline(pid)}")
                for pid in left:
                    with contextlib.suppress(ProcessLookupError):
                        os.kill(pid, signal.SIGKILL)
                del self.ended[sid]


def wait_exit(proc: subprocess.Popen, timeout: float) -> int | None:
    try:
        return proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def strike(proc, rng, fault: Fault, targets) -> None:
    """Send the fault's signal to its target, drawn among what runs now (while the warm-up
    runs, a job target is one of its processes)."""
    sid = proc.pid                                 # session leader: sid == its pid
    jobs = job_pids(sid, proc.pid)
    warm = [p for p in jobs if WARMUP in _cmdline(p)]
    jobs = warm or jobs
    kinds = [k for k in TARGETS if k in targets and (k != "job" or jobs)]
    fault.target = rng.choice(kinds or ["snakemake"])
    sig = SIGNALS[fault.signal]
    if fault.target == "snakemake":
        fault.process = _cmdline(proc.pid)
        os.kill(proc.pid, sig)
    elif fault.target == "job":
        pid = rng.choice(jobs)
        fault.process = _cmdline(pid)
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, sig)
    else:
        fault.process = f"the whole run ({len(session_pids(sid))} processes)"
        with contextlib.suppress(ProcessLookupError):
            os.killpg(sid, sig)


def _instant(rng, args, n_fault: int, left: float, ref_seconds: float) -> tuple[float, bool]:
    """(seconds to wait, counted from the warm-up's start?) for the next fault: uniform
    over WARMUP_WINDOW for a warm-up fault, else over twice the remaining work's share per
    fault left (``left``: fraction of the outputs not written yet)."""
    if n_fault < args.warmup_faults:
        return rng.uniform(0.5, WARMUP_WINDOW), True
    window = 2 * left * ref_seconds / (args.faults - n_fault + 1)
    return rng.uniform(0.5, min(args.max_window, max(args.min_window, window))), False


def _locked(text: str) -> bool:
    """Did the run stop on the directory's lock?"""
    return any(m in text for m in LOCKED)


def run_with_faults(run: Run, args, rng, report: Report, orphans: Orphans,
                    total: int, ref_seconds: float) -> None:
    """Attempts of the same command, with faults until ``args.faults``, then to the end;
    each attempt after a fault or a failure is the README's remedy."""
    unlocked = False
    while run.n < args.max_attempts:
        orphans.check()
        last = report.faults[-1] if report.faults else None
        if last is not None and not unlocked:
            last.remedy.append("the same command")
        proc = run.start()
        report.attempts += 1
        n_before = len(report.faults)
        rc = _attempt(proc, run, args, rng, report, total, ref_seconds)
        orphans.add(proc.pid)
        text = run.log_text()
        _cache_damage(text, f"attempt {run.n}", report)
        if len(report.faults) > n_before:          # faulted: the remedy is the next attempt
            unlocked = False
            continue
        if rc == 0:
            if len(report.faults) < args.faults:   # ended before the next instant
                report.notes.append(f"the run completed before the next instant: "
                                    f"{len(report.faults)} of {args.faults} faults")
            return
        if _locked(text) and not unlocked:
            if last is not None:
                last.remedy += ["locked", "snakemake --unlock", "the same command"]
            report.unlocks += 1
            if run.unlock(text) != 0:
                report.findings.append(f"attempt {run.n}: `snakemake --unlock` failed")
            unlocked = True
            continue
        unlocked = False
        tail = " | ".join(text.strip().splitlines()[-6:])
        report.findings.append(f"attempt {run.n} (no fault in it) failed with exit {rc}"
                               f"{' (still locked after --unlock)' if _locked(text) else ''}"
                               f": {tail}")
        if last is not None:
            last.remedy.append(f"failed ({rc})")
    report.findings.append(f"not complete after {run.n} attempts")


def _attempt(proc, run: Run, args, rng, report: Report, total: int,
             ref_seconds: float) -> int:
    """Faults into one running Snakemake until it ends; its exit status. A fault to Snakemake
    or the whole run ends it (else `kill -9` after --hang); after one to a job,
    Snakemake goes on (finishes the running jobs, or the run after a warm-up fault) and the
    next fault may strike it again."""
    res = run.work / "results" / RUN
    t0, first = time.monotonic(), len(report.faults)
    while len(report.faults) < args.faults:
        n = len(report.faults)
        left = 1.0 - len(output_files(res)) / max(total, 1)
        delay, from_warmup = _instant(rng, args, n, left, ref_seconds)
        sig = rng.choice(args.signals)
        rc = _wait_for_instant(proc, time.monotonic(), delay, from_warmup and n == first)
        if rc is not None:
            break
        fault = Fault(n + 1, round(time.monotonic() - t0, 1), sig, "")
        strike(proc, rng, fault, args.targets)
        report.faults.append(fault)
        _say(f"fault {fault.n}/{args.faults}: {sig} to {fault.target} at {fault.at_s} s of "
             f"attempt {run.n} ({fault.process[:100]})")
        if fault.target != "job":
            if wait_exit(proc, args.hang) is None:
                _hung(proc, fault, args.hang, report)
            break
    rc = wait_exit(proc, 10 * args.hang)
    if rc is None:
        report.findings.append(f"attempt {run.n}: Snakemake still running after "
                               f"{10 * args.hang:.0f} s; killed")
        os.killpg(proc.pid, signal.SIGKILL)
        rc = proc.wait()
    t_end = round(time.monotonic() - t0, 1)
    for fault in report.faults[first:]:
        fault.snakemake_rc, fault.exit_s = rc, round(t_end - fault.at_s, 1)
    if len(report.faults) > first:
        _say(f"attempt {run.n}: Snakemake exit {rc} at {t_end} s")
    return rc


def _hung(proc, fault: Fault, hang: float, report: Report) -> None:
    """Snakemake still runs ``hang`` s after a signal to it: the README's remedy ("Snakemake
    does not exit after `kill`": `kill -9`, then the same command). After SIGTERM that is
    Snakemake's known deadlock (its handler waits for the lock of an interrupted job
    selection), a note; after SIGKILL it cannot be, a finding."""
    msg = (f"fault {fault.n}: Snakemake still running {hang:.0f} s after {fault.signal} to "
           f"{fault.target}; kill -9")
    if fault.signal == "SIGTERM":
        report.notes.append(msg + " (Snakemake's SIGTERM deadlock, README)")
        report.sigterm_hangs += 1
    else:
        report.findings.append(msg)
    fault.remedy.append("kill -9")
    os.kill(proc.pid, signal.SIGKILL)


def _wait_for_instant(proc, t0: float, delay: float, from_warmup: bool) -> int | None:
    """Wait until ``delay`` seconds after t0 (after the warm-up's start if ``from_warmup``
    and it starts before the first job); Snakemake's exit status if it ended first."""
    if from_warmup:
        while proc.poll() is None:
            names = [_cmdline(p) for p in session_pids(proc.pid)]
            if any(WARMUP in c or SCRIPTS in c for c in names):
                break
            time.sleep(0.1)
        t0 = time.monotonic()
    while time.monotonic() - t0 < delay:
        if proc.poll() is not None:
            return proc.returncode
        time.sleep(0.1)
    return None


def _cache_damage(text: str, where: str, report: Report) -> None:
    for mark in CACHE_DAMAGE:
        if mark in text:
            report.findings.append(f"{where}: numba cache damaged ({mark})")
            return


def check_cache(src: Path, report: Report) -> None:
    """Read every numba cache file under ``src`` to the end of its pickles (an index .nbi
    holds two: numba's version, then the overloads; a data file .nbc one), without running
    them: a truncated or empty file is a finding; temporary files left by a kill, a note."""
    import io
    import pickletools
    for path in sorted([*src.rglob("*.nbi"), *src.rglob("*.nbc")]):
        stream = io.BytesIO(path.read_bytes())
        try:
            for _ in range(2 if path.suffix == ".nbi" else 1):
                for _op in pickletools.genops(stream):
                    pass
            if stream.read(1):
                raise ValueError("bytes after the last pickle")
        except Exception as err:  # noqa: BLE001 (any failure to read is the finding)
            report.findings.append(f"numba cache damaged: {path.relative_to(src)}: "
                                   f"{type(err).__name__}: {err}")
    tmp = [p for p in src.rglob("*") if ".tmp." in p.name or p.name.startswith(".numba-warm")]
    if tmp:
        report.notes.append(f"{len(tmp)} temporary cache files left by kills, e.g. "
                            f"{tmp[0].relative_to(src)}")


def _tracebacks(text: str, where: str, report: Report) -> None:
    """A note per traceback in ``text``, naming its exception (the first line after it that
    is not indented)."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("Traceback"):
            err = next((ln for ln in lines[i + 1:] if ln and not ln[0].isspace()), "?")
            report.notes.append(f"{where}: a traceback ({err.strip()[:200]})")


# ------------------------------------------------------------------ comparison

def same_array(a, b) -> bool:
    import numpy as np
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind in "fc":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


def same_attrs(a: dict, b: dict, skip=()) -> list[str]:
    keys = (set(a) | set(b)) - set(skip)
    return sorted(k for k in keys if k not in a or k not in b or not same_array(a[k], b[k]))


def compare_dataset(a: Path, b: Path, timed: bool) -> list[str]:
    """What differs between two datasets (empty if nothing)."""
    import xarray as xr
    skip = TIMING if timed else set()
    with xr.open_dataset(a, decode_times=False, mask_and_scale=False) as da, \
            xr.open_dataset(b, decode_times=False, mask_and_scale=False) as db:
        bad = [f"attribute {k}" for k in same_attrs(da.attrs, db.attrs, PROVENANCE)]
        for n in sorted((set(da.variables) | set(db.variables)) - skip):
            if n not in da.variables or n not in db.variables:
                bad.append(f"variable {n} only in one")
            elif da[n].dims != db[n].dims or not same_array(da[n].values, db[n].values):
                bad.append(f"variable {n}")
            else:
                bad += [f"{n} attribute {k}" for k in same_attrs(da[n].attrs, db[n].attrs)]
    return bad


def compare_results(ref: Path, got: Path, report: Report) -> None:
    files = sorted(output_files(ref) | output_files(got))
    for rel in files:
        a, b = ref / rel, got / rel
        is_nc = rel.endswith(".nc")
        if is_nc:
            report.datasets += 1
        else:
            report.figures += 1
        if not (a.exists() and b.exists()):
            report.findings.append(f"{rel}: only in the {'reference' if a.exists() else 'faulted'} run")
            continue
        if is_nc:
            bad = compare_dataset(a, b, Path(rel).parts[0] in TIMED)
            if bad:
                report.findings.append(f"{rel} differs: {', '.join(bad)}")
            else:
                report.datasets_identical += 1
        elif a.read_bytes() == b.read_bytes():
            report.figures_identical += 1
        elif not any(t in Path(rel).name for t in TIMED_FIGURES):
            report.findings.append(f"{rel} differs (bytes)")
        else:
            report.figures -= 1        # drawn from wall-clock timings: not compared


# ------------------------------------------------------------------ main

def _say(msg: str) -> None:
    print(f"[faults {time.strftime('%H:%M:%S')}] {msg}", flush=True)


def _load() -> str:
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "?"


def make_reference(dst: Path, cores: int) -> tuple[Path, float]:
    """An uninterrupted `all` smoke run in its own copy; (results folder, wall seconds)."""
    copy_workflow(dst)
    _say(f"reference run in {dst}")
    t0 = time.monotonic()
    proc = subprocess.Popen([shutil.which("snakemake") or "snakemake", f"-c{cores}", "all",
                             "--configfile", CONFIGFILE], cwd=dst, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True,
                            env=dict(os.environ, PYTHONPATH=str(dst / "src")))
    try:
        out, _ = proc.communicate()
    except BaseException:                  # stopped: end the reference run with it
        os.killpg(proc.pid, signal.SIGKILL)
        raise
    if proc.returncode != 0:
        raise SystemExit(f"fault injection: the reference run failed:\n{out[-3000:]}")
    return dst / "results" / RUN, time.monotonic() - t0


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--seed", type=int, default=0, help="seed of the instants, targets, signals")
    p.add_argument("--faults", type=int, default=3, help="number of faults (default 3)")
    p.add_argument("--warmup-faults", type=int, default=1,
                   help="how many of the first faults strike during the warm-up (default 1)")
    p.add_argument("--run-dir", type=Path, help="folder for the copies and logs "
                   "(default: a temporary folder, removed unless --keep)")
    p.add_argument("--reference", type=Path, help="results/smoke of an uninterrupted "
                   "`snakemake -c2 all --configfile config/smoke.yaml` of this code")
    p.add_argument("--reference-seconds", type=float, default=150.0,
                   help="wall time of an uninterrupted run with a warm cache, used to spread "
                   "the instants when --reference is given (default 150)")
    p.add_argument("--targets", nargs="+", choices=TARGETS, default=list(TARGETS),
                   help="what may be signalled (default all; snakemake when no job runs)")
    p.add_argument("--signals", nargs="+", choices=sorted(SIGNALS), default=sorted(SIGNALS))
    p.add_argument("--cores", type=int, default=2)
    p.add_argument("--grace", type=float, default=180.0, help="seconds a process of an "
                   "interrupted run may outlive its Snakemake (default 180)")
    p.add_argument("--hang", type=float, default=180.0, help="seconds Snakemake may take to "
                   "exit after a signal to it (default 180)")
    p.add_argument("--min-window", type=float, default=3.0)
    p.add_argument("--max-window", type=float, default=90.0)
    p.add_argument("--max-attempts", type=int, default=0, help="default: 3 x faults + 10")
    p.add_argument("--keep", action="store_true", help="keep --run-dir's temporary folder")
    p.add_argument("--json", type=Path, help="write the report here as JSON")
    args = p.parse_args(argv)
    for name in ("faults", "warmup_faults", "cores", "max_attempts"):
        if getattr(args, name) < 0 or (name == "cores" and args.cores < 1):
            p.exit(2, f"fault injection: --{name.replace('_', '-')} {getattr(args, name)}: "
                   "must be a non-negative integer (--cores: at least 1)\n")
    if args.reference is not None and not (args.reference / "figures").is_dir():
        p.exit(2, f"fault injection: --reference {args.reference}: not a results folder of a "
               "smoke run (no figures/ in it)\n")
    args.max_attempts = args.max_attempts or 3 * args.faults + 10
    return args


def main(argv=None) -> int:
    args = parse_args(argv)
    if not Path("/proc/self/stat").exists():
        print("fault injection: needs /proc (Linux) to find the run's processes; not run")
        return 0
    if shutil.which("snakemake") is None:
        print("fault injection: snakemake not found (pip install -e '.[pipeline]')")
        return 2
    tmp = None
    if args.run_dir is None:
        tmp = args.run_dir = Path(tempfile.mkdtemp(prefix="vines-faults-"))
    base = args.run_dir.resolve()
    base.mkdir(parents=True, exist_ok=True)
    report = Report(args.seed, args.faults, load_before=_load())
    t_start = time.monotonic()
    run = None
    on_term = signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # to the finally
    try:
        if args.reference is not None:
            ref, ref_seconds = args.reference.resolve(), args.reference_seconds
        else:
            ref, ref_seconds = make_reference(base / "reference", args.cores)
            _say(f"reference: {ref_seconds:.0f} s")
        work = base / "faulted"
        if work.exists():
            shutil.rmtree(work)
        copy_workflow(work)
        logs = base / "logs"
        logs.mkdir(exist_ok=True)
        run = Run(work, args.cores, logs)
        orphans = Orphans(args.grace, report)
        rng = random.Random(args.seed)
        _say(f"seed {args.seed}, {args.faults} faults, in {work}")
        total = len(output_files(ref))
        run_with_faults(run, args, rng, report, orphans, total, ref_seconds)
        orphans.check(final=True)
        plan = run.dry_run()
        if "Nothing to be done" not in plan:
            report.findings.append("a dry-run after the run still has jobs to do: "
                                   + " | ".join(plan.strip().splitlines()[-4:]))
        for p in sorted((work / "results" / RUN / "logs").rglob("*.log")):
            _cache_damage(p.read_text(errors="replace"), str(p.relative_to(work)), report)
        for p in sorted(logs.glob("*.log")):
            _tracebacks(p.read_text(errors="replace"), p.name, report)
        check_cache(work / "src", report)
        partial = sorted(str(q.relative_to(work)) for q in (work / "results").rglob(".*")
                         if q.is_file())
        if partial:
            report.notes.append(f"{len(partial)} temporary files of killed writes left in "
                                f"results/: {', '.join(partial[:5])}")
        compare_results(ref, work / "results" / RUN, report)
    finally:
        signal.signal(signal.SIGTERM, on_term)
        if run is not None:
            run.kill_all()
        report.wall_s = round(time.monotonic() - t_start, 1)
        report.load_after = _load()
        if tmp is not None and not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    _summary(report, args)
    return 1 if report.findings else 0


def _summary(report: Report, args) -> None:
    kinds = {}
    for f in report.faults:
        key = f"{f.signal} {f.target}"
        kinds[key] = kinds.get(key, 0) + 1
    for line in report.notes:
        print("  note:", line)
    for line in report.findings:
        print("  finding:", line)
    print(f"fault injection (seed {report.seed}): {len(report.faults)} faults "
          f"({', '.join(f'{v} {k}' for k, v in sorted(kinds.items()))}), "
          f"{report.attempts} attempts, {report.unlocks} unlocks, "
          f"{report.sigterm_hangs} SIGTERM deadlocks; "
          f"{report.datasets} datasets, {report.datasets_identical} identical; "
          f"{report.figures} figures, {report.figures_identical} identical; "
          f"{len(report.findings)} findings; {report.wall_s:.0f} s "
          f"(load {report.load_before} -> {report.load_after})")
    if args.json is not None:
        data = asdict(report)
        args.json.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main())
