"""Fig 11: (a, b) x_max (m, log axis) vs W of the VINES (red) and of the stuck linear
system Eq. 28 (black), one panel per eta (grid fig11_*); (c-e) LO displacement of the
VINES (red) and the steady state of Eq. 28 (black) at the points of timehistories.fig11."""
import matplotlib.pyplot as plt
import numpy as np

import vines.plotting as P
from vines.pipeline.jobs import run_job


def eq28_steady(t, eta, omega, F, d, phi=0.0):
    """Steady state of (1+eta) z'' + d z' + z = F sin(W t + phi) + d W F cos(W t + phi)."""
    H = F * (1 + 1j * d * omega) / (1 - (1 + eta) * omega ** 2 + 1j * d * omega)
    return np.imag(H * np.exp(1j * (omega * t + phi)))


def main(sm):
    ds = P.measures(sm.input.measures[0], axes=("omega",), fixed=("F",), min_size=3)
    P.require(ds, coords=("eta",), finite=("xmax_stuck_linear_m",))
    th = P.timehistory(sm.input.th[0])
    d = th.attrs.get("solver_d")
    if d is None or not np.isfinite(float(d)):
        raise P.FigureInputError(f"{sm.input.th[0]}: global attribute solver_d (damping d) "
                                 "is missing")
    d = float(d)
    ne, nt = ds.sizes["eta"], th.sizes["point"]
    fig = plt.figure(figsize=(max(3.6 * nt, 4.5 * ne), 6.4), constrained_layout=True)
    gs = fig.add_gridspec(2, ne * nt)
    F = P.fixed_value(ds, "F")
    W = ds["omega"].values
    for i in range(ne):
        ax = fig.add_subplot(gs[0, i * nt:(i + 1) * nt])
        s = ds.isel(eta=i, F=0)
        eta = float(s["eta"])
        ax.semilogy(W, s["xmax_m"].values, "-", color="tab:red", lw=1.3,
                    label="VINES, Eqs. (5)-(6)")
        ax.semilogy(W, s["xmax_stuck_linear_m"].values, "-", color="black", lw=1.0,
                    label="stuck linear, Eq. (28)")
        kv, kl = np.argmax(s["xmax_m"].values), np.argmax(s["xmax_stuck_linear_m"].values)
        ax.axvline(1.0, color="0.6", lw=0.6, ls=":")
        ax.axvline(1 / np.sqrt(1 + eta), color="tab:pink", lw=0.9, ls="--",
                   label=r"$\Omega = 1/\sqrt{1+\eta}$")
        ax.set_xlabel(P.LABELS["omega"])
        ax.set_ylabel(P.LABELS["xmax_m"])
        ax.set_xlim(W.min(), W.max())
        P.panel_label(ax, i, rf"$\eta$ = {P.fmt(eta)}, $F$ = {P.fmt(F)}; peaks at "
                      rf"$\Omega$ = {W[kv]:.3f} (VINES), {W[kl]:.3f} (Eq. 28)")
        ax.legend(fontsize=7, loc="upper right")
    for k in range(nt):
        ax = fig.add_subplot(gs[1, k * (ne * nt) // nt:(k + 1) * (ne * nt) // nt])
        t, zm = th["t"].values[k], th["z_m"].values[k]
        eta, om, Fk = (float(th[v].values[k]) for v in ("eta", "omega", "F"))
        ax.plot(t, P.metres(zm), color="tab:red", lw=1.0, label="VINES")
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
