"""Release metadata: one version, citable, the environment file follows the lock, the
config schema ships inside the package."""
import importlib.metadata
import subprocess
import sys
import tomllib
from importlib.resources import files
from pathlib import Path

import yaml

import vines

ROOT = Path(__file__).resolve().parents[1]


def test_one_version_in_pyproject_package_and_citation():
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    cited = yaml.safe_load((ROOT / "CITATION.cff").read_text())["version"]
    assert importlib.metadata.version("vines") == vines.__version__ == declared == cited


def test_citation_names_the_license_and_the_reproduced_study():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert cff["cff-version"] == "1.2.0"
    assert cff["license"] == "BSD-3-Clause"
    assert "BSD 3-Clause" in (ROOT / "LICENSE").read_text()
    assert any("vibro-impact nonlinear energy sink" in r["title"] for r in cff["references"])


def test_changelog_has_an_entry_for_the_version():
    text = (ROOT / "CHANGELOG.md").read_text()
    assert f"## [{vines.__version__}]" in text or "## [Unreleased]" in text


def test_environment_file_follows_the_lock():
    run = subprocess.run([sys.executable, str(ROOT / "requirements" / "make_environment.py"),
                          "--check"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def test_config_schema_is_package_data():
    schema = files("vines.pipeline").joinpath("config.schema.yaml")
    assert schema.is_file()
    pkg_data = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert "config.schema.yaml" in pkg_data["package-data"]["vines.pipeline"]
    assert not (ROOT / "workflow" / "schemas" / "config.schema.yaml").exists()  # one copy
