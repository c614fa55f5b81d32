"""Datasets: the one schema (CF ``long_name``/``units`` of every variable), one builder per
pipeline stage, NetCDF encoding with atomic writes, and provenance attributes. The only
place that builds xarray datasets."""
