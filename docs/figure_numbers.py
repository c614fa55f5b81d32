"""Regenerate the measured numbers of docs/figures.md from a run's datasets.

    python docs/figure_numbers.py [RUN] [--check] [--doc FILE]

Rewrites the part of docs/figures.md between the markers ``<!-- numbers:begin -->`` and
``<!-- numbers:end -->`` with the numbers measured on the datasets of the run RUN (a results
folder, default results/paper), stating the commit and config they were made from (the
datasets' provenance attributes). ``--check``: print each number line that differs from the
file (old and new) and exit 1, exit 0 when they agree; nothing is written. Figures whose
stage is not in the run (the ``all`` figures after a paper run) are reported as "not in
this run" and are not compared. A path that is not a vines run is refused (exit 2). Reads
datasets only; no computation is rerun.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import sys
from collections import Counter
from itertools import zip_longest
from pathlib import Path
from typing import NamedTuple

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


class Section(NamedTuple):
    """One figure's numbers: its title, its function of the run folder and the datasets it
    reads, as (stage folder, dataset name prefix) pairs."""
    title: str
    fn: object
    needs: tuple


def _th(name):
    return Section(f"Fig {name[3:]}", lambda r: timehistories(r, name), (("timehistory", name),))


SECTIONS = (Section("Fig 2", fig2, (("extract_measures", "fig2"),)),
            Section("Fig 3", fig3, (("bifurcation_sweep", "fig3"),)),
            Section("fig3_lyapunov", fig3_lyapunov, (("lyapunov", "fig3"),)),
            _th("fig4"), _th("fig5"),
            Section("Fig 6", lambda r: zoom(r, "fig6"), (("map_solve", "fig6"),)),
            Section("Fig 7", fig7, (("extract_measures", "fig7"),)),
            _th("fig9"), _th("fig10"),
            Section("Fig 11", fig11, (("extract_measures", "fig11"),)),
            Section("Fig 12", fig12, (("extract_measures", "fig12"), ("stability_map", "fig16"))),
            Section("Fig 14", fig14, (("bifurcation_sweep", "fig14"),)),
            Section("Fig 15", lambda r: zoom(r, "fig15"), (("map_solve", "fig15"),)),
            Section("Fig 16", fig16, (("stability_map", "fig16"),)),
            Section("robust_tet", robust, (("robust_map", "robust"),)))

NOT_IN_RUN = "not in this run"


def in_run(res: Path, section: Section) -> bool:
    """True if the run holds every kind of dataset the section reads."""
    return all(_files(res, folder, prefix) for folder, prefix in section.needs)


def measure(res: Path) -> dict:
    """{title: [number line, ...]} of every section; ``[NOT_IN_RUN]`` where the run lacks
    its datasets."""
    out = {}
    for s in SECTIONS:
        if not in_run(res, s):
            out[s.title] = [NOT_IN_RUN]
            continue
        try:
            out[s.title] = s.fn(res) or ["no dataset"]
        except (P.FigureInputError, KeyError) as err:
            out[s.title] = [f"not available ({type(err).__name__}: {err})"]
    return out


def datasets(res: Path) -> list:
    """The run's stage datasets (``<stage>/<name>.nc``; simulate_grid's chunks excluded)."""
    return sorted(res.glob("*/*.nc"))


def provenance(res: Path) -> dict:
    """Provenance attributes of the run's datasets that carry them, by file."""
    import netCDF4
    out = {}
    for p in datasets(res):
        try:
            with netCDF4.Dataset(p) as nc:
                attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
        except OSError:
            continue
        if "vines_version" in attrs:
            out[p] = attrs
    return out


def origin(res: Path, prov: dict) -> str:
    """The sentence stating the commit(s) and config the run's datasets were made from."""
    commits = Counter(a.get("git_commit", "unknown") for a in prov.values())
    made = ", ".join(f"`{c}`" + (f" ({n} datasets)" if len(commits) > 1 else "")
                     for c, n in commits.most_common())
    keys = sorted(f"{p.parent.name}/{p.name}:{a.get('config_sha256', '')}"
                  for p, a in prov.items())
    digest = hashlib.sha256("\n".join(keys).encode()).hexdigest()[:16]
    sims = sorted({(a.get("solver_t_end"), a.get("solver_t_transient")) for a in prov.values()
                   if "solver_t_end" in a})
    window = "; ".join(f"t_end = {float(e):g}, t_transient = {float(t):g}" for e, t in sims)
    return (f"Measured on the {len(prov)} datasets of the run `{res.name}`, made by commit "
            f"{made} from the config with fingerprint `{digest}` (sha256 of the datasets' "
            f"`config_sha256` attributes; simulation window {window or 'none'}), by `python "
            f"docs/figure_numbers.py results/{res.name}` (do not edit by hand).")


def render(head: str, sections: dict) -> str:
    lines = [BEGIN, "", head, ""]
    for title, rows in sections.items():
        lines += [f"**{title}**", ""] + [f"- {r}" for r in rows] + [""]
    return "\n".join(lines + [END])


def parse(block: str) -> tuple:
    """(head line, {title: [line, ...]}) of a generated section."""
    head, sections, title = "", {}, None
    for line in block.splitlines():
        if line.startswith("**") and line.endswith("**"):
            title = line.strip("*")
            sections[title] = []
        elif line.startswith("- ") and title is not None:
            sections[title].append(line[2:])
        elif line.strip() and title is None and not line.startswith("<!--"):
            head = line
    return head, sections


def differences(old: dict, new: dict) -> list:
    """Lines ``title: old ... / new ...`` for every number line that differs; sections
    not in the new run are skipped."""
    out = []
    for title, rows in new.items():
        if rows == [NOT_IN_RUN]:
            continue
        for a, b in zip_longest(old.get(title, []), rows, fillvalue="(no line)"):
            if a != b:
                out.append(f"{title}:\n  old: {a}\n  new: {b}")
    return out


def refuse(msg: str) -> int:
    print(f"figure_numbers.py: {msg}", file=sys.stderr)
    return 2


def run_provenance(res: Path) -> tuple:
    """(why ``res`` is not a vines run or None, provenance of its datasets)."""
    if not res.is_dir():
        return f"RUN = '{res}' is not a folder; give a run's results folder, e.g. results/paper", {}
    prov = provenance(res)
    if not prov:
        return (f"RUN = '{res}' holds no vines datasets (<stage>/<name>.nc with provenance "
                "attributes); give a run's results folder, e.g. results/paper"), {}
    return None, prov


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="python docs/figure_numbers.py",
        description="Regenerate the measured numbers of docs/figures.md (between its "
                    "numbers markers) from the datasets of a run.")
    ap.add_argument("run", nargs="?", default="results/paper", metavar="RUN",
                    help="a run's results folder (default: results/paper)")
    ap.add_argument("--check", action="store_true",
                    help="write nothing; print each number that differs from the file and "
                         "exit 1 (0 when they agree); figures not in this run are skipped")
    ap.add_argument("--doc", type=Path, default=DOC, help=f"file to update (default: {DOC.name} "
                    "beside this script)")
    return ap


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    res = Path(args.run)
    why, prov = run_provenance(res)
    if why:
        return refuse(why)
    text = args.doc.read_text() if args.doc.is_file() else ""
    if BEGIN not in text or END not in text:
        return refuse(f"--doc = '{args.doc}' has no markers {BEGIN} / {END}")
    before, rest = text.split(BEGIN, 1)
    block, after = rest.split(END, 1)
    new, head = measure(res), origin(res, prov)
    missing = [t for t, rows in new.items() if rows == [NOT_IN_RUN]]
    if missing:
        print(f"{NOT_IN_RUN} ({res}): {', '.join(missing)}")
    if args.check:
        old_head, old = parse(block)
        diffs = differences(old, new)
        print("\n".join(diffs) if diffs else "numbers agree with the file")
        if old_head != head:
            print(f"note: the file says: {old_head}\n      this run: {head}")
        return 1 if diffs else 0
    _write(args.doc, before + render(head, new) + after)
    print(f"wrote {args.doc}")
    return 0


def _write(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("figure_numbers.py: interrupted; nothing written", file=sys.stderr)
        sys.exit(130)
