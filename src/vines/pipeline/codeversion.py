"""Code versions of the pipeline's rules: sha256 of the vines subpackages a rule depends on.

Snakemake tracks a rule's script by its modification time only and not the modules it
imports, so every rule gets as params the code version of the subpackages its numbers (or
drawings) come from and the hash of its own script (``script_version``): editing one of them
reruns exactly the rules that depend on it, while touching or checking out an unchanged file reruns
nothing (the default profile turns Snakemake's mtime-based ``code`` trigger off; see
docs/pipeline.md). The package's top-level modules other than the command line
(``__init__``, the numba cache guard) count for every rule.
"""
from __future__ import annotations

import hashlib
from pathlib import Path

PKG_DIR = Path(__file__).resolve().parents[1]

#: top-level modules and subpackages no dataset or figure depends on (the command line)
NOT_TRACKED = ("cli", "__main__.py")

#: subpackages each kind of rule depends on
COMPUTE = ("core", "orbits", "data", "pipeline")           # every dataset stage
STUDIES = COMPUTE + ("reference", "studies", "multimode")  # work-precision, convergence;
#                                                            multimode: the reference imports it
ATTRACTORS = COMPUTE + ("attractors",)                     # robust-TET maps, basin slices
DESIGN = STUDIES + ("attractors",)                         # designs (census of the attractors)
FIGURES = ("plotting",)                                    # figure rules (+ their script)
MODELS = DESIGN + ("slowflow",)                            # the slow flow beside the exact model
#: every kind above (a job's code param must be the version of one of them)
KINDS = (COMPUTE, STUDIES, ATTRACTORS, DESIGN, FIGURES, MODELS)


def tracked_files(subpackages, pkg_dir=PKG_DIR) -> list[Path]:
    """The sources a rule depending on ``subpackages`` is rerun for, sorted."""
    pkg_dir = Path(pkg_dir)
    files = [f for f in pkg_dir.glob("*.py") if f.name not in NOT_TRACKED]
    for sub in subpackages:
        if not (pkg_dir / sub / "__init__.py").is_file():
            raise ValueError(f"vines has no subpackage {sub!r}")
        files += (pkg_dir / sub).rglob("*.py")
    return sorted(files)


def code_version(subpackages, pkg_dir=PKG_DIR) -> str:
    """sha256 (16 hex digits) over the names and contents of ``tracked_files``."""
    h = hashlib.sha256()
    for f in tracked_files(subpackages, pkg_dir):
        h.update(f.relative_to(pkg_dir).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()[:16]


def script_version(path) -> str:
    """sha256 (16 hex digits) of the contents of one workflow script."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
