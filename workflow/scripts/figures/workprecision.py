"""Work-precision: error against cost per run for the exact solver and the RK solvers, one
row per case (work_precision/<case>.nc), columns impact times, KE ratio, x_max."""
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job

FLOOR = 1e-16          # errors below (exact agreement in double precision) drawn here
_C = P.palette.OKABE_ITO
STYLE = {"exact": dict(color="k", marker="o"), "RK45": dict(color=_C["blue"], marker="s"),
         "DOP853": dict(color=_C["vermillion"], marker="^"),
         "LSODA": dict(color=_C["bluish green"], marker="v"),
         "Radau": dict(color=_C["reddish purple"], marker="x")}
COLUMNS = (("t_error", "max error of impact times"), ("ke_error", "error of KE ratio"),
           ("xmax_error", r"error of $x_m^{\max}$ (units of $L$)"))
VARS = ("method", "knob", "tolerance", "seconds", "sequence_ok", "t_error", "ke_error",
        "xmax_error", "impacts_per_second")


def _series(ds):
    """(label, style, rows) per method and knob, rows sorted by tolerance (loose first)."""
    out = []
    for method in dict.fromkeys(ds["method"].values.tolist()):
        for knob in dict.fromkeys(ds["knob"].values[ds["method"].values == method].tolist()):
            idx = np.nonzero((ds["method"].values == method) & (ds["knob"].values == knob))[0]
            idx = idx[np.argsort(-ds["tolerance"].values[idx])]
            style = dict(STYLE.get(method, dict(color="0.4", marker=".")))
            label = f"{method} ({knob})"
            if knob == "v_stick":
                style.update(color="0.55", marker="D")
            out.append((label, style, idx))
    return out


def _summary(ds):
    m, sec, te = ds["method"].values, ds["seconds"].values, ds["t_error"].values
    ex = (m == "exact") & (ds["knob"].values == "root_tol") & np.isfinite(te)
    dop = (m == "DOP853") & np.isfinite(te)
    if not ex.any() or not dop.any():
        return ""
    i = np.nonzero(ex)[0][np.argmin(te[ex])]
    j = np.nonzero(dop)[0][np.argmin(te[dop])]
    return (f"exact: {te[i]:.1e} in {sec[i] * 1e3:.2g} ms; DOP853 best: {te[j]:.1e} in "
            f"{sec[j] * 1e3:.3g} ms ({sec[j] / sec[i]:.0f}x the cost)")


def main(sm):
    P.configure(sm)
    cases = [P.load(p) for p in sm.input.cases]
    for ds in cases:
        P.require(ds, variables=VARS, finite=("seconds",))
    fig, axes = P.figure(len(cases), 3, width=13.5, height=3.4 * len(cases))
    for row, ds in enumerate(cases):
        ok = ds["sequence_ok"].values.astype(bool)
        sec = ds["seconds"].values
        for col, (var, ylabel) in enumerate(COLUMNS):
            ax = axes[row, col]
            err = np.maximum(np.nan_to_num(ds[var].values, nan=np.inf), FLOOR)
            top = 10.0 ** np.ceil(np.log10(max(np.max(err[np.isfinite(err)], initial=FLOOR), 1e-3)))
            for label, style, idx in _series(ds):
                y = np.where(np.isfinite(err[idx]), err[idx], top)
                ax.plot(sec[idx], y, "-", lw=0.9, color=style["color"], label=label,
                        marker=style["marker"], ms=4)
                bad = idx[~ok[idx]] if var == "t_error" else idx[~np.isfinite(err[idx])]
                if bad.size:
                    ax.plot(sec[bad], np.full(bad.size, top), style["marker"], ms=7,
                            mfc="none", color=style["color"])
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("wall-clock time per run (s)")
            ax.set_ylabel(ylabel)
            ax.grid(True, which="major", lw=0.3, color="0.85")
            a = ds.attrs
            title = (rf"$\eta$ = {P.fmt(a['case_eta'])}, $\Omega$ = {P.fmt(a['case_omega'])}, "
                     rf"$F$ = {P.fmt(a['case_F'])}, $t \in$ [0, {P.fmt(a['t_end'])}]")
            P.panel_label(ax, row * 3 + col, title if col == 0 else None)
        summary = _summary(ds)
        if summary:      # after the panel letter, small: the panels' titles must not overlap
            axes[row, 1].set_title(f"({chr(ord('a') + row * 3 + 1)}) {summary}", loc="left",
                                   fontsize=7)
    seen = {}
    for ax in axes.ravel():
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            seen.setdefault(lab, h)
    handles = list(seen.values()) + [P.Line2D([], [], ls="", marker="o", ms=7, mfc="none",
                                              color="0.3", label="impact sequence differs "
                                              "from the reference (drawn at the top)")]
    fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=7.5,
               frameon=False)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
