"""No config places an output, log or benchmark outside results/<run>/ (issue: a run named
'..' wrote into the repository root): every path of the planned DAG of the full and the
smoke config lies under results/<run>/, and unsafe names are refused before any job."""
import re
import subprocess
from pathlib import Path

import pytest
import yaml
from test_pipeline import ROOT, SNAKEMAKE, needs_snakemake

from vines.pipeline.axes import ConfigError
from vines.pipeline.config import load_schema, load_yaml, validate_config

PATH_LINE = re.compile(r"^\s+(output|log|benchmark): (.*)$", re.M)


def _planned_paths(configfile: Path, workdir: Path) -> list[str]:
    r = subprocess.run([SNAKEMAKE, "-n", "-c2", "all", "--workflow-profile", "none",
                        "--snakefile", str(ROOT / "Snakefile"), "--directory", str(workdir),
                        "--configfile", str(configfile)],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    paths = [p.strip() for _, group in PATH_LINE.findall(r.stdout) for p in group.split(",")]
    assert paths, "the dry run listed no job"
    return paths


@needs_snakemake
@pytest.mark.parametrize("name", ["smoke.yaml", "config.yaml"])
def test_every_planned_path_lies_under_results_run(tmp_path, name):
    configfile = ROOT / "config" / name
    run = yaml.safe_load(configfile.read_text())["run"]
    root = (tmp_path / "results" / run).resolve()
    for p in _planned_paths(configfile, tmp_path):
        assert (tmp_path / p).resolve().is_relative_to(root), p


def _smoke():
    return yaml.safe_load((ROOT / "config" / "smoke.yaml").read_text())


@pytest.mark.parametrize("run", ["..", ".", ".hidden", "a/b", "smoke\n", "a b", "x" * 65, ""])
def test_unsafe_run_names_are_refused(run):
    cfg = _smoke()
    cfg["run"] = run
    with pytest.raises(ConfigError, match="run"):
        validate_config(cfg, load_schema())


@pytest.mark.parametrize("name", ["..", ".", "a/b", "g\n", "x" * 250])
def test_unsafe_entry_names_are_refused(name):
    cfg = _smoke()
    grids = cfg["grids"]
    first = next(iter(grids))
    grids[name] = grids.pop(first)
    with pytest.raises(ConfigError, match="grids"):
        validate_config(cfg, load_schema())


def test_a_key_given_twice_is_refused(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text((ROOT / "config" / "smoke.yaml").read_text() + "\nrun: other\n")
    with pytest.raises(ConfigError, match="given twice"):
        load_yaml(path)
