"""The layout of ``vines.orbits`` (issue: one family, one engine): no import circle (imports
inside functions included), no private name imported from another module, and one place
that tells the 1:1 family apart (``Family.engine``). Read from the sources (ast), no
numba."""
import ast
import re
from pathlib import Path

from test_import_graph import circles_within, private_imports

import vines

SRC = Path(vines.__file__).resolve().parent
ORBITS = SRC / "orbits"


def test_no_import_circle_in_orbits():
    assert circles_within("vines.orbits") == []


def test_no_private_name_imported_across_orbit_modules():
    assert private_imports("vines.orbits") == []


def test_one_place_tells_the_one_to_one_family_apart():
    pattern = re.compile(r"""\(\s*["']LR["']\s*,\s*1\s*\)""")
    roots = [SRC, SRC.parent.parent / "workflow"]
    hits = [str(f) for root in roots if root.is_dir()
            for f in list(root.rglob("*.py")) + list(root.rglob("*.smk"))
            if pattern.search(f.read_text()) and f != ORBITS / "family" / "family.py"]
    assert not hits, hits


def test_only_the_family_asks_one_to_one():
    """Callers ask ``Family.engine``; no module outside family.py reads an attribute
    ``one_to_one`` (attribute reads in the sources; the .smk files by their text)."""
    own = ORBITS / "family" / "family.py"
    hits = [str(f) for f in SRC.rglob("*.py") if f != own
            for node in ast.walk(ast.parse(f.read_text()))
            if isinstance(node, ast.Attribute) and node.attr == "one_to_one"]
    workflow = SRC.parent.parent / "workflow"
    if workflow.is_dir():
        hits += [str(f) for f in workflow.rglob("*.smk") if ").one_to_one" in f.read_text()]
    assert not hits, hits
