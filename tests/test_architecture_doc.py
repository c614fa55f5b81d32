"""docs/architecture.md names every module of src/vines (so that it stays the map of the
package): a module ``vines.sub.mod`` is named when the page writes it qualified
(`` `sub.mod` ``, `` `vines.sub.mod` ``, or followed by an attribute: `` `sub.mod.f` ``), or
bare (`` `mod` ``) in a table row or paragraph about its subpackage (one that writes
`` `vines.sub` ``); a top-level module ``vines.mod`` when the page writes `` `vines.mod` ``
(or `` `mod` ``). Nested subpackages (``vines.sub.pkg.mod``) count like modules: their
name relative to any enclosing package, qualified or bare in their top subpackage's blocks.
Text only: no module is imported."""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "src" / "vines"
DOC = (ROOT / "docs" / "architecture.md").read_text()


def _modules() -> list[tuple[str, ...]]:
    """Every module and subpackage of vines as a tuple of names (``__init__`` files give
    their package; the package itself excluded)."""
    out = []
    for f in sorted(PKG.rglob("*.py")):
        parts = f.relative_to(PKG).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        if parts:
            out.append(parts)
    return sorted(set(out))


def _blocks() -> list[str]:
    """Table rows and paragraphs of the page."""
    blocks = []
    for para in re.split(r"\n\s*\n", DOC):
        lines = para.splitlines()
        rows = [ln for ln in lines if ln.lstrip().startswith("|")]
        blocks += rows
        rest = "\n".join(ln for ln in lines if not ln.lstrip().startswith("|"))
        if rest.strip():
            blocks.append(rest)
    return blocks


def _written(name: str, text: str) -> bool:
    """``name`` appears in backticks, alone or followed by an attribute or a call."""
    return re.search(r"`(vines\.)?" + re.escape(name) + r"([`.(\[]|\s*->)", text) is not None


def named(parts: tuple[str, ...]) -> bool:
    top = parts[0]
    if len(parts) == 1:
        return _written(top, DOC)
    # qualified by its top subpackage or by any enclosing package
    if any(_written(".".join(parts[k:]), DOC) for k in range(len(parts) - 1)):
        return True
    mine = [b for b in _blocks() if f"`vines.{top}`" in b or f"`vines.{top}." in b]
    return any(_written(parts[-1], b) or _written(".".join(parts[1:]), b) for b in mine)


MODULES = _modules()


def test_the_package_has_modules():
    assert len(MODULES) > 50 and ("core", "params") in MODULES


@pytest.mark.parametrize("parts", MODULES, ids=".".join)
def test_architecture_names_the_module(parts):
    assert named(parts), (f"docs/architecture.md does not name vines.{'.'.join(parts)}: "
                          "add it to its subpackage's entry")


def test_a_missing_module_is_found():
    """The check can fail: a made-up module is not named."""
    assert not named(("orbits", "no_such_module"))
    assert not named(("no_such_module",))
