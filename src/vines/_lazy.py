"""Package attributes loaded on first access (PEP 562 module ``__getattr__``), so that
importing a package does not load the modules behind its public names (numba, scipy)."""
from __future__ import annotations

import sys
from collections.abc import Callable
from importlib import import_module


def lazy_attributes(package: str, modules: dict[str, str],
                    computed: dict[str, Callable[[], object]] | None = None):
    """(``__getattr__``, ``__dir__``) for ``package``: a name of ``modules`` is imported from
    its module (relative to the package) on first access, a name of ``computed`` is what its
    function returns; either is then kept in the package's namespace."""
    computed = computed or {}

    def __getattr__(name: str):
        if name in computed:
            value = computed[name]()
        elif name in modules:
            value = getattr(import_module(modules[name], package), name)
        else:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(modules) | set(computed))

    return __getattr__, __dir__
