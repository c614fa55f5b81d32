"""The model and its exact simulation: parameters and validation, closed-form flow, walls and
impact law, the compiled event-driven kernel and its driver, ``simulate`` /
``simulate_batch``, regimes, bifurcation sweeps, the stuck linear system and the measures
derived from raw runs. Numbers only: no datasets, no files."""
