"""The solver studies on figures (datasets of ``vines.studies``): the convergence figure
(the measures against run length and window, sticking threshold and grid resolution) and
the work-precision figure (error against cost per run of the exact and the RK solvers)."""
from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

from . import palette
from .draw import LABELS, figure, fmt, panel_label

#: |differences| and errors below (round-off, exact agreement in double precision, exact
#: zeros) are drawn at this value
FLOOR = 1e-16


# ------------------------------------------------------------------ convergence

SYM = {"eta": r"\eta", "omega": r"\Omega", "F": "F"}


def point_label(ds, i):
    lab = str(ds["label"].values[i]) if "label" in ds else ""
    par = ", ".join(f"${SYM[k]}$={fmt(float(ds[k].values[i]))}" for k in SYM)
    return f"{lab}: {par}" if lab and not lab.startswith("eta=") else par


def point_colours(n):
    """n distinct colours: the palette's categorical ones, or steps of the colour map."""
    return palette.CATEGORICAL[:n] if n <= len(palette.CATEGORICAL) else palette.sequence(n)


def log_values(y, floor=FLOOR):
    """|y| lifted to at least ``floor``; the mask marks exact zeros (bitwise equal)."""
    a = np.abs(np.asarray(y, dtype=float))
    return np.maximum(a, floor), a == 0


def window_panels(ax_ke, ax_x, ax_leg, w):
    t = w["t_end"].values
    n_p = w.sizes["point"]
    col = point_colours(n_p)
    styles = {"length": "-", "fraction": "--"}
    ref_k = t.size - 1
    for i in range(n_p):
        for j in range(w.sizes["window"]):
            rule = str(w["window_rule"].values[j])
            same = w["regime_same"].values[i, j].astype(bool)
            for ax, name in ((ax_ke, "d_ke"), (ax_x, "rel_d_xmax")):
                y, zero = log_values(w[name].values[i, j])
                ref = (np.arange(t.size) == ref_k) & (
                    w["t_transient"].values[i, j, ref_k] == w["reference_t_transient"].values[i])
                y = np.where(ref, np.nan, y)
                ax.plot(t, y, styles.get(rule, ":"), color=col[i], lw=1.0)
                ax.plot(t[same & ~ref], y[same & ~ref], "o", color=col[i], ms=3.5)
                ax.plot(t[~same & ~ref], y[~same & ~ref], "o", color=col[i], ms=4.5,
                        mfc="white")
    t_test = float(w.attrs.get("tested_t_end", t[0]))
    for ax, tol, ylabel in ((ax_ke, w.attrs.get("ke_tol"), r"$|\Delta$KE ratio$|$"),
                            (ax_x, w.attrs.get("xmax_rtol"),
                             r"$|\Delta x_m^{\max}|/x_m^{\max}$")):
        ax.set_yscale("log")
        ax.set_xlabel(r"run length $t_{\rm end}$ (dimensionless time)")
        ax.set_ylabel(ylabel)
        ax.axvline(t_test, color="0.5", lw=0.8, ls=":")
        if tol is not None:
            ax.axhline(float(tol), color="black", lw=0.8, ls=":")
        ax.set_ylim(bottom=max(ax.get_ylim()[0], FLOOR / 2))
    t_tr = float(w.attrs.get("tested_t_transient", np.nan))
    panel_label(ax_ke, 0, rf"KE ratio vs run length (tested {fmt(t_test)}/"
                            rf"{fmt(t_tr)} dotted)")
    panel_label(ax_x, 1, r"$x_m^{\max}$ vs run length")
    handles = [Line2D([], [], color=col[i], marker="o", ms=3.5, lw=1.0,
                      label=point_label(w, i)) for i in range(n_p)]
    rules = []
    for j in range(w.sizes["window"]):
        rule = str(w["window_rule"].values[j])
        text = (f"window {fmt(float(w['window_length'].values[j]))}" if rule == "length"
                else f"window {100 * float(w['window_fraction'].values[j]):g} % of run")
        rules.append(Line2D([], [], color="black", ls=styles.get(rule, ":"), label=text))
    rules.append(Line2D([], [], color="black", marker="o", mfc="white", ls="none",
                        label="regime differs from reference"))
    rules.append(Line2D([], [], color="black", ls=":", lw=0.8, label="tolerance"))
    ax_leg.legend(handles=handles + rules, fontsize=6.5, loc="center left", frameon=False)


def vstick_panels(ax_d, ax_c, ax_leg, v):
    vs = v["v_stick"].values
    n_p = v.sizes["point"]
    col = point_colours(n_p)
    d_ke, z1 = log_values(v["d_ke"].values)
    d_x, z2 = log_values(v["rel_d_xmax"].values)
    ident = (z1 & z2).all(axis=0)                   # every point bitwise equal to reference
    k = np.argmin(ident) if not ident.all() else ident.size
    if k > 1:
        ax_d.axvspan(vs[0], vs[k - 1], color="0.9", lw=0,
                     label="identical to smallest $v_{\\rm stick}$ (all points)")
    for i in range(n_p):
        ax_d.plot(vs, d_ke[i], "-o", color=col[i], ms=3, lw=1.0)
        ax_d.plot(vs, d_x[i], "--s", color=col[i], ms=2.5, lw=0.8, mfc="none")
        ax_c.plot(vs, 1e3 * v["run_time"].values[i], "-o", color=col[i], ms=3, lw=1.0,
                  label=point_label(v, i))
    tested = float(v.attrs.get("tested_v_stick", np.nan))
    for ax in (ax_d, ax_c):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"sticking threshold $v_{\rm stick}$ (units of $L\omega_0$)")
        ax.axvline(tested, color="0.5", lw=0.8, ls=":")
    ke_tol, x_tol = v.attrs.get("ke_tol"), v.attrs.get("xmax_rtol")
    if ke_tol is not None:
        ax_d.axhline(float(ke_tol), color="black", lw=0.8, ls=":")
    if x_tol is not None:
        ax_d.axhline(float(x_tol), color="black", lw=0.8, ls="-.")
    ax_d.set_ylabel(r"$|\Delta$KE ratio$|$ (solid), $|\Delta x_m^{\max}|/x_m^{\max}$ (dashed)",
                    fontsize=8)
    ax_d.set_ylim(FLOOR / 3, None)
    ax_d.text(0.02, 0.06, f"|diff.| <= {FLOOR:g} drawn at {FLOOR:g}", transform=ax_d.transAxes,
              fontsize=6, color="0.4")
    extra = [Line2D([], [], color="black", ls=":", lw=0.8,
                    label=rf"KE tolerance {fmt(float(ke_tol))}" if ke_tol else "KE tol."),
             Line2D([], [], color="black", ls="-.", lw=0.8,
                    label=rf"$x_m^{{\max}}$ tolerance {fmt(float(x_tol))}" if x_tol
                    else "x tol.")]
    h, _ = ax_d.get_legend_handles_labels()
    ax_d.legend(handles=h + extra, fontsize=6, loc="upper left")
    ax_c.set_ylabel("run time per simulation (ms)")
    h, lab = ax_c.get_legend_handles_labels()
    style = [Line2D([], [], color="black", ls="-", marker="o", ms=3, label=r"$|\Delta$KE ratio$|$"),
             Line2D([], [], color="black", ls="--", marker="s", ms=2.5, mfc="none",
                    label=r"$|\Delta x_m^{\max}|/x_m^{\max}$")]
    ax_leg.legend(handles=h + style, fontsize=6.5, loc="center left", frameon=False)
    panel_label(ax_d, 2, rf"chatter points vs $v_{{\rm stick}}$ (tested {fmt(tested)})")
    panel_label(ax_c, 3, r"cost vs $v_{\rm stick}$ "
                           rf"($t_{{\rm end}}$ = {fmt(float(v.attrs['solver_t_end']))})")


def grid_panels(fig, ax_e, ax_f, ax_leg, g):
    res = g["resolution"].values
    coarse = res < res.max()
    for k, (name, style, lab) in enumerate((
            ("contour_dist_mean", "-o", "mean distance"),
            ("contour_dist_max", "-s", "max distance (one-sided Hausdorff)"),
            ("contour_hausdorff", "--^", "symmetric Hausdorff"))):
        ax_e.plot(res[coarse], g[name].values[coarse], style, ms=4, lw=1.0, label=lab,
                  color=palette.CATEGORICAL[k])
    da = np.abs(g["d_area_fraction"].values[coarse])
    ax_e.plot(res[coarse], np.where(da > 0, da, np.nan), ":d", ms=4, lw=1.0,
              color="0.3", label=r"$|\Delta$ area fraction$|$ (KE > level)")
    if coarse.sum() >= 1:
        n0 = res[coarse][0]
        y0 = float(g["contour_dist_mean"].values[coarse][0])
        nn = res[coarse].astype(float)
        if np.isfinite(y0) and y0 > 0:
            ax_e.plot(nn, y0 * (n0 / nn), color="0.6", lw=0.8, ls="-.", label=r"$\propto h$")
    ax_e.set_xscale("log")
    ax_e.set_yscale("log")
    ax_e.set_xticks(res[coarse])
    ax_e.set_xticklabels([str(int(n)) for n in res[coarse]])
    ax_e.minorticks_off()
    ax_e.set_xlabel("grid points per axis (nested grids)")
    ax_e.set_ylabel(r"distance to finest contour ($(\Omega, \eta)$ units)")
    # below the panel: inside, it hid points of the area-fraction curve
    ax_e.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2,
                frameon=False)
    level, F = float(g.attrs["level"]), float(g.attrs["F"])
    panel_label(ax_e, 4, rf"KE ratio = {fmt(level)} contour vs grid "
                           rf"(finest {int(res.max())}$^2$)")
    eta, om = g["eta"].values, g["omega"].values
    ke = np.asarray(g["ke_ratio"].transpose("omega", "eta").values, dtype=float)
    mesh = ax_f.pcolormesh(eta, om, ke, cmap=palette.GREY_COLORMAP, vmin=0, vmax=1,
                           shading="nearest", rasterized=True)
    cb = fig.colorbar(mesh, ax=ax_f, shrink=0.9)
    cb.set_label(LABELS["ke_ratio"] + f" ({int(res.max())}$^2$ grid)", fontsize=7)
    handles = []
    for c, n, s in zip(palette.sequence(res.size), res, g["stride"].values, strict=False):
        s = int(s)
        ax_f.contour(eta[::s], om[::s], ke[::s, ::s], levels=[level], colors=[c],
                     linewidths=1.6 if s == 1 else 1.0)
        handles.append(Line2D([], [], color=c, label=f"{int(n)} x {int(n)}"))
    ax_leg.legend(handles=handles, fontsize=6.5, loc="center left", frameon=False,
                  title=f"contour KE ratio = {fmt(level)}\non the grid",
                  title_fontsize=6.5)
    # (f) the plane of Figs 12 and 16: eta across, Omega up
    ax_f.set_xlim(eta.min(), eta.max())
    ax_f.set_ylim(om.min(), om.max())
    ax_f.set_xlabel(LABELS["eta"])
    ax_f.set_ylabel(LABELS["omega"])
    panel_label(ax_f, 5, rf"contours KE ratio = {fmt(level)} over ($\eta$, $\Omega$), "
                           rf"$F$ = {fmt(F)}")


def convergence_figure(w, v, g):
    """(a, b) the window study ``w``, (c, d) the v_stick study ``v``, (e, f) the grid study
    ``g``; each row's legend in a third column."""
    fig, axes = figure(3, 3, width=12.0, height=10.5,
                       gridspec_kw={"width_ratios": [1.0, 1.0, 0.55]})
    for ax in axes[:, 2]:
        ax.axis("off")
    window_panels(axes[0, 0], axes[0, 1], axes[0, 2], w)
    vstick_panels(axes[1, 0], axes[1, 1], axes[1, 2], v)
    grid_panels(fig, axes[2, 0], axes[2, 1], axes[2, 2], g)
    return fig


# ------------------------------------------------------------------ work-precision

_C = palette.OKABE_ITO
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


def work_precision_figure(cases):
    """One row per case, columns impact times, KE ratio, x_max: error against wall-clock
    time per run of each method and knob; one legend below."""
    fig, axes = figure(len(cases), 3, width=13.5, height=3.4 * len(cases))
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
            title = (rf"$\eta$ = {fmt(a['case_eta'])}, $\Omega$ = {fmt(a['case_omega'])}, "
                     rf"$F$ = {fmt(a['case_F'])}, $t \in$ [0, {fmt(a['t_end'])}]")
            panel_label(ax, row * 3 + col, title if col == 0 else None)
        summary = _summary(ds)
        if summary:      # after the panel letter, small: the panels' titles must not overlap
            axes[row, 1].set_title(f"({chr(ord('a') + row * 3 + 1)}) {summary}", loc="left",
                                   fontsize=7)
    seen = {}
    for ax in axes.ravel():
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            seen.setdefault(lab, h)
    handles = list(seen.values()) + [Line2D([], [], ls="", marker="o", ms=7, mfc="none",
                                            color="0.3", label="impact sequence differs "
                                            "from the reference (drawn at the top)")]
    fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=7.5,
               frameon=False)
    return fig
