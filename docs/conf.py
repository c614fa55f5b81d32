"""Sphinx configuration of the vines site (docs/building.md says how to build it).

The pages are the Markdown files of docs/ (MyST), the API reference is generated from the
docstrings (autosummary + napoleon), the gallery from examples/ (sphinx-gallery, executed at
build time). intersphinx to numpy, scipy and xarray needs the network, so it is on only with
VINES_DOCS_INTERSPHINX=1: the default build (and CI's, warnings as errors) reads nothing from
outside.
"""
import ast
import importlib.util
import inspect
import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))   # the vines of this checkout, installed or not
sys.path.insert(0, str(ROOT / "docs"))   # the local extension _vines_links

import vines  # noqa: E402

project = "vines"
author = "vines developers"
copyright = "vines developers, BSD-3-Clause"
release = vines.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "_vines_links",
]
if os.environ.get("VINES_DOCS_INTERSPHINX") == "1":
    extensions.append("sphinx.ext.intersphinx")
    intersphinx_mapping = {
        "python": ("https://docs.python.org/3", None),
        "numpy": ("https://numpy.org/doc/stable", None),
        "scipy": ("https://docs.scipy.org/doc/scipy", None),
        "xarray": ("https://docs.xarray.dev/en/stable", None),
    }

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
# the two scripts of docs/ are tools, not pages; _build and the generated folders likewise
exclude_patterns = ["_build", "figure_numbers.py", "make_cli_reference.py",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip"]

# MyST: the existing pages as they are (GitHub-flavoured Markdown, $...$ maths)
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 4          # [text](page.md#a-heading) links as on GitHub

# API reference: autosummary writes one page per public name (docs/api.rst lists them)
autosummary_generate = True
templates_path = ["_templates"]
autosummary_imported_members = True
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "signature"   # the annotations in the signature; docstrings give units
autodoc_member_order = "bysource"
napoleon_numpy_docstring = True
napoleon_google_docstring = False

# gallery: every examples/*.py run at build time, its figures drawn into the page
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "abort_on_example_error": True,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "pydata_sphinx_theme"
html_title = f"vines {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_show_sourcelink = False
html_last_updated_fmt = None


# The docstrings are plain text in which |x| is an absolute value, never a reStructuredText
# substitution: bars are escaped outside inline literals and literal blocks.
_INLINE_LITERAL = re.compile(r"(``.*?``)")


def _escape_bars(app, what, name, obj, options, lines) -> None:
    literal_indent = None                # indentation of the line that opened a literal block
    for i, line in enumerate(lines):
        text = line.lstrip()
        indent = len(line) - len(text)
        if literal_indent is not None:
            if not text or indent > literal_indent:
                continue
            literal_indent = None
        parts = _INLINE_LITERAL.split(line)
        lines[i] = "".join(p if p.startswith("``") else p.replace("|", r"\|") for p in parts)
        if text.endswith("::"):
            literal_indent = indent


def _doc_comment(module: str, attr: str, depth: int = 0) -> list[str]:
    """The ``#:`` comment of ``attr`` in ``module``, or in the module it imports it from."""
    from sphinx.pycode import ModuleAnalyzer
    try:
        analyzer = ModuleAnalyzer.for_module(module)
    except Exception:                     # no source (a compiled or built-in module)
        return []
    doc = analyzer.find_attr_docs().get(("", attr))
    if doc or depth > 3:
        return list(doc or [])
    loaded = importlib.import_module(module)
    package = module if hasattr(loaded, "__path__") else module.rpartition(".")[0]
    lazy = getattr(loaded, "_LAZY", {})       # names a package loads on first access
    if attr in lazy:
        return _doc_comment(importlib.util.resolve_name(lazy[attr], package), attr, depth + 1)
    for node in ast.walk(ast.parse(analyzer.code)):
        if isinstance(node, ast.ImportFrom) and any(a.name == attr for a in node.names):
            source = importlib.util.resolve_name("." * node.level + (node.module or ""),
                                                 package) if node.level else node.module
            return _doc_comment(source, attr, depth + 1)
    return []


def _constant_doc(app, what, name, obj, options, lines) -> None:
    """A constant is described by its ``#:`` comment, not by the docstring of its type
    (``float``, ``tuple``): found where the package imports it from."""
    if what not in ("data", "attribute"):
        return
    inherited = {(inspect.getdoc(t) or "").strip() for t in type(obj).__mro__}
    if "\n".join(lines).strip() in inherited:
        module, _, attr = name.rpartition(".")
        lines[:] = _doc_comment(module, attr)


def setup(app):
    app.connect("autodoc-process-docstring", _constant_doc, priority=400)
    app.connect("autodoc-process-docstring", _escape_bars)
