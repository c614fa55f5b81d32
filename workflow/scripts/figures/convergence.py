"""Convergence figure: (a, b) KE ratio and x_max against run length at the named points
(difference to the longest run's widest window; solid: window of fixed length, dashed:
window a fraction of the run), (c) the same against the sticking threshold v_stick at chatter
points (difference to the smallest v_stick), (d) the cost of those runs, (e) distance of the
KE-ratio contour to the finest grid's against grid resolution, (f) the contours themselves.

Inputs (datasets of ``vines.studies.convergence``): ``snakemake.input.window``, ``.vstick``,
``.grid``; outputs ``snakemake.output.pdf`` / ``.png``; log ``snakemake.log[0]``.
"""
import vines.plotting as P
from vines.pipeline.jobs import run_job
from vines.plotting import studies


def main(sm):
    P.configure(sm)
    w = P.require(P.load(sm.input.window), coords=("t_end",),
                  variables=("window_rule", "window_length", "window_fraction",
                             "regime_same", "t_transient", "reference_t_transient"),
                  finite=("d_ke", "rel_d_xmax"))
    v = P.require(P.load(sm.input.vstick), coords=("v_stick",), min_size=2,
                  finite=("d_ke", "rel_d_xmax", "run_time"))
    g = P.require(P.load(sm.input.grid), coords=("eta", "omega", "resolution"), min_size=2,
                  variables=("stride", "contour_dist_mean", "contour_dist_max",
                             "contour_hausdorff", "d_area_fraction"),
                  finite=("ke_ratio",))
    for key in ("level", "F"):
        if key not in g.attrs:
            raise P.FigureInputError(f"{sm.input.grid}: global attribute {key!r} is missing")
    if "solver_t_end" not in v.attrs:
        raise P.FigureInputError(f"{sm.input.vstick}: global attribute 'solver_t_end' is "
                                 f"missing")
    P.save(studies.convergence_figure(w, v, g), sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
