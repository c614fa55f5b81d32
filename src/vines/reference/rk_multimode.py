"""RK oracle of the general host with absorbers (``vines.multimode``): its own code path.

scipy's DOP853 on the second-order equations written out with the full mass matrix (no
modes, no closed form): accelerations from the saddle-point system
[[M_f, G^T], [G, 0]] [a, -lambda] = [f, 0] (M_f = diag(M, m), G the rows x_j - y_i of the
stuck absorbers); a terminal event on every gap (x_j - y_i = +-L_i) and on every stuck
absorber's stop force (steps of at most a tenth of the fastest rate, so that no crossing
and return of a gap fits in one step); impacts by the impulse of the same saddle-point system with the
target w'+ = -r w'- for the impacting pair and w' = 0 for the stuck ones. The dissipation of
the host damping and of each damper and the forcing's work are integrated as extra states.
Shares only the model container with the engine, so that comparing them can fail.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ..multimode.model import HostModel


class _RKModel:
    def __init__(self, model: HostModel):
        h = model.host
        self.N, self.na = model.n_dof, model.n_absorbers
        self.nP = self.N + self.na
        self.M, self.C, self.K, self.iota = h.mass, h.damping, h.stiffness, h.influence
        self.ab = model.absorbers
        self.Mf = np.zeros((self.nP, self.nP))
        self.Mf[:self.N, :self.N] = self.M
        for i, a in enumerate(self.ab):
            self.Mf[self.N + i, self.N + i] = a.mass
        f = model.forcing
        self.A, self.W, self.ph = f.amplitude, f.frequency, f.phase
        # the fastest rate of the motion: steps of a tenth of it cannot hold a gap's
        # crossing and return (solve_ivp sees an event only as a sign change over a step)
        rates = [self.W] + [math.sqrt(a.stiffness / a.mass) for a in self.ab]
        rates += list(np.sqrt(np.abs(np.linalg.eigvals(np.linalg.solve(self.M, self.K)))))
        self.max_step = 0.1 / max(rates)

    def base(self, t):
        th = self.W * t + self.ph
        return self.A * math.sin(th), self.A * self.W * math.cos(th)

    def forces(self, t, q, v):
        """Generalised forces (without contact), host damping power, damper powers, work."""
        N = self.N
        u, ud = self.base(t)
        e, ed = q[:N] - self.iota * u, v[:N] - self.iota * ud
        el = self.C @ ed + self.K @ e
        f = np.zeros(self.nP)
        f[:N] = -el
        dd = np.zeros(self.na)
        for i, a in enumerate(self.ab):
            s, sd = q[N + i] - q[a.dof], v[N + i] - v[a.dof]
            fl = a.stiffness * s + a.damping * sd
            f[N + i] -= fl
            f[a.dof] += fl
            dd[i] = a.damping * sd * sd
        return f, float(ed @ self.C @ ed), dd, float(-ud * (self.iota @ el))

    def G(self, rows):
        G = np.zeros((len(rows), self.nP))
        for k, i in enumerate(rows):
            G[k, self.ab[i].dof] = 1.0
            G[k, self.N + i] = -1.0
        return G

    def saddle(self, rhs_top, rows, rhs_bottom):
        n, m = self.nP, len(rows)
        A = np.zeros((n + m, n + m))
        A[:n, :n] = self.Mf
        G = self.G(rows)
        A[:n, n:] = G.T
        A[n:, :n] = G
        sol = np.linalg.solve(A, np.concatenate((rhs_top, rhs_bottom)))
        return sol[:n], sol[n:]


def run_rk_model(model: HostModel, t_end: float, *, t_transient: float = 0.0, state0=None,
                 rtol: float = 1e-12, atol: float = 1e-14, v_stick: float = 1e-6,
                 max_events: int = 10000) -> dict:
    """Impacts (t, absorber, wall, w' before, stuck after), final state and dissipation of
    an RK run."""
    S = _RKModel(model)
    N, na, nP = S.N, S.na, S.nP
    q = np.zeros(nP) if state0 is None else np.array(state0[0], float)
    v = np.zeros(nP) if state0 is None else np.array(state0[1], float)
    stuck = {}                                 # absorber -> wall
    acc = np.zeros(2 + na)                     # host damping, work, dampers
    t = 0.0
    impacts, losses = [], np.zeros(na)

    def rhs(t_, y):
        qq, vv = y[:nP], y[nP:2 * nP]
        f, dh, dd, pw = S.forces(t_, qq, vv)
        rows = sorted(stuck)
        a, _ = S.saddle(f, rows, np.zeros(len(rows)))
        return np.concatenate((vv, a, [dh, pw], dd))

    def stop_force(t_, y, i):
        qq, vv = y[:nP], y[nP:2 * nP]
        f, *_ = S.forces(t_, qq, vv)
        rows = sorted(stuck)
        _, lam = S.saddle(f, rows, np.zeros(len(rows)))
        # the constraint force on the absorber is -lambda (G^T lambda, row -1 at y_i)
        return stuck[i] * (-lam[rows.index(i)])

    def kinetic(vv):
        return 0.5 * vv @ S.Mf @ vv

    def impulse(rows, target):
        """Velocity change meeting G dv = target for the pairs ``rows`` (saddle point)."""
        dv, _ = S.saddle(np.zeros(nP), rows, target)
        return dv

    n_ev = 0
    while t < t_end and n_ev < max_events:
        evs, kinds = [], []
        for i, a in enumerate(S.ab):
            if i in stuck:
                def ev(t_, y, i=i):
                    return stop_force(t_, y, i)
                ev.terminal, ev.direction = True, -1
                evs.append(ev)
                kinds.append((i, 0))
            elif math.isfinite(a.gap):
                for wall in (1, -1):
                    def ev(t_, y, i=i, wall=wall, L=a.gap, j=a.dof):
                        return L - wall * (y[j] - y[N + i])
                    ev.terminal, ev.direction = True, -1
                    evs.append(ev)
                    kinds.append((i, wall))
        t_stop = t_transient if t < t_transient else t_end
        y0 = np.concatenate((q, v, acc))
        sol = solve_ivp(rhs, (t, t_stop), y0, method="DOP853", rtol=rtol, atol=atol,
                        events=evs or None, max_step=S.max_step)
        hit = None
        if sol.status == 1:
            tt = [(te[0], k) for k, te in enumerate(sol.t_events) if te.size
                  and te[0] > t]
            if tt:
                te, k = min(tt)
                hit = (te, k, sol.y_events[k][0])
        if hit is None:
            y = sol.y[:, -1]
            t = t_stop
            q, v, acc = y[:nP].copy(), y[nP:2 * nP].copy(), y[2 * nP:].copy()
            continue
        te, k, y = hit
        t = te
        q, v, acc = y[:nP].copy(), y[nP:2 * nP].copy(), y[2 * nP:].copy()
        i, wall = kinds[k]
        n_ev += 1
        if wall == 0:                       # release
            del stuck[i]
            continue
        j = S.ab[i].dof
        wd = v[j] - v[N + i]
        if wall * wd <= 0.0:
            continue                        # touching, not closing
        e0 = kinetic(v)
        r = S.ab[i].restitution
        for _ in range(na + 1):
            rows = [i] + sorted(stuck)
            tgt = np.zeros(len(rows))
            tgt[0] = -(1.0 + r) * wd
            dv = impulse(rows, tgt)
            pulled = [other for other in stuck if other != i and stuck[other] * dv[S.ab[other].dof] < 0.0]
            if not pulled:
                break
            for other in pulled:
                del stuck[other]
        v = v + dv
        after = v[j] - v[N + i]
        sticks = abs(after) <= v_stick
        if sticks:
            rows = [i] + sorted(stuck)
            tgt = np.zeros(len(rows))
            tgt[0] = -after
            v = v + impulse(rows, tgt)
            stuck[i] = wall
        losses[i] += e0 - kinetic(v)
        impacts.append((t, i, wall, wd, float(sticks)))
    imp = np.array(impacts, float).reshape(-1, 5)
    return {"t": imp[:, 0], "absorber": imp[:, 1].astype(int), "wall": imp[:, 2].astype(int),
            "dw_before": imp[:, 3], "stuck": imp[:, 4].astype(int), "P": q, "V": v, "t_final": t,
            "dissipated_host": acc[0], "forcing_work": acc[1], "dissipated_dampers": acc[2:],
            "dissipated_impacts": losses, "stuck_at_end": dict(stuck)}
