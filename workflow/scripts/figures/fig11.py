"""Fig 11: (a, b) x_max (m, log axis) vs W of the VINES (vermillion, grid fig11_*) and of the stuck
linear system Eq. 28 (black, `vines.core.linear` on a fine omega grid, its exact peak
(closed form, `stuck_peak`) marked and quoted), one panel per eta; (c-e) LO displacement of the
VINES (vermillion) and the steady state of Eq. 28 (black) at the points of timehistories.fig11."""
import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.core.linear import stuck_amplitude, stuck_peak
from vines.core.params import L_HALF_M
from vines.pipeline.jobs import run_job

#: points of the fine omega grid on which the Eq. 28 curve is drawn
FINE_POINTS = 4001


def eq28_steady(t, eta, omega, F, d, phi=0.0):
    """Steady state of (1+eta) z'' + d z' + z = F sin(W t + phi) + d W F cos(W t + phi)."""
    H = F * (1 + 1j * d * omega) / (1 - (1 + eta) * omega ** 2 + 1j * d * omega)
    return np.imag(H * np.exp(1j * (omega * t + phi)))


def stuck_curve(W, eta, F, d):
    """Eq. 28 amplitude (m) on a fine omega grid (FINE_POINTS over the grid's range, plus the
    exact peak) and the exact peak (omega, x_max in m)."""
    w_pk, a_pk = stuck_peak(eta, F, d)
    fine = np.linspace(W.min(), W.max(), FINE_POINTS)
    if W.min() < w_pk < W.max():
        fine = np.sort(np.append(fine, w_pk))
    return fine, stuck_amplitude(eta, fine, F, d) * L_HALF_M, float(w_pk), float(a_pk) * L_HALF_M


def xmax_panel(ax, s, F, d, i):
    """x_max (m, log axis) vs omega of the VINES (grid) and Eq. 28 (fine grid, exact peak)."""
    eta, W = float(s["eta"]), s["omega"].values
    on_grid = stuck_amplitude(eta, W, F, d) * L_HALF_M
    if not np.allclose(on_grid, s["xmax_stuck_linear_m"].values, rtol=1e-9, atol=0):
        raise P.FigureInputError("xmax_stuck_linear_m of the grid differs from Eq. 28 with "
                                 f"the grid's d = {d} (eta = {eta})")
    fine, amp, w_pk, a_pk = stuck_curve(W, eta, F, d)
    kv = int(np.argmax(s["xmax_m"].values))
    ax.semilogy(W, s["xmax_m"].values, "-", color=P.C_BALL, lw=1.3, label="VINES, Eqs. (5)-(6)")
    ax.semilogy(fine, amp, "-", color="black", lw=1.0, label="stuck linear, Eq. (28)")
    ax.plot([W[kv]], [s["xmax_m"].values[kv]], "o", color=P.C_BALL, ms=4)
    ax.plot([w_pk], [a_pk], "o", color="black", ms=4)
    ax.axvline(1.0, color="0.6", lw=0.6, ls=":")
    ax.axvline(1 / np.sqrt(1 + eta), color=P.palette.OKABE_ITO["reddish purple"], lw=0.9, ls="--",
               label=r"$\Omega = 1/\sqrt{1+\eta}$")
    ax.set_xlabel(P.LABELS["omega"])
    ax.set_ylabel(P.LABELS["xmax_m"])
    ax.set_xlim(W.min(), W.max())
    P.panel_label(ax, i, rf"$\eta$ = {P.fmt(eta)}, $F$ = {P.fmt(F)}")
    ax.text(0.02, 0.03, f"peaks: VINES {1e3 * s['xmax_m'].values[kv]:.0f} mm at "
            rf"$\Omega$ = {W[kv]:.4f} (grid)" "\n"
            f"Eq. (28) {1e3 * a_pk:.0f} mm at " rf"$\Omega$ = {w_pk:.4f} (exact)",
            transform=ax.transAxes, fontsize=7, va="bottom")
    print(f"eta = {eta}: VINES peak {s['xmax_m'].values[kv]:.6g} m at omega {W[kv]:.6g}; "
          f"Eq. 28 peak {a_pk:.6g} m at omega {w_pk:.8f}")
    ax.legend(fontsize=7, loc="upper right")


def damping(ds, path) -> float:
    """The damping d of a dataset's runs (global attribute solver_d)."""
    d = ds.attrs.get("solver_d")
    if d is None or not np.isfinite(float(d)):
        raise P.FigureInputError(f"{path}: global attribute solver_d (damping d) is missing")
    return float(d)


def main(sm):
    P.configure(sm)
    ds = P.measures(sm.input.measures[0], axes=("omega",), fixed=("F",), min_size=3)
    P.require(ds, coords=("eta",), finite=("xmax_stuck_linear_m",))
    th = P.timehistory(sm.input.th[0])
    d_grid, d = damping(ds, sm.input.measures[0]), damping(th, sm.input.th[0])
    ne, nt = ds.sizes["eta"], th.sizes["point"]
    fig = plt.figure(figsize=(max(3.6 * nt, 4.5 * ne), 6.4), constrained_layout=True)
    gs = fig.add_gridspec(2, ne * nt)
    F = P.fixed_value(ds, "F")
    for i in range(ne):
        ax = fig.add_subplot(gs[0, i * nt:(i + 1) * nt])
        xmax_panel(ax, ds.isel(eta=i, F=0), F, d_grid, i)
    for k in range(nt):
        ax = fig.add_subplot(gs[1, k * (ne * nt) // nt:(k + 1) * (ne * nt) // nt])
        t, zm = th["t"].values[k], th["z_m"].values[k]
        eta, om, Fk = (float(th[v].values[k]) for v in ("eta", "omega", "F"))
        ax.plot(t, P.metres(zm), color=P.C_BALL, lw=1.0, label="VINES")
        ax.plot(t, P.metres(eq28_steady(t, eta, om, Fk, d)), color="black", lw=1.0,
                label="Eq. (28)")
        ax.set_xlim(t[0], t[-1])
        ax.set_xlabel(P.LABELS["t"])
        ax.set_ylabel(r"$x_m$ (m)")
        P.panel_label(ax, ne + k, P.th_title(th, k))
        if k == 0:
            ax.legend(fontsize=7, loc="upper right")
    P.save(fig, sm.output.pdf, sm.output.png)


run_job(snakemake, lambda: main(snakemake))  # noqa: F821  (injected by Snakemake)
