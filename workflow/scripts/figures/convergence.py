"""Convergence figure: (a, b) KE ratio and x_max against run length at the named points
(difference to the longest run's widest window; solid: window of fixed length, dashed:
window a fraction of the run), (c) the same against the sticking threshold v_stick at chatter
points (difference to the smallest v_stick), (d) the cost of those runs, (e) distance of the
KE-ratio contour to the finest grid's against grid resolution, (f) the contours themselves.

Inputs (datasets of ``vines.studies.convergence``): ``snakemake.input.window``, ``.vstick``,
``.grid``; outputs ``snakemake.output.pdf`` / ``.png``; log ``snakemake.log[0]``.
"""
import numpy as np
from matplotlib.lines import Line2D

import vines.plotting as P
from vines.pipeline.jobs import run_job

FLOOR = 1e-16       # |differences| below (round-off, exact zeros) are drawn at this value
SYM = {"eta": r"\eta", "omega": r"\Omega", "F": "F"}


def point_label(ds, i):
    lab = str(ds["label"].values[i]) if "label" in ds else ""
    par = ", ".join(f"${SYM[k]}$={P.fmt(float(ds[k].values[i]))}" for k in SYM)
    return f"{lab}: {par}" if lab and not lab.startswith("eta=") else par


def colours(n):
    """n distinct colours: the palette's categorical ones, or steps of the colour map."""
    return P.palette.CATEGORICAL[:n] if n <= len(P.palette.CATEGORICAL) else P.palette.sequence(n)


def log_values(y, floor=FLOOR):
    """|y| lifted to at least ``floor``; the mask marks exact zeros (bitwise equal)."""
    a = np.abs(np.asarray(y, dtype=float))
    return np.maximum(a, floor), a == 0


def window_panels(ax_ke, ax_x, ax_leg, w):
    t = w["t_end"].values
    n_p = w.sizes["point"]
    col = colours(n_p)
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
    P.panel_label(ax_ke, 0, rf"KE ratio vs run length (tested {P.fmt(t_test)}/"
                            rf"{P.fmt(t_tr)} dotted)")
    P.panel_label(ax_x, 1, r"$x_m^{\max}$ vs run length")
    handles = [Line2D([], [], color=col[i], marker="o", ms=3.5, lw=1.0,
                      label=point_label(w, i)) for i in range(n_p)]
    rules = []
    for j in range(w.sizes["window"]):
        rule = str(w["window_rule"].values[j])
        text = (f"window {P.fmt(float(w['window_length'].values[j]))}" if rule == "length"
                else f"window {100 * float(w['window_fraction'].values[j]):g} % of run")
        rules.append(Line2D([], [], color="black", ls=styles.get(rule, ":"), label=text))
    rules.append(Line2D([], [], color="black", marker="o", mfc="white", ls="none",
                        label="regime differs from reference"))
    rules.append(Line2D([], [], color="black", ls=":", lw=0.8, label="tolerance"))
    ax_leg.legend(handles=handles + rules, fontsize=6.5, loc="center left", frameon=False)


def vstick_panels(ax_d, ax_c, ax_leg, v):
    vs = v["v_stick"].values
    n_p = v.sizes["point"]
    col = colours(n_p)
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
                    label=rf"KE tolerance {P.fmt(float(ke_tol))}" if ke_tol else "KE tol."),
             Line2D([], [], color="black", ls="-.", lw=0.8,
                    label=rf"$x_m^{{\max}}$ tolerance {P.fmt(float(x_tol))}" if x_tol
                    else "x tol.")]
    h, _ = ax_d.get_legend_handles_labels()
    ax_d.legend(handles=h + extra, fontsize=6, loc="upper left")
    ax_c.set_ylabel("run time per simulation (ms)")
    h, lab = ax_c.get_legend_handles_labels()
    style = [Line2D([], [], color="black", ls="-", marker="o", ms=3, label=r"$|\Delta$KE ratio$|$"),
             Line2D([], [], color="black", ls="--", marker="s", ms=2.5, mfc="none",
                    label=r"$|\Delta x_m^{\max}|/x_m^{\max}$")]
    ax_leg.legend(handles=h + style, fontsize=6.5, loc="center left", frameon=False)
    P.panel_label(ax_d, 2, rf"chatter points vs $v_{{\rm stick}}$ (tested {P.fmt(tested)})")
    P.panel_label(ax_c, 3, r"cost vs $v_{\rm stick}$ "
                           rf"($t_{{\rm end}}$ = {P.fmt(float(v.attrs['solver_t_end']))})")


def grid_panels(fig, ax_e, ax_f, ax_leg, g):
    res = g["resolution"].values
    coarse = res < res.max()
    for k, (name, style, lab) in enumerate((
            ("contour_dist_mean", "-o", "mean distance"),
            ("contour_dist_max", "-s", "max distance (one-sided Hausdorff)"),
            ("contour_hausdorff", "--^", "symmetric Hausdorff"))):
        ax_e.plot(res[coarse], g[name].values[coarse], style, ms=4, lw=1.0, label=lab,
                  color=P.palette.CATEGORICAL[k])
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
    P.panel_label(ax_e, 4, rf"KE ratio = {P.fmt(level)} contour vs grid "
                           rf"(finest {int(res.max())}$^2$)")
    eta, om = g["eta"].values, g["omega"].values
    ke = np.asarray(g["ke_ratio"].transpose("omega", "eta").values, dtype=float)
    mesh = ax_f.pcolormesh(eta, om, ke, cmap=P.palette.GREY_COLORMAP, vmin=0, vmax=1,
                           shading="nearest", rasterized=True)
    cb = fig.colorbar(mesh, ax=ax_f, shrink=0.9)
    cb.set_label(P.LABELS["ke_ratio"] + f" ({int(res.max())}$^2$ grid)", fontsize=7)
    handles = []
    for c, n, s in zip(P.palette.sequence(res.size), res, g["stride"].values, strict=False):
        s = int(s)
        ax_f.contour(eta[::s], om[::s], ke[::s, ::s], levels=[level], colors=[c],
                     linewidths=1.6 if s == 1 else 1.0)
        handles.append(Line2D([], [], color=c, label=f"{int(n)} x {int(n)}"))
    ax_leg.legend(handles=handles, fontsize=6.5, loc="center left", frameon=False,
                  title=f"contour KE ratio = {P.fmt(level)}\non the grid",
                  title_fontsize=6.5)
    # (f) the plane of Figs 12 and 16: eta across, Omega up
    ax_f.set_xlim(eta.min(), eta.max())
    ax_f.set_ylim(om.min(), om.max())
    ax_f.set_xlabel(P.LABELS["eta"])
    ax_f.set_ylabel(P.LABELS["omega"])
    P.panel_label(ax_f, 5, rf"contours KE ratio = {P.fmt(level)} over ($\eta$, $\Omega$), "
                           rf"$F$ = {P.fmt(F)}")


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
    fig, axes = P.figure(3, 3, width=12.0, height=10.5,
                         gridspec_kw={"width_ratios": [1.0, 1.0, 0.55]})
    for ax in axes[:, 2]:
        ax.axis("off")
    window_panels(axes[0, 0], axes[0, 1], axes[0, 2], w)
    vstick_panels(axes[1, 0], axes[1, 1], axes[1, 2], v)
    grid_panels(fig, axes[2, 0], axes[2, 1], axes[2, 2], g)
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
