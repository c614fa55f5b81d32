"""The built documentation site, opened as a reader opens it: headless Chromium (Debian's
``chromium``) loads the index, a gallery page and the search page from a local server.

Checks: a screenshot of the index that is not blank, every image of the index and of the
gallery page fetched by the browser (the server's log, status 200, a PNG), and a search
that lists results (Sphinx's search runs in JavaScript: the DOM is read after Chromium ran
it, ``--dump-dom`` after a virtual-time budget). Skipped when the site is not built
(docs/building.md) or Chromium is missing, unless ``VINES_REQUIRE_DOCS=1`` (CI): then
those are failures.
"""
from __future__ import annotations

import functools
import html.parser
import http.server
import os
import re
import shutil
import subprocess
import threading
from pathlib import Path
from urllib.parse import unquote, urljoin, urlsplit

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "_build" / "html"
GALLERY_PAGE = "auto_examples/plot_01_simulation.html"
SEARCH_WORD = "attractor"
BROWSERS = ("chromium", "chromium-browser", "google-chrome")
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run",
         "--window-size=1280,1000")


def _missing(what: str) -> None:
    if os.environ.get("VINES_REQUIRE_DOCS") == "1":
        pytest.fail(f"VINES_REQUIRE_DOCS=1 but {what}")
    pytest.skip(what)


@pytest.fixture(scope="module")
def browser() -> str:
    found = next((p for p in map(shutil.which, BROWSERS) if p), None)
    if found is None:
        _missing("no Chromium on PATH (Debian: apt-get install chromium)")
    if not (SITE / "index.html").is_file():
        _missing(f"the site is not built ({SITE.relative_to(ROOT)}; see docs/building.md)")
    return found


class _Handler(http.server.SimpleHTTPRequestHandler):
    """Serves the site; records (path, status) of every request, no log on stderr."""

    def log_request(self, code="-", size="-"):
        self.server.requests.append((unquote(urlsplit(self.path).path), int(code)))

    def log_message(self, *args):
        pass


@pytest.fixture(scope="module")
def server(browser):
    httpd = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), functools.partial(_Handler, directory=str(SITE)))
    httpd.requests = []
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield httpd
    httpd.shutdown()
    httpd.server_close()


def _url(httpd, page: str) -> str:
    return f"http://127.0.0.1:{httpd.server_address[1]}/{page}"


def _chromium(browser, tmp_path, url: str, *args: str) -> str:
    """Run Chromium on ``url`` with a fresh profile; its stdout."""
    profile = tmp_path / f"profile{len(list(tmp_path.glob('profile*')))}"
    cmd = [browser, *FLAGS, f"--user-data-dir={profile}", "--virtual-time-budget=10000",
           *args, url]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout


class _Images(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.sources = []

    def handle_starttag(self, tag, attrs):
        src = dict(attrs).get("src")
        if tag == "img" and src and not src.startswith("data:"):
            self.sources.append(src)


def _image_paths(page: str) -> list[str]:
    """URL paths of the <img> of a built page."""
    parser = _Images()
    parser.feed((SITE / page).read_text(encoding="utf-8"))
    return [urlsplit(urljoin(f"/{page}", src)).path for src in parser.sources]


def _assert_images_loaded(httpd, page: str) -> None:
    wanted = _image_paths(page)
    served = {path for path, code in httpd.requests if code == 200}
    assert wanted, f"{page} has no image"
    missing = [p for p in wanted if p not in served]
    assert not missing, f"{page}: images not fetched by the browser: {missing}"
    for path in wanted:
        assert (SITE / path.lstrip("/")).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path


def _assert_not_blank(png: Path) -> None:
    import matplotlib.image

    pixels = matplotlib.image.imread(png)[..., :3]
    assert pixels.shape[0] >= 500 and pixels.shape[1] >= 800, pixels.shape
    dark = (pixels.mean(axis=2) < 0.5).mean()          # text, headings, code
    assert 0.002 < dark < 0.5, f"{png.name}: {dark:.4f} of the pixels dark"
    assert pixels.std() > 0.05, f"{png.name}: a uniform picture"


def test_index_renders(browser, server, tmp_path):
    shot = tmp_path / "index.png"
    _chromium(browser, tmp_path, _url(server, "index.html"), f"--screenshot={shot}")
    _assert_not_blank(shot)
    served = {path for path, code in server.requests if code == 200}
    assert {"/index.html", "/_static/pygments.css"} <= served, sorted(served)
    assert any(p.endswith(".js") for p in served)           # the theme's scripts


def test_gallery_thumbnails_load(browser, server, tmp_path):
    server.requests.clear()
    shot = tmp_path / "gallery.png"
    _chromium(browser, tmp_path, _url(server, "auto_examples/index.html"),
              f"--screenshot={shot}")
    _assert_not_blank(shot)
    _assert_images_loaded(server, "auto_examples/index.html")


def test_gallery_page_renders_its_figure(browser, server, tmp_path):
    server.requests.clear()
    shot = tmp_path / "example.png"
    _chromium(browser, tmp_path, _url(server, GALLERY_PAGE), f"--screenshot={shot}")
    _assert_not_blank(shot)
    _assert_images_loaded(server, GALLERY_PAGE)
    dom = _chromium(browser, tmp_path, _url(server, GALLERY_PAGE), "--dump-dom")
    assert "One simulation and its time history" in dom
    assert "sphx-glr-single-img" in dom                    # the figure the example drew
    assert re.search(r"regime \S+, KE ratio [0-9.]+", dom)  # the example's printed output


def test_search_lists_results(browser, server, tmp_path):
    server.requests.clear()
    dom = _chromium(browser, tmp_path, _url(server, f"search.html?q={SEARCH_WORD}"),
                    "--dump-dom")
    found = re.search(r"Search finished, found (\d+) page", dom)
    assert found and int(found.group(1)) > 0, dom[-3000:]
    results = re.search(r'<ul[^>]*class="search"[^>]*>(.*?)</ul>', dom, re.S)
    assert results, dom[-3000:]
    links = re.findall(r'<li[^>]*>\s*<a href="([^"#]+)', results.group(1))
    assert len(links) == int(found.group(1)), links
    assert "attractors.html" in links                      # the page about them is found
    assert ("/searchindex.js", 200) in server.requests
