"""Links from the pages to Markdown files outside docs/ (config/README.md, ...) lead to the
site's pages that include those files (``REPOSITORY_PAGES``), so that the pages read the same
on the repository and on the site."""
from pathlib import Path

from sphinx.addnodes import pending_xref

#: repository file (from the root, no suffix) -> the page of the site that includes it
REPOSITORY_PAGES = {
    "config/README": "config-keys",
    "benchmarks/README": "benchmarks",
    "tests/slurm/README": "slurm-test",
}


def _redirect(app, doctree) -> None:
    root = Path(app.srcdir).resolve().parent
    for node in doctree.findall(pending_xref):
        if node.get("reftype") != "myst" or node.get("refdomain") != "doc":
            continue
        target = Path(app.srcdir, node["reftarget"]).resolve()
        try:
            key = target.relative_to(root).as_posix()
        except ValueError:
            continue
        if key in REPOSITORY_PAGES:
            node["reftarget"] = REPOSITORY_PAGES[key]


def setup(app):
    app.connect("doctree-read", _redirect)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
