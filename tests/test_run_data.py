"""A run's datasets as data: ``vines.open_run`` (one DataTree of a finished run) and the
header/size check that finds damaged datasets at every parse of the workflow.

The open_run test reads the smoke run's datasets (results/smoke, made by
`snakemake -c2 --configfile config/smoke.yaml`, or the directory named by VINES_SMOKE) and
is skipped without them; the damage check runs on files written here.
"""
import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import vines
from vines.data.netcdf import dataset_damage, read_dataset, unreadable_datasets, write_dataset

ROOT = Path(__file__).resolve().parents[1]
SMOKE = Path(os.environ.get("VINES_SMOKE", ROOT / "results" / "smoke"))


def _small_dataset():
    x = np.linspace(0.0, 1.0, 2000)
    return xr.Dataset({"y": ("x", np.sin(x), {"long_name": "sine of x", "units": "1"})},
                      coords={"x": ("x", x, {"long_name": "x", "units": "1"})})


# ------------------------------------------------------------------ damaged datasets

def test_damage_check_finds_truncated_empty_and_foreign_files(tmp_path):
    good = write_dataset(_small_dataset(), tmp_path / "good.nc")
    data = good.read_bytes()
    cases = {"half.nc": data[: len(data) // 2], "one_byte_short.nc": data[:-1],
             "header_only.nc": data[:40], "empty.nc": b"", "text.nc": b"not netcdf\n" * 100}
    for name, content in cases.items():
        (tmp_path / name).write_bytes(content)
        with pytest.raises(OSError):      # the full read agrees that each is unreadable
            read_dataset(tmp_path / name)
    assert dataset_damage(good) is None
    assert dataset_damage(tmp_path / "half.nc") == f"truncated: {len(data) // 2} of {len(data)} bytes"
    assert dataset_damage(tmp_path / "empty.nc") == "empty file"
    assert "not a NetCDF file" in dataset_damage(tmp_path / "text.nc")
    paths = [good, tmp_path / "missing.nc"] + [tmp_path / n for n in sorted(cases)]
    bad = dict(unreadable_datasets(paths))
    assert sorted(bad) == sorted(str(tmp_path / n) for n in cases)   # missing: not damaged
    assert all(r.startswith("(") and r.endswith(")") for r in bad.values())


def test_damage_check_accepts_a_user_block_and_classic_netcdf(tmp_path):
    data = write_dataset(_small_dataset(), tmp_path / "a.nc").read_bytes()
    # HDF5 addresses are relative to the base address: a 512-byte user block in front keeps
    # the superblock's end-of-file address, moves the base
    shifted = bytearray(512) + bytearray(data)
    version = shifted[512 + 8]
    assert version in (2, 3)
    shifted[512 + 12:512 + 20] = (512).to_bytes(8, "little")        # base address
    (tmp_path / "ub.nc").write_bytes(bytes(shifted))
    assert dataset_damage(tmp_path / "ub.nc") is None
    (tmp_path / "ub_cut.nc").write_bytes(bytes(shifted[:-10]))
    assert dataset_damage(tmp_path / "ub_cut.nc").startswith("truncated")
    _small_dataset().to_netcdf(tmp_path / "classic.nc", format="NETCDF3_CLASSIC")
    assert dataset_damage(tmp_path / "classic.nc") is None


# ------------------------------------------------------------------ open_run

@pytest.mark.skipif(not (SMOKE / "extract_measures").is_dir(), reason="no smoke datasets")
def test_open_run_holds_every_dataset_of_the_smoke_run_lazily():
    files = sorted(p for p in SMOKE.rglob("*.nc") if not p.name.startswith("."))
    with vines.open_run(SMOKE) as run:
        groups = {node.path.lstrip("/") for node in run.subtree if node.has_data}
        assert groups == {p.relative_to(SMOKE).with_suffix("").as_posix() for p in files}
        assert set(run.children) == {p.relative_to(SMOKE).parts[0] for p in files}
        # nothing read before use
        name = next(g for g in sorted(groups) if g.startswith("extract_measures/"))
        data_vars = run[name].data_vars
        assert data_vars and not any(v.variable._in_memory for v in data_vars.values())
        for p in files[:: max(1, len(files) // 8)]:   # values and attrs as in the file
            node = run[p.relative_to(SMOKE).with_suffix("").as_posix()]
            xr.testing.assert_identical(node.to_dataset(inherit=False).load(),
                                        read_dataset(p))


def test_open_run_names_a_missing_or_empty_directory(tmp_path):
    with pytest.raises(FileNotFoundError, match="no-such-run"):
        vines.open_run(tmp_path / "no-such-run")
    with pytest.raises(ValueError, match="no dataset"):
        vines.open_run(tmp_path)


def _fake_run(root):
    """Two stages: 'alpha' with 6 datasets, 'beta' with one grid of 2 chunks."""
    for k in range(6):
        write_dataset(_small_dataset(), root / "alpha" / f"d{k}.nc")
    for k in range(2):
        write_dataset(_small_dataset().rename({"y": "chunk_var"}),
                      root / "beta" / "g1" / f"chunk_{k}.nc")
    return {s: sum(f.stat().st_size for f in (root / s).rglob("*.nc")) for s in ("alpha", "beta")}


def test_a_runs_repr_is_a_summary_with_the_full_tree_one_call_away(tmp_path):
    sizes = _fake_run(tmp_path / "myrun")
    with vines.open_run(tmp_path / "myrun") as run:
        text = repr(run)
        assert str(run) == text
        lines = text.splitlines()
        assert len(lines) == 4                           # the run, 2 stages, the hint
        total = sum(sizes.values()) / 1e3
        assert lines[0] == f"vines run 'myrun': 2 stages, 8 datasets, {total:.1f} kB on disk " \
                           "(read lazily)"
        assert lines[1].split()[:3] == ["alpha", "6", "datasets"]
        assert f"{sizes['alpha'] / 1e3:.1f} kB" in lines[1]
        assert lines[1].endswith("d0, d1, d2, d3, ... (+2)")
        assert lines[2].split()[:3] == ["beta", "2", "datasets"] and lines[2].endswith("g1")
        assert "run.full_repr()" in lines[3]
        assert "chunk_var" not in text and "sine of x" not in text
        full = run.full_repr()                           # xarray's tree: every variable
        assert full.startswith("<xarray.DataTree>") and "chunk_var" in full
        assert full.count("Group: /alpha/d") == 6
        # a stage or a dataset keeps xarray's repr
        assert repr(run["alpha/d1"]).startswith("<xarray.DataTree 'd1'>")
        assert "y " in repr(run["alpha/d1"])


def test_readme_opens_the_run_of_its_quick_start():
    # the README's first open_run line opens the run its first pipeline command made (a
    # reader who ran only the quick start has no smoke run)
    text = (ROOT / "README.md").read_text()
    first = text.index("vines.open_run(")
    command = next(ln for ln in text[:first].splitlines() if "snakemake -c2" in ln)
    made = "results/smoke" if "smoke.yaml" in command else "results/paper"
    assert text[first:].split('"')[1] == made
