"""Figure, dataset and Snakefile parse-time code must not load numba (each Snakemake job is
a new process that would pay for it), while the public API still loads it on first use."""
import subprocess
import sys

import pytest

NUMBA_FREE = ["vines", "vines.plotting", "vines.data.builders", "vines.data.netcdf",
              "vines.pipeline.config", "vines.pipeline.axes",
              "vines.pipeline.codeversion", "vines.pipeline.stages", "vines.pipeline.jobs",
              "vines.studies.design_checks", "vines.studies.shock", "vines.cli.shock",
              "vines.slowflow", "vines.cli.slowflow"]


def _loaded_after(code: str) -> set[str]:
    out = subprocess.run([sys.executable, "-c", code + "\nimport sys\nprint(' '.join(sys.modules))"],
                         check=True, capture_output=True, text=True).stdout
    return set(out.split())


@pytest.mark.parametrize("module", NUMBA_FREE)
def test_module_does_not_load_numba(module):
    assert "numba" not in _loaded_after(f"import {module}")


def test_public_api_loads_on_first_use():
    mods = _loaded_after("import vines\nvines.simulate\nfrom vines import SimulationResult")
    assert {"numba", "vines.core.simulation", "vines.core.result"} <= mods


def test_unknown_attribute_is_an_attribute_error():
    import vines
    with pytest.raises(AttributeError, match="no attribute 'simulat'"):
        vines.simulat  # noqa: B018
