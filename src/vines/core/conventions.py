"""Conventions shared by the numerics, the datasets and the figures: wall codes and the
names and dtypes of ``simulate_batch``'s fields. Numba-free, so that dataset and figure code
can use them without loading the compiled kernels (``core.walls`` re-exports the wall codes
next to the impact law)."""

WALL_L = 1      # w = z_m - z_b = +1
WALL_R = -1     # w = -1
WALL_NAMES = {WALL_L: "L", WALL_R: "R"}

#: fields of ``simulate_batch`` and their dtypes (CF attributes: ``vines.data.schema``)
BATCH_FIELDS = {
    "ke_ratio": "f8", "xmax": "f8", "xmax_whole_run": "f8", "n_impacts": "i8",
    "impacts_per_period": "f8", "t_stuck": "f8", "period": "i8", "regime": "U16",
    "status": "U16", "shortcut_time": "f8",
}
