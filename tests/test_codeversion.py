"""Rerun hashes by subpackage: every module but the CLI is tracked by some rule kind, and a
plotting module by the figure rules only (the dry-run check is in test_pipeline.py)."""
import shutil
from pathlib import Path

import pytest

from vines.pipeline.codeversion import (
    ATTRACTORS,
    COMPUTE,
    FIGURES,
    MODELS,
    NOT_TRACKED,
    PKG_DIR,
    STUDIES,
    code_version,
    tracked_files,
)

KINDS = {"compute": COMPUTE, "studies": STUDIES, "attractors": ATTRACTORS, "figures": FIGURES,
         "models": MODELS}
MODULES = sorted(p.relative_to(PKG_DIR) for p in PKG_DIR.rglob("*.py")
                 if p.relative_to(PKG_DIR).parts[0] not in NOT_TRACKED)


@pytest.fixture(scope="module")
def pkg_copy(tmp_path_factory):
    dst = tmp_path_factory.mktemp("src") / "vines"
    shutil.copytree(PKG_DIR, dst, ignore=shutil.ignore_patterns("__pycache__"))
    return dst


def _versions(pkg):
    return {k: code_version(subs, pkg) for k, subs in KINDS.items()}


@pytest.mark.parametrize("module", MODULES, ids=str)
def test_editing_any_module_changes_a_code_version(pkg_copy, module):
    f = pkg_copy / module
    before, text = _versions(pkg_copy), f.read_text()
    f.write_text(text + "\n# edited\n")
    try:
        after = _versions(pkg_copy)
    finally:
        f.write_text(text)
    changed = {k for k in KINDS if before[k] != after[k]}
    assert changed, f"editing {module} reruns nothing"
    if module.parts[0] == "plotting":
        assert changed == {"figures"}
    if module.parts[0] in ("core", "orbits", "data", "pipeline"):
        assert {"compute", "studies", "attractors", "models"} <= changed and "figures" not in changed
    if module.parts[0] == "attractors":       # the model ladder measures exact orbits with it
        assert changed == {"attractors", "models"}
    if module.parts[0] == "slowflow":
        assert changed == {"models"}


def test_cli_changes_no_code_version(pkg_copy):
    f = pkg_copy / "cli" / "common.py"
    before, text = _versions(pkg_copy), f.read_text()
    f.write_text(text + "\n# edited\n")
    try:
        assert _versions(pkg_copy) == before
    finally:
        f.write_text(text)


def test_every_subpackage_is_known():
    subs = {p.parent.name for p in PKG_DIR.glob("*/__init__.py")} - set(NOT_TRACKED)
    assert subs == set(STUDIES) | set(ATTRACTORS) | set(FIGURES) | set(MODELS)
    with pytest.raises(ValueError, match="no subpackage"):
        tracked_files(("nonexistent",))
    assert all(isinstance(p, Path) for p in tracked_files(COMPUTE))
