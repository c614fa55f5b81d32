"""Names and dtypes of the per-point measures of ``simulate_batch`` (numba-free, so that
dataset and figure code can name them without loading the compiled kernels)."""

#: fields of ``simulate_batch`` and their dtypes (CF attributes: ``vines.data.schema``)
BATCH_FIELDS = {
    "ke_ratio": "f8", "xmax": "f8", "xmax_whole_run": "f8", "n_impacts": "i8",
    "impacts_per_period": "f8", "t_stuck": "f8", "period": "i8", "regime": "U16",
    "status": "U16", "shortcut_time": "f8",
}
