"""The import graph of src/vines has no circles, imports inside functions included: a module
never needs, directly or through others, a module that needs it (issue 38). Read from the
source with ``ast``; nothing is imported."""
import ast

from conftest import SRC


def _modules():
    """Dotted name -> (path, is a package) of every module under src/vines."""
    mods = {}
    for path in (SRC / "vines").rglob("*.py"):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        mods[".".join(parts[:-1] if is_pkg else parts)] = (path, is_pkg)
    return mods


def _targets(node, module, is_pkg, mods):
    """The vines modules one import statement names (a name imported from a package that is
    a submodule counts as that submodule)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names if a.name.split(".")[0] == "vines"]
    base = module.split(".") if is_pkg else module.split(".")[:-1]
    if node.level:
        base = base[: len(base) - node.level + 1]
    target = ".".join(base + [node.module]) if node.level and node.module else (
        ".".join(base) if node.level else node.module or "")
    if target.split(".")[0] != "vines":
        return []
    return [f"{target}.{a.name}" if f"{target}.{a.name}" in mods else target
            for a in node.names]


def _graph():
    mods = _modules()
    graph = {}
    for module, (path, is_pkg) in mods.items():
        edges = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                for target in _targets(node, module, is_pkg, mods):
                    while target not in mods and "." in target:
                        target = target.rsplit(".", 1)[0]
                    if target in mods and target != module:
                        edges.add(target)
        graph[module] = edges
    return graph


def _circles(graph):
    """The strongly connected components of more than one module (iterative Tarjan)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        top = stack.pop()
                        on_stack.discard(top)
                        comp.append(top)
                        if top == node:
                            break
                    if len(comp) > 1:
                        found.append(sorted(comp))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(sorted(graph[child]))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
    return found


def test_the_checker_finds_a_circle():
    assert _circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _circles({"a": {"b"}, "b": set()}) == []


def test_relative_imports_resolve_to_modules():
    flow = _graph()["vines.core.flow"]      # from .._jit import njit; from .params import ...
    assert {"vines._jit", "vines.core.params"} <= flow


def test_no_import_circles_in_vines():
    assert _circles(_graph()) == []


def circles_within(package: str) -> list:
    """The import circles among the modules of ``package`` (e.g. ``"vines.orbits"``)."""
    inside = {m: e for m, e in _graph().items() if m.startswith(package)}
    return _circles({m: {t for t in e if t in inside} for m, e in inside.items()})


def private_imports(package: str = "vines") -> list:
    """``"module: name"`` for every private name (``_name``) a module of ``package``
    imports from another module: ``from .x import _name``."""
    mods = _modules()
    private = []
    for module, (path, is_pkg) in mods.items():
        if not module.startswith(package):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and _targets(node, module, is_pkg, mods):
                private += [f"{module}: {a.name}" for a in node.names
                            if a.name.startswith("_") and not a.name.startswith("__")
                            and not any(t.endswith(f".{a.name}") for t in
                                        _targets(node, module, is_pkg, mods))]
    return private


def test_no_private_names_imported_across_modules():
    """A module's private names (``_name``) stay its own: no ``from .x import _name``."""
    assert private_imports() == []
