"""The chunked stages: a dataset gathered from chunk parts is bitwise the dataset of one job
computing every item, for two chunkings (and thread counts) of each stage."""
import numpy as np
import pytest

from vines.pipeline import stages
from vines.pipeline.parts import item_ranges, read_parts, write_part

MODEL = {"r": 0.65, "d": 0.011997966952746818}
SIM = {"t_end": 300.0, "t_transient": 150.0, "v_stick": 1e-6, "max_impacts": 10**6,
       "root_tol": 1e-13}
SWEEP = {"param": "eta", "values": {"start": 0.05, "stop": 0.3, "num": 2}, "outer": "omega",
         "outer_values": [0.9, 1.1], "fixed": {"F": 0.3077}, "directions": ["up", "down"],
         "t_settle": 200.0, "t_step": 100.0, "n_record": 3, "v_stick": 1e-6}

#: stage -> (its config entry and keywords, items, points per item)
CASES = {
    # coexisting attractors, states that change attractor between t_end and t_max
    "robust_map": (dict(spec={"eta": [0.1, 0.5], "omega": [0.8, 1.0], "F": 0.2, "n": 4,
                              "seed": 0, "threshold": 0.7, "t_max": 600.0},
                        model=MODEL, simulation=SIM), 4, 1),
    "basin_slice": (dict(spec={"eta": 0.1, "omega": 0.8, "F": 0.2,
                               "z_m0": [-1.5, -0.5, 0.5, 1.5], "v_m0": [-1.5, 0.0, 1.5],
                               "t_max": 600.0},
                         model=MODEL, simulation=SIM), 12, 1),
    "orbit_atlas": (dict(grid={"eta": [0.1, 0.3, 0.5], "omega": [0.8, 1.0], "F": 0.3077},
                         sim_t_end=0.0, model=MODEL), 3, 2),
    "lyapunov": (dict(spec={"sweep": "s", "t_window": 100.0, "n_batches": 2}, sweep=SWEEP,
                      model=MODEL),
                 4, 2),
    "design": (dict(spec={"omega_band": [0.9, 1.1], "n_omega": 3, "amplitudes_m": [0.003],
                          "eta_max": 0.1, "n_eta": 1, "n_clearance": 3, "census_n": 0,
                          "t_end": 200.0, "t_transient": 100.0},
                    model=MODEL, simulation=SIM), 3, 3),
    # the points of the pick-freeze blocks: 2 x (1 + 2) points, none repeated
    "uncertainty": (dict(spec={"design": {"omega_band": [0.9, 1.1], "n_omega": 3,
                                          "amplitudes_m": [0.003], "eta": 0.1,
                                          "clearance_m": 0.02, "t_end": 200.0,
                                          "t_transient": 100.0},
                               "parameters": {"r": ["uniform", 0.5, 0.8]}, "samples": 2,
                               "seed": 0},
                         model=MODEL, simulation=SIM), 6, 3),
    # the search grid (1 x 2 designs) on the nominal host and the robust search's 3 hosts
    "design_robust": (dict(spec={"omega_band": [0.9, 1.1], "n_omega": 3,
                                 "amplitudes_m": [0.003], "eta_max": 0.1, "n_eta": 1,
                                 "n_clearance": 2, "census_n": 0, "t_end": 200.0,
                                 "t_transient": 100.0, "mistuning": 0.1, "n_delta": 3,
                                 "n_search": 3},
                           model=MODEL, simulation=SIM), 6, 3),
    # cells of a design map, each checked by the exact solver (its sampled draw)
    "design_map": (dict(spec={"eta": [0.05], "half_width": [0.2], "span": [1.0, 4.0],
                              "restitution": [0.65], "n_amplitudes": 2, "n_omega": 21,
                              "n_clearance": 5, "n_omega_exact": 3, "exact_sample": 1.0,
                              "exact_refine": False, "t_end": 300.0, "t_transient": 150.0},
                        model=MODEL, simulation=SIM), 2, 1),
    "convergence": (dict(study="grid", spec={"F": 0.4, "resolutions": [2, 3]}, model=MODEL,
                         simulation=SIM), 3, 3),
}


def _gathered(stage, kw, ranges, n_workers, tmp_path):
    """The stage's dataset from one part per range, each through a part file."""
    part = getattr(stages, f"{stage}_part")
    args = (kw["study"],) if stage == "convergence" else ()
    rest = {k: v for k, v in kw.items() if k != "study"}
    paths = [write_part(part(*args, **rest, start=a, stop=b, n_workers=n_workers),
                        tmp_path / stage / f"chunk_{k}.pkl")
             for k, (a, b) in enumerate(ranges)]
    return getattr(stages, stage)(*args, **rest, code="t", title="t",
                                  n_workers=n_workers, parts=read_parts(paths))


def _same(a, b):
    assert set(a.variables) == set(b.variables)
    for name in a.variables:
        x, y = a[name].values, b[name].values
        assert x.dtype == y.dtype and x.shape == y.shape, name
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(f"u{x.itemsize}"), y.view(f"u{y.itemsize}")), name
        else:
            assert np.array_equal(x, y), name


@pytest.mark.parametrize("stage", sorted(CASES))
def test_parts_give_the_dataset_of_one_job(stage, tmp_path):
    kw, n_items, per_item = CASES[stage]
    args = (kw["study"],) if stage == "convergence" else ()
    rest = {k: v for k, v in kw.items() if k != "study"}
    whole = getattr(stages, stage)(*args, **rest, code="t", title="t", n_workers=1)
    one_per_item = item_ranges(n_items, per_item, per_item)
    assert len(one_per_item) == n_items >= 2         # every item a part of its own
    _same(whole, _gathered(stage, kw, one_per_item, 1, tmp_path / "a"))
    _same(whole, _gathered(stage, kw, item_ranges(n_items, per_item, 2 * per_item), 2,
                           tmp_path / "b"))


def test_item_ranges_cover_the_items_in_even_runs_of_whole_items():
    assert item_ranges(7, 1, 3) == [(0, 2), (2, 5), (5, 7)]
    assert item_ranges(103, 150, 3000) == [(0, 17), (17, 34), (34, 52), (52, 69), (69, 86),
                                           (86, 103)]
    assert item_ranges(3, 100, 10) == [(0, 1), (1, 2), (2, 3)]    # one item at least a run
    assert item_ranges(5, 1, 1000) == [(0, 5)]
    assert item_ranges(0, 1, 10) == []


def _config(**top):
    from vines.pipeline.config import load_schema, validate_config
    return validate_config({"run": "t", **top}, load_schema())


def test_chunks_section_threads_and_the_deprecated_chunk_size():
    from vines.pipeline.axes import ConfigError
    from vines.pipeline.config import move_chunk_size
    assert _config()["chunks"]["robust_map"] == 16 and _config()["threads"] == 2
    assert _config(threads="max")["threads"] == "max"
    old = {"chunk_size": 40}
    assert "chunks: {simulate_grid: 40}" in move_chunk_size(old)
    assert old == {"chunks": {"simulate_grid": 40}}
    assert _config(chunk_size=40)["chunks"]["simulate_grid"] == 40
    assert "chunk_size" not in _config(chunk_size=40)
    for bad, key in (({"chunks": {"robust_map": 0}}, "chunks.robust_map"),
                     ({"chunks": {"lyapunov": 2.0}}, "chunks.lyapunov"),
                     ({"chunks": {"atlas": 5}}, "chunks"),
                     ({"threads": "all"}, "threads"), ({"threads": 0}, "threads"),
                     ({"chunk_size": 0}, "chunk_size"),
                     ({"chunk_size": 8, "chunks": {"simulate_grid": 16}}, "chunk_size")):
        with pytest.raises(ConfigError, match=f"'{key}'"):
            _config(**bad)
