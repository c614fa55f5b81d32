"""Running a figure script outside Snakemake: a stand-in ``snakemake`` object."""
from __future__ import annotations

import runpy
from pathlib import Path
from types import SimpleNamespace

SCRIPTS = Path(__file__).resolve().parents[1] / "workflow" / "scripts" / "figures"


def run_figure(script: str, tmp_path: Path, name: str, colormap: str | None = "viridis",
               **inputs) -> tuple[Path, str]:
    """Run workflow/scripts/figures/<script>.py on ``inputs`` (lists of dataset paths by
    input name); (the PNG written, the text of the job's log)."""
    out = tmp_path / "figures"
    params = SimpleNamespace() if colormap is None else SimpleNamespace(colormap=colormap)
    log = tmp_path / "logs" / f"{name}.log"
    sm = SimpleNamespace(input=SimpleNamespace(**inputs), rule=f"fig_{name}", wildcards={},
                         params=params, output=SimpleNamespace(pdf=str(out / f"{name}.pdf"),
                                                              png=str(out / f"{name}.png")),
                         log=[str(log)])
    runpy.run_path(str(SCRIPTS / f"{script}.py"), init_globals={"snakemake": sm})
    return out / f"{name}.png", log.read_text()
