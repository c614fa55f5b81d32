"""The Snakemake pipeline's Python side (importable and tested without Snakemake): config
validation, axes and chunking, code versions of the rules, execution on dask, job logging,
and the stage functions the workflow scripts call."""
