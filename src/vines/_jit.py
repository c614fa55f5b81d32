"""numba's ``njit`` for vines' kernels, with an on-disk compile cache that heals itself.

numba (``cache=True``) keeps each compiled kernel in an index file (``*.nbi``) and data files
(``*.nbc``) and does not recover from a damaged one: a truncated or empty file (a full disk, a
crash, a bad copy) raises ``UnpicklingError`` or ``EOFError`` from every call. ``njit(cache=True)``
here gives the dispatcher a ``HealingCache`` in place of numba's ``FunctionCache``:

- a cache file that cannot be loaded: every cache file of vines' kernels is checked
  (``damaged``), the damaged ones are removed, one line on stderr names them, and the kernels
  are compiled again (and cached anew);
- a cache that cannot be written (full disk, read-only folder): one line; the compiled kernels
  are kept in memory for the run;
- no writable folder at all (a read-only install without a writable ``~/.cache`` or
  ``NUMBA_CACHE_DIR``): one line; the kernels are compiled in memory at every start.

An index written by another numba version is no damage: numba ignores it and replaces it;
one line says so (read only when a kernel is not found in the cache, i.e. compiled anyway). The
numba internals used here: the dispatcher's ``_cache`` slot (what ``enable_caching`` sets),
``caching.FunctionCache`` and ``caching._CacheLocator.get_suitable_cache_subpath``
(tests/test_cache_faults.py fails if they change).
"""
from __future__ import annotations

import functools
import io
import pickle
import sys
from pathlib import Path

import numba
from numba import njit as _numba_njit
from numba.core import caching

from ._numba_cache import kernel_sources

PKG_DIR = Path(__file__).resolve().parent
_said: set[str] = set()   # the messages of this process, each said once


def _say(key: str, message: str) -> None:
    """One line on stderr, once per process for each ``key``."""
    if key not in _said:
        _said.add(key)
        print(f"vines: {message}", file=sys.stderr, flush=True)


def damaged(path: Path) -> str | None:
    """Why numba cannot load the cache file ``path`` (None: it can, or it is gone)."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return None
    except OSError as exc:
        return exc.strerror or type(exc).__name__
    if not data:
        return "empty"
    try:
        if path.suffix == ".nbi":
            stream = io.BytesIO(data)
            if pickle.load(stream) != numba.__version__:
                return None                       # another numba's: numba replaces it
            _stamp, overloads = pickle.loads(stream.read())
            if not isinstance(overloads, dict):
                return "not an index"
        else:
            pickle.loads(data)
    except Exception as exc:                      # noqa: BLE001 (any unreadable pickle)
        return str(exc) or type(exc).__name__
    return None


def cache_folders(cache_path: str) -> list[Path]:
    """The folders of all vines' kernels, given the folder of one: numba keeps those of a
    source folder in its ``__pycache__`` or in ``<cache root>/<name>_<sha1 of its path>``."""
    sources = sorted({PKG_DIR / Path(rel).parent for rel in kernel_sources(PKG_DIR)})
    if Path(cache_path).name == "__pycache__":
        return [folder / "__pycache__" for folder in sources]
    root = Path(cache_path).parent
    return [root / caching._CacheLocator.get_suitable_cache_subpath(str(folder / "x.py"))
            for folder in sources]


def _remove(path: Path, removed: list[Path], kept: list[Path]) -> None:
    try:
        path.unlink()
        removed.append(path)
    except FileNotFoundError:
        pass
    except OSError:
        kept.append(path)


def _names(folder: Path, names: list[str], shown: int = 3) -> str:
    """'in <folder>: a, b, c and 4 more'."""
    more = f" and {len(names) - shown} more" if len(names) > shown else ""
    return f"in {folder}: {', '.join(names[:shown])}{more}"


def heal(cache_path: str) -> bool:
    """Remove every damaged cache file of vines' kernels (with the data files of a damaged
    index) and say so in one line; True if any was damaged."""
    removed: list[Path] = []
    kept: list[Path] = []
    reasons: dict[str, None] = {}
    for folder in cache_folders(cache_path):
        for path in sorted(folder.glob("*.nbi")) + sorted(folder.glob("*.nbc")):
            why = damaged(path)
            if why is None:
                continue
            reasons[why] = None
            data = sorted(folder.glob(f"{path.stem}.*.nbc")) if path.suffix == ".nbi" else []
            for victim in [path, *data]:
                _remove(victim, removed, kept)
    if not removed and not kept:
        return False
    where = "; ".join(_names(folder, [p.name for p in removed if p.parent == folder])
                      for folder in dict.fromkeys(p.parent for p in removed))
    why = "; ".join(list(reasons)[:2]) + ("; ..." if len(reasons) > 2 else "")
    text = f"removed {len(removed)} damaged numba cache file(s) ({why}) {where}"
    if kept:
        text += f"; could not remove {', '.join(map(str, kept))}"
    _say(f"heal {sorted(map(str, removed + kept))}", f"{text}; their kernels are compiled again")
    return True


def index_version(path: Path) -> str | None:
    """The numba version that wrote the index ``path`` (None: absent or unreadable)."""
    try:
        with open(path, "rb") as fh:
            version = pickle.load(fh)
    except Exception:                             # noqa: BLE001 (absent or damaged: heal's)
        return None
    return version if isinstance(version, str) else None


def _say_other_version(index: Path) -> None:
    """One line (once per process) if ``index`` was written by another numba version: numba
    ignores such an index and writes its own over it."""
    version = index_version(index)
    if version is not None and version != numba.__version__:
        _say("other version", f"numba cache in {index.parent} written by numba {version} "
                              f"(this is {numba.__version__}): ignored and replaced; the "
                              "kernels are compiled again")


class HealingCache(caching.FunctionCache):
    """numba's per-function cache; a damaged file is removed and the kernel compiled again, a
    failed write leaves the kernel in memory (see the module's docstring)."""

    def load_overload(self, sig, target_context):
        try:
            loaded = super().load_overload(sig, target_context)
        except Exception as exc:                  # noqa: BLE001 (then compiled: always safe)
            if not heal(self.cache_path):
                _say(f"load {self.cache_path} {self._name}",
                     f"could not load {self._name} from numba's cache in {self.cache_path} "
                     f"({exc}); it is compiled again")
            return None
        if loaded is None:                        # a miss: compiled now (say why if foreign)
            _say_other_version(Path(self._cache_file._index_path))
        return loaded

    def save_overload(self, sig, data):
        try:
            super().save_overload(sig, data)
        except Exception as exc:                  # noqa: BLE001 (the kernel is compiled)
            why = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
            _say("save", f"could not write numba's cache in {self.cache_path} ({why}); the "
                         "compiled kernels are kept in memory for this run")


def _enable_cache(dispatcher) -> None:
    """What numba's ``enable_caching`` does, with a ``HealingCache``."""
    try:
        dispatcher._cache = HealingCache(dispatcher.py_func)
    except RuntimeError:                          # numba found no writable folder
        _say("no folder", "no writable folder for numba's cache (the package's __pycache__, "
                          "~/.cache/numba): the kernels are compiled in memory at every start; "
                          "set NUMBA_CACHE_DIR to a writable folder to keep them")


def njit(fn=None, *, cache: bool = False, **options):
    """``numba.njit``; with ``cache=True`` the compiled code is kept in a ``HealingCache``.
    With ``NUMBA_DISABLE_JIT=1`` numba returns ``fn`` itself (no dispatcher, no cache)."""
    if fn is None:
        return functools.partial(njit, cache=cache, **options)
    dispatcher = _numba_njit(**options)(fn)
    if cache and hasattr(dispatcher, "py_func"):
        _enable_cache(dispatcher)
    return dispatcher


def check_cache(kernel) -> bool:
    """Check the cache files of vines' kernels now (``heal``), wherever numba keeps them,
    found from the cache of one of them, ``kernel`` (a dispatcher of ``njit(cache=True)``);
    True if any was damaged (the warm-up does this before its workers start)."""
    cache = getattr(kernel, "_cache", None)
    path = getattr(cache, "cache_path", None)    # None: no cache (compiled in memory)
    return heal(path) if path else False
