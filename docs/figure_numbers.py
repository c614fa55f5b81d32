"""Regenerate the measured numbers of docs/figures.md from a run's datasets.

    python docs/figure_numbers.py [results/paper] [--check]

Rewrites the part of docs/figures.md between the markers ``<!-- numbers:begin -->`` and
``<!-- numbers:end -->`` with the numbers measured on the datasets of the run (default
results/paper, the full study). ``--check``: exit 1 if the file would change (the numbers
are stale), without writing. Reads datasets only; no computation is rerun.
"""
from __future__ import annotations

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.core.linear import stuck_peak
from vines.core.params import L_HALF_M
from vines.plotting import bifurcation as B
from vines.plotting.uncertainty import WIDE_INTERVAL, wilson_width

DOC = Path(__file__).with_name("figures.md")
BEGIN, END = "<!-- numbers:begin -->", "<!-- numbers:end -->"


def _files(res: Path, folder: str, prefix: str) -> list:
    return sorted(p for p in (res / folder).glob("*.nc")
                  if p.stem == prefix or p.stem.startswith(prefix + "_"))


def _g(v) -> str:
    return f"{v:.3g}"


def _interval(x) -> str:
    x = np.asarray(x)
    return f"{_g(x.min())}-{_g(x.max())}" if x.size else "none"


def fig2(res):
    out = []
    for p in _files(res, "extract_measures", "fig2"):
        ds = P.measures(p, axes=("eta",), fixed=("omega", "F"))
        eta, ke, xm = ds["eta"].values, ds["ke_ratio"].values.ravel(), ds["xmax_m"].values.ravel()
        k, j = int(np.argmax(ke)), int(np.argmin(xm))
        out.append(f"F = {P.fmt(P.fixed_value(ds, 'F'))}: KE peak {ke[k]:.2f} at eta = "
                   f"{eta[k]:.3f}; x_max minimum {1e3 * xm[j]:.2g} mm at eta = {eta[j]:.3f}")
    return out


def _one_to_one(sw, outer, direction):
    sel = (sw["direction"].values == direction) & np.isclose(sw["outer_value"].values, outer)
    codes = P.sweep_regimes(sw)[sel]
    return sw["value"].values[sel][np.isin(codes, (P.REGIME_SYM, P.REGIME_ASYM))]


def fig3(res):
    out = []
    for p in _files(res, "bifurcation_sweep", "fig3"):
        sw = P.sweep(p)
        for o in np.unique(sw["outer_value"].values):
            out.append(f"F = {P.fmt(o)}: 1:1 for eta {_interval(_one_to_one(sw, o, 1))} (up "
                       f"sweep), {_interval(_one_to_one(sw, o, -1))} (down)")
    return out


def fig3_lyapunov(res):
    out = []
    for p in _files(res, "lyapunov", "fig3"):
        ly = P.load(p)
        ci = ly["exponents_ci"].values[:, 0, :]
        for o in np.unique(ly["outer_value"].values):
            for d, name in ((1, "up"), (-1, "down")):
                sel = np.isclose(ly["outer_value"].values, o) & (ly["direction"].values == d)
                pos, neg = sel & (ci[:, 0] > 0), sel & (ci[:, 1] < 0)
                out.append(f"F = {P.fmt(o)} ({name}): lambda_1 > 0 at {int(pos.sum())}, < 0 at "
                           f"{int(neg.sum())}, interval containing 0 at "
                           f"{int((sel & ~pos & ~neg).sum())} of {int(sel.sum())} points; "
                           f"lambda_1 {_interval(ly['lambda_1'].values[sel])}")
    return out


def timehistories(res, name):
    out = []
    for p in _files(res, "timehistory", name):
        ds = P.timehistory(p)
        for i in range(ds.sizes["point"]):
            fig, ax = P.figure(1, 1)
            counts = P.impact_phase_panel(ax[0, 0], ds, i)
            plt.close(fig)
            dw = np.abs(P.point_impacts(ds, i)["dw"])
            walls = "; ".join(f"{w}: {n} impacts, {k} with LO and ball moving the same way"
                              for w, (n, k) in counts.items())
            out.append(f"{P.th_title(ds, i).replace('$', '')}: regime "
                       f"{ds['regime'].values[i]}, KE {float(ds['ke_ratio'].values[i]):.2f}; "
                       f"{walls}; max |w'_i| {dw.max() if dw.size else 0:.3g}")
    return out


def zoom(res, name):
    out = []
    for p in _files(res, "map_solve", name):
        br = P.branch(p)
        main = B.continued_branches([br])[0]
        adm = main["admissible"].values.astype(bool)
        st = main["stable"].values.astype(bool) & adm
        lam = main["lambda_max"].values[st]
        subs = B.switched_branches(br)
        asym = [s["eta"].values[s["admissible"].values.astype(bool)] for s in subs]
        asym = ", ".join(_interval(a) for a in asym if a.size) or "none"
        out.append(f"{p.stem}: symmetric branch stable for eta {_interval(main['eta'].values[st])}"
                   f" (lambda_max there up to {lam.max() if lam.size else np.nan:.3f}); "
                   f"asymmetric branches admissible for eta {asym}")
    return out


def fig7(res):
    out = []
    grids = P.sorted_by_fixed([P.measures(p, axes=("eta", "F"), fixed=("omega",))
                               for p in _files(res, "extract_measures", "fig7")], "omega")
    for ds in grids:
        xm = P.grid2d(ds, "xmax_m", "eta", "F")
        j, i = np.unravel_index(np.argmax(xm), xm.shape)
        silent = P.grid2d(ds, "n_impacts", "eta", "F") == 0
        out.append(f"W = {P.fmt(P.fixed_value(ds, 'omega'))}: peak x_max {xm[j, i]:.2f} m at "
                   f"eta = {ds['eta'].values[i]:.2f}, F = {ds['F'].values[j]:.2f}; no impact at "
                   f"{int(silent.sum())} of {silent.size} points")
    return out


def fig11(res):
    out = []
    for p in _files(res, "extract_measures", "fig11"):
        ds = P.measures(p, axes=("omega",), fixed=("F",), min_size=3)
        F, d = P.fixed_value(ds, "F"), float(ds.attrs["solver_d"])
        for k in range(ds.sizes["eta"]):
            s = ds.isel(eta=k, F=0)
            eta, xm = float(s["eta"]), s["xmax_m"].values
            kv = int(np.argmax(xm))
            w_pk, a_pk = stuck_peak(eta, F, d)
            out.append(f"eta = {P.fmt(eta)}: VINES peak {xm[kv]:.3g} m at W = "
                       f"{s['omega'].values[kv]:.4f} (grid); Eq. 28 peak "
                       f"{float(a_pk) * L_HALF_M:.3g} m at "
                       f"W = {float(w_pk):.5f} (exact)")
    return out


def _maps(res):
    return {round(float(m.attrs["F"]), 9): m for m in map(P.stability, _files(res, "stability_map",
                                                                                  "fig16"))}


def fig12(res):
    out, maps = [], _maps(res)
    for p in _files(res, "extract_measures", "fig12"):
        ds = P.measures(p, axes=("eta", "omega"), fixed=("F",))
        F = P.fixed_value(ds, "F")
        c = P.region_counts(ds, maps[round(F, 9)])
        W = ds["omega"].values
        hit = (P.grid2d(ds, "n_impacts", "eta", "omega") > 0).any(axis=1)
        out.append(f"F = {P.fmt(F)}: grid points in the stable 1:1 region {c['stable']}, "
                   f"reached from rest {c['reached']}, no impact there {c['ke_zero']}; "
                   f"impacts only for W in [{W[hit].min():.3f}, {W[hit].max():.3f}]")
    return out


def fig14(res):
    out = []
    for p in _files(res, "bifurcation_sweep", "fig14"):
        sw = P.sweep(p)
        W = np.unique(sw["outer_value"].values)
        one = W[np.isclose(W, 1.0)]
        win = _interval(_one_to_one(sw, one[0], 1)) if one.size else "W = 1 not swept"
        out.append(f"F = {P.fmt(P.sweep_fixed(sw, 'F'))}: 1:1 at W = 1 for eta {win} (up sweep)")
    return out


def fig16(res):
    out = []
    for F, m in sorted(_maps(res).items()):
        counts = {P.CLASSES[k][0]: int((m["cls"].values == k).sum()) for k in sorted(P.CLASSES)}
        at = P.stable_at(m, m["eta"].values, np.array([0.5]))
        out.append(f"F = {P.fmt(F)}: class counts {counts}; stable at W = 0.5 for "
                   f"{int(at.sum())} of {at.size} eta values")
    return out


def robust(res):
    out = []
    for p in _files(res, "robust_map", "robust"):
        r = P.robust_map(p)
        n = int(r.attrs["n_states"])
        st, ef = r["stable_1to1_fraction"].values, r["efficient_fraction"].values
        wide = (wilson_width(st, n) > WIDE_INTERVAL) | (wilson_width(ef, n) > WIDE_INTERVAL)
        out.append(f"F = {P.fmt(float(r.attrs['F']))}: stable 1:1 holds >= half the basin at "
                   f"{int((st >= 0.5).sum())} of {st.size} points, efficient basin >= 0.5 at "
                   f"{int((ef >= 0.5).sum())}, efficient from rest at "
                   f"{int(r['from_rest_efficient'].values.sum())}; a 95 % Wilson interval "
                   f"wider than {P.fmt(WIDE_INTERVAL)} ({n} states) at {int(wide.sum())} points")
        if "efficient_fraction_asymptotic" in r:
            late = r["efficient_fraction_asymptotic"].values
            out.append(f"F = {P.fmt(float(r.attrs['F']))}, t_max = {_g(float(r.attrs['t_max']))}:"
                       f" efficient basin >= 0.5 at {int((late >= 0.5).sum())} points, the "
                       f"efficient fraction differs from the window's at "
                       f"{int((np.abs(late - ef) > 1e-12).sum())}, states escaped at "
                       f"{int((r['escaped_fraction'].values > 0).sum())} points")
    return out


SECTIONS = (("Fig 2", fig2), ("Fig 3", fig3), ("fig3_lyapunov", fig3_lyapunov),
            ("Fig 4", lambda r: timehistories(r, "fig4")),
            ("Fig 5", lambda r: timehistories(r, "fig5")), ("Fig 6", lambda r: zoom(r, "fig6")),
            ("Fig 7", fig7), ("Fig 9", lambda r: timehistories(r, "fig9")),
            ("Fig 10", lambda r: timehistories(r, "fig10")), ("Fig 11", fig11),
            ("Fig 12", fig12), ("Fig 14", fig14), ("Fig 15", lambda r: zoom(r, "fig15")),
            ("Fig 16", fig16), ("robust_tet", robust))


def numbers(res: Path) -> str:
    lines = [BEGIN, "", f"Measured on `{res.as_posix()}` by `python docs/figure_numbers.py "
             f"{res.as_posix()}` (do not edit by hand).", ""]
    for title, fn in SECTIONS:
        try:
            rows = fn(res)
        except (P.FigureInputError, KeyError) as err:
            rows = [f"not available ({type(err).__name__}: {err})"]
        lines.append(f"**{title}**")
        lines.append("")
        lines += [f"- {r}" for r in rows] or ["- no dataset"]
        lines.append("")
    lines.append(END)
    return "\n".join(lines)


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    check = "--check" in args
    args = [a for a in args if a != "--check"]
    res = Path(args[0] if args else "results/paper")
    text = DOC.read_text()
    if BEGIN not in text or END not in text:
        print(f"{DOC}: markers {BEGIN} / {END} missing", file=sys.stderr)
        return 2
    head, rest = text.split(BEGIN, 1)
    new = head + numbers(res) + rest.split(END, 1)[1]
    if check:
        return 0 if new == text else 1
    DOC.write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
