"""Fig 3 with its leading Lyapunov exponent (beyond the paper): the bifurcation diagrams of
w'_i vs eta at W = 1 (sweep fig3, both directions) and, under each, lambda_1 of every sweep
point over the last t_window of its run (lyapunov dataset fig3), up and down sweeps apart,
with the 95 % batch-means intervals."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job

DIRECTIONS = {1: ("up", P.palette.C_TOWARDS, "o"), -1: ("down", P.palette.C_SAME_WAY, "s")}


def _lyapunov(path):
    ds = P.load(path)
    P.require(ds, variables=("value", "outer_value", "direction", "lambda_1", "exponents_ci"),
              finite=("value", "outer_value"))
    return ds


def _exponent_panel(ax, ly, outer):
    at = np.isclose(ly["outer_value"].values, outer, rtol=0, atol=1e-9)
    if not at.any():
        raise P.FigureInputError(f"{ly.attrs['_path']}: no exponents at outer value {outer}")
    for code, (label, colour, marker) in DIRECTIONS.items():
        sel = at & (ly["direction"].values == code)
        x, lam = ly["value"].values[sel], ly["lambda_1"].values[sel]
        ci = ly["exponents_ci"].values[sel, 0, :]
        err = np.abs(np.vstack([lam - ci[:, 0], ci[:, 1] - lam]))
        ax.errorbar(x, lam, yerr=err, fmt=marker, ms=2.5, lw=0.6, color=colour,
                    mfc="none" if code < 0 else colour, label=f"sweep {label}")
    ax.axhline(0, color="0.4", lw=0.6)
    ax.set_xlabel(P.LABELS["eta"])
    ax.set_ylabel(r"$\lambda_1$ (per unit time)")


def main(sm):
    P.configure(sm)
    sw = P.sweep(sm.input.sweep[0])
    ly = _lyapunov(sm.input.lyapunov[0])
    if sw.attrs.get("swept_parameter") != "eta":
        raise P.FigureInputError(f"{sm.input.sweep[0]}: Fig 3 sweeps eta, the dataset "
                                 f"sweeps {sw.attrs.get('swept_parameter')!r}")
    outer_name = sw.attrs.get("outer_parameter", "F")
    outers = np.unique(sw["outer_value"].values)
    fig, axes = P.figure(2, len(outers), width=5.0 * len(outers), height=6.0,
                         sharex="col", gridspec_kw={"height_ratios": [3, 2]})
    t_window = ly.attrs.get("window", "")
    for i, o in enumerate(outers):
        ax = axes[0, i]
        x, y = P.sweep_points(sw, o)
        P.bifurcation_dots(ax, x, y, s=1.0)
        ax.axhline(0, color="0.7", lw=0.5)
        ax.set_ylabel(P.LABELS["dw"])
        title = rf"${P.SYMBOLS[outer_name]}$ = {P.fmt(o)}, {sw.attrs.get('fixed', '')}"
        P.panel_label(ax, i, title.replace("omega=", r"$\Omega$ = "))
        _exponent_panel(axes[1, i], ly, o)
        P.panel_label(axes[1, i], len(outers) + i,
                      r"leading Lyapunov exponent $\lambda_1$ (finite time)")
    axes[1, -1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7,
                       frameon=False)
    fig.supxlabel(f"exponents over the {t_window}; intervals: 95 % batch means",
                  fontsize=7)
    P.save(fig, sm.output.pdf, sm.output.png, dpi=200)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
