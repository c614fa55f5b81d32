"""Every caption of `snakemake --report` (workflow/report/*.rst) renders without a
reStructuredText error or warning for both shipped configs, as Snakemake renders it: Jinja
(``trim_blocks``, ``lstrip_blocks``) with ``snakemake.config``, then docutils. An error
there shows as a red box in the report and an ``(ERROR/3)`` line in its log (a bare
``|delta|`` was a substitution reference). CI also builds the smoke run's report and fails
on ERROR in its output (.ci/run).
"""
import io
from pathlib import Path
from types import SimpleNamespace

import pytest

from vines.pipeline.config import load_schema, load_yaml, validate_config

jinja2 = pytest.importorskip("jinja2")
docutils_core = pytest.importorskip("docutils.core")

ROOT = Path(__file__).resolve().parents[1]
CAPTIONS = sorted((ROOT / "workflow" / "report").glob("*.rst"))
CONFIGS = ("config.yaml", "smoke.yaml")


@pytest.fixture(scope="module", params=CONFIGS)
def config(request):
    return validate_config(load_yaml(ROOT / "config" / request.param), load_schema())


def _messages(rst: str) -> str:
    """docutils' system messages (level >= WARNING) for ``rst``, one per line."""
    stream = io.StringIO()
    docutils_core.publish_parts(rst, writer="html", settings_overrides={
        "warning_stream": stream, "report_level": 2, "halt_level": 5})
    return stream.getvalue()


def test_there_are_captions():
    assert len(CAPTIONS) >= 20


@pytest.mark.parametrize("caption", CAPTIONS, ids=lambda p: p.stem)
def test_caption_renders_without_error(caption, config):
    env = jinja2.Environment(trim_blocks=True, lstrip_blocks=True)
    text = env.from_string(caption.read_text()).render(
        snakemake=SimpleNamespace(config=config), categories={}, files={})
    assert text.strip()
    assert _messages(text) == "", caption.name


def test_a_bare_bar_pair_is_caught():
    assert "Undefined substitution" in _messages("worst case over |delta| <= 0.1")
    assert _messages(r"worst case over \|delta\| <= 0.1") == ""
