"""The layout of ``vines.orbits`` (issue: one family, one engine): no import circle (imports
inside functions included), no private name imported from another module, and one place
that tells the 1:1 family apart (``Family.one_to_one``). Read from the sources (ast), no
numba."""
import ast
import re
from pathlib import Path

import vines

SRC = Path(vines.__file__).resolve().parent
ORBITS = SRC / "orbits"


def _module(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path):
    """(module imported, name) of every ``from ... import name`` in the file, at any depth."""
    pkg = _module(path) if path.name == "__init__.py" else _module(path).rsplit(".", 1)[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = pkg.split(".")
            if node.level:
                base = base[:len(base) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            for a in node.names:
                yield mod, a.name


def _graph() -> dict:
    files = {_module(f): f for f in ORBITS.rglob("*.py")}
    graph = {}
    for name, f in files.items():
        deps = set()
        for mod, item in _imports(f):
            full = f"{mod}.{item}"
            target = full if full in files else mod
            if target in files and target != name and files[target].name != "__init__.py":
                deps.add(target)
        graph[name] = deps
    return graph


def test_no_import_circle_in_orbits():
    graph = _graph()
    seen, stack, cycles = set(), [], []

    def visit(v):
        if v in stack:
            cycles.append(stack[stack.index(v):] + [v])
            return
        if v in seen:
            return
        seen.add(v)
        stack.append(v)
        for w in sorted(graph[v]):
            visit(w)
        stack.pop()

    for v in sorted(graph):
        visit(v)
    assert not cycles, cycles


def test_no_private_name_imported_across_orbit_modules():
    bad = [(str(f.relative_to(SRC)), mod, name) for f in ORBITS.rglob("*.py")
           for mod, name in _imports(f)
           if mod.startswith("vines.orbits") and name.startswith("_")
           and mod != _module(f)]
    assert not bad, bad


def test_one_place_tells_the_one_to_one_family_apart():
    pattern = re.compile(r"""\(\s*["']LR["']\s*,\s*1\s*\)""")
    roots = [SRC, SRC.parent.parent / "workflow"]
    hits = [str(f) for root in roots if root.is_dir()
            for f in list(root.rglob("*.py")) + list(root.rglob("*.smk"))
            if pattern.search(f.read_text()) and f != ORBITS / "family" / "family.py"]
    assert not hits, hits


def test_only_the_family_asks_one_to_one():
    """Callers dispatch on ``Family.engine``; ``Family.one_to_one`` is read in family.py
    alone (attribute reads in the sources; the .smk files by their text)."""
    own = ORBITS / "family" / "family.py"
    hits = [str(f) for f in SRC.rglob("*.py") if f != own
            for node in ast.walk(ast.parse(f.read_text()))
            if isinstance(node, ast.Attribute) and node.attr == "one_to_one"]
    workflow = SRC.parent.parent / "workflow"
    if workflow.is_dir():
        hits += [str(f) for f in workflow.rglob("*.smk") if ").one_to_one" in f.read_text()]
    assert not hits, hits
