"""vines against its peers, all timed in ONE process: heyoka.py and scipy's DOP853.

Run:  PYTHONPATH=src python benchmarks/bench_peers.py [--quick] [--repeat N]
      (heyoka: pip install -e ".[bench]"; without it the heyoka rows are skipped.)

Cases (d = vines.D_DEFAULT, r = 0.65, start from rest, phi = 0, window [4000, 7000]):
  (a) 1:1 orbit, eta 0.05, omega 1, F 0.05, t in [0, 7000];
  (b) chatter,   eta 0.2,  omega 0.9, F 0.4: vines sticks (v_stick = 1e-6); heyoka has no
      sticking phase and DOP853 is run both with the reference solver's sticking rule and
      without it (v_stick = 0), each under an event budget (and heyoka under a wall clock).

Peers
  vines   vines.simulate (public API: closed-form kernel + measures + regime), best of N;
          a second row with periodic_shortcut=False (every impact integrated).
  heyoka  the same physics as a Taylor integrator (tol = machine epsilon, LLVM-compiled
          once; compilation is reported apart and never timed): state (z_m, v_m, z_b, v_b,
          int v_m^2, int v_b^2), terminal events on w - 1 (direction +) and w + 1
          (direction -) whose callbacks apply the impact law and let the propagation go on,
          a non-terminal event on v_m = 0 (window only) for max |z_m|. The transient
          [0, 4000] runs on an integrator without that event, the window on a second one
          that starts from the first's state with the integrals reset to 0. "batch" runs
          B = heyoka.recommended_simd_size() copies of the case in one SIMD batch integrator
          (time per trajectory = total / B).
  DOP853  vines.simulate(..., solver="rk", method="DOP853", rtol=1e-10) (scipy's
          solve_ivp event loop, vines.reference.rk). --quick runs it to t = 1000 only
          (window [571.4, 1000]) and EXTRAPOLATES its time per time unit to t = 7000.

Prints per-trajectory times, ratios, us per impact, agreement with vines (impacts, KE ratio,
x_max, impact times), what each peer did in chatter, the batch scaling of
vines.simulate_batch on 64 random points (1 -> 2 threads), next to the acceptance targets.
No timing is asserted anywhere.
"""
import argparse
import math
import os
import platform
import time

import numpy as np

import vines
from vines.core.params import V_STICK_DEFAULT

CASE_A = dict(eta=0.05, omega=1.0, F=0.05)
CASE_B = dict(eta=0.2, omega=0.9, F=0.4)
R, D = 0.65, vines.D_DEFAULT
T_END, T_TR = 7000.0, 4000.0
TARGETS = ("kernel <= 1.0 us per impact (case (a) through vines.simulate, periodic shortcut "
           "off); vines >= 6x heyoka.py per trajectory on the 1:1 case, shortcut off (with "
           "it >= 5x, stretch 10x); >= 1000x DOP853 at rtol 1e-10 on the same run; batch 2 "
           "threads >= 1.8x")

try:
    import heyoka as hy
except ImportError:             # optional extra: pip install -e ".[bench]"
    hy = None


def load():
    return "load {:.2f} {:.2f} {:.2f}".format(*os.getloadavg())


def best_of(fn, repeat, clock=time.perf_counter):
    best, out = float("inf"), None
    for _ in range(repeat):
        t = clock()
        out = fn()
        best = min(best, clock() - t)
    return best, out


def verdict(ok):
    return "MET" if ok else "NOT MET"


# ---- heyoka model ---------------------------------------------------------------------------

class HeyokaVines:
    """The VI NES in heyoka.py: two compiled integrators (transient, window), see module doc.

    batch=None: scalar integrators; batch=B: SIMD batch integrators running B trajectories.
    diag=True adds a non-terminal event on w' = 0 recording the largest |w| at turning points
    (a ball that went through a wall shows |w| > 1). cooldown: heyoka's event cooldown
    (-1 = heyoka's automatic choice). xmax=False drops the v_m = 0 event (x_max is then
    only taken at impacts: a lower bound of heyoka's cost, with an incomplete measure).
    """

    def __init__(self, batch=None, diag=False, cooldown=-1.0, xmax=True):
        self.B = batch
        zm, vm, zb, vb, im, ib = hy.make_vars("zm", "vm", "zb", "vb", "im", "ib")
        om, F, d = hy.par[0], hy.par[1], hy.par[2]
        f = F * hy.sin(om * hy.time) + d * om * F * hy.cos(om * hy.time)
        sys_ = [(zm, vm), (vm, f - d * vm - zm), (zb, vb), (vb, hy.expression(0.0)),
                (im, vm * vm), (ib, vb * vb)]
        rec = self.rec = _Rec()

        # callbacks are closures over `rec` (heyoka may copy callback objects; a function
        # is copied as itself, so they all share this record)
        if batch is None:
            def impact(ta, d_sgn):
                s = ta.state
                a, b = s[1], s[3]
                rec.t_imp.append(ta.time)
                eta, r = rec.eta, rec.r
                s[1] = ((1.0 - r * eta) * a + eta * (1.0 + r) * b) / (1.0 + eta)
                s[3] = ((1.0 + r) * a + (eta - r) * b) / (1.0 + eta)
                if rec.win:
                    z = abs(s[0])
                    if z > rec.xm:
                        rec.xm = z
                if len(rec.t_imp) >= rec.max_events:
                    rec.stop = "event budget"
                    return False
                if time.perf_counter() > rec.deadline:
                    rec.stop = "wall-clock limit"
                    return False
                return True

            def vm_zero(ta, t, d_sgn):          # extremum of z_m (window integrator only)
                z = abs(ta.update_d_output(t)[0])
                if z > rec.xm:
                    rec.xm = z

            def turning(ta, t, d_sgn):          # extremum of w
                o = ta.update_d_output(t)
                w = abs(o[0] - o[2])
                if w > rec.wmax:
                    rec.wmax = w
                if w > 1.0 + 1e-6 and rec.t_escape is None:
                    rec.t_escape = t
            T, NT, kw = hy.t_event, hy.nt_event, {}
            make = hy.taylor_adaptive
        else:
            def impact(ta, d_sgn, j):
                s = ta.state
                a, b = s[1, j], s[3, j]
                rec.n[j] += 1
                eta, r = rec.eta[j], rec.r
                s[1, j] = ((1.0 - r * eta) * a + eta * (1.0 + r) * b) / (1.0 + eta)
                s[3, j] = ((1.0 + r) * a + (eta - r) * b) / (1.0 + eta)
                if rec.win:
                    z = abs(s[0, j])
                    if z > rec.xm[j]:
                        rec.xm[j] = z
                return True

            def vm_zero(ta, t, d_sgn, j):
                z = abs(ta.update_d_output(np.full(batch, t))[0, j])
                if z > rec.xm[j]:
                    rec.xm[j] = z
            turning = None
            T, NT, kw = hy.t_event_batch, hy.nt_event_batch, {}
            make = hy.taylor_adaptive_batch

        ev = [T(zm - zb - 1.0, callback=impact, direction=hy.event_direction.positive,
                cooldown=cooldown),
              T(zm - zb + 1.0, callback=impact, direction=hy.event_direction.negative,
                cooldown=cooldown)]
        nt_tr = [NT(vm - vb, turning)] if diag else []
        nt_w = ([NT(vm, vm_zero)] if xmax else []) + nt_tr
        s0 = [0.0] * 6 if batch is None else np.zeros((6, batch))
        p0 = [1.0, 0.0, D] if batch is None else np.tile([[1.0], [0.0], [D]], (1, batch))
        t0 = time.perf_counter()
        self.ta_tr = make(sys_, s0, pars=p0, t_events=ev, nt_events=nt_tr,
                          compact_mode=False, **kw)
        self.ta_w = make(sys_, s0, pars=p0, t_events=ev, nt_events=nt_w,
                         compact_mode=False, **kw)
        self.compile_s = time.perf_counter() - t0
        self.order, self.tol = self.ta_w.order, self.ta_w.tol

    def run(self, eta, omega, F, r=R, d=D, t_end=T_END, t_tr=T_TR, max_events=10**9,
            wall_s=math.inf):
        """One trajectory (batch: B trajectories with per-lane eta, omega, F) from rest."""
        rec, ta, tw = self.rec, self.ta_tr, self.ta_w
        rec.reset(eta, r, self.B, max_events, time.perf_counter() + wall_s)
        if self.B is None:
            ta.time = 0.0
        else:
            ta.set_time(np.zeros(self.B))
        ta.state[:] = 0.0
        ta.pars[0], ta.pars[1], ta.pars[2] = omega, F, d
        oc = self._prop(ta, t_tr)
        if rec.stop is None:            # window: second integrator, integrals from 0
            tw.state[:] = ta.state
            tw.state[4:6] = 0.0
            tw.pars[:] = ta.pars
            if self.B is None:
                tw.time = ta.time
            else:
                tw.set_time(ta.time.copy())
            rec.win = True
            rec.xm = np.abs(tw.state[0]).copy() if self.B else abs(tw.state[0])
            oc = self._prop(tw, t_end)
            ta = tw
        s = ta.state
        t_last = ta.time
        xm = np.maximum(rec.xm, np.abs(s[0])) if self.B else max(rec.xm, abs(s[0]))
        tw_len = np.asarray(t_last) - t_tr
        with np.errstate(invalid="ignore", divide="ignore"):
            K_m = 0.5 * s[4] / tw_len
            K_b = 0.5 * np.asarray(eta) * s[5] / tw_len
            ke = np.where(tw_len > 0, K_b / (K_m + K_b), np.nan)
            ke = ke if self.B else float(ke)
        n = rec.n.copy() if self.B else len(rec.t_imp)
        return dict(n_impacts=n, ke_ratio=ke, xmax=xm, t_last=t_last, outcome=oc,
                    stop=rec.stop, t_imp=np.array(rec.t_imp), wmax=rec.wmax,
                    t_escape=rec.t_escape)

    def _prop(self, ta, t):
        out = ta.propagate_until(t)
        if self.B is None:
            return out[0]
        return [res[0] for res in ta.propagate_res]


class _Rec:
    def reset(self, eta, r, B, max_events, deadline):
        self.r, self.max_events, self.deadline = r, max_events, deadline
        self.eta = np.broadcast_to(np.asarray(eta, float), (B,)).copy() if B else float(eta)
        self.n = np.zeros(B, dtype=np.int64) if B else None
        self.xm = np.zeros(B) if B else 0.0
        self.t_imp, self.win, self.stop = [], False, None
        self.wmax, self.t_escape = 0.0, None


# ---- the benchmark --------------------------------------------------------------------------

def case_a(args):
    """Interleaved timings (every repeat runs each contender once, so all see the same
    load); best wall time and best CPU time (time.process_time, insensitive to other jobs on
    the machine) of each."""
    n_rep = args.repeat
    print(f"== (a) 1:1 case eta 0.05, omega 1, F 0.05, d {D:g}, r {R}, t in [0, 7000], "
          f"window [4000, 7000], from rest   [{load()}]")
    t = time.perf_counter()
    vines.simulate(**CASE_A, t_end=50.0, t_transient=10.0)
    print(f"  vines first call (numba cache load / compile, not timed): "
          f"{time.perf_counter() - t:.2f} s")
    runs = {"vines": lambda: vines.simulate(**CASE_A, r=R, d=D, t_end=T_END, t_transient=T_TR),
            "vines_full": lambda: vines.simulate(**CASE_A, r=R, d=D, t_end=T_END,
                                                 t_transient=T_TR, periodic_shortcut=False)}
    B = 1
    if hy is None:
        print("  heyoka  : SKIPPED (heyoka not importable: pip install -e \".[bench]\")")
    else:
        h, h0 = HeyokaVines(), HeyokaVines(xmax=False)
        B = hy.recommended_simd_size()
        hb = HeyokaVines(batch=B)
        print(f"  heyoka {hy.__version__} JIT compilation (not timed): scalar integrators "
              f"{h.compile_s:.3f} s, without x_max event {h0.compile_s:.3f} s, batch (B = {B} "
              f"SIMD lanes) {hb.compile_s:.3f} s; Taylor order {h.order}, tol {h.tol:.2e}")
        runs.update(heyoka=lambda: h.run(**CASE_A), heyoka_noxmax=lambda: h0.run(**CASE_A),
                    heyoka_batch=lambda: hb.run(**CASE_A))
    wall = {k: math.inf for k in runs}
    cpu = dict(wall)
    res = {}
    for _ in range(n_rep):
        for k, fn in runs.items():
            w, c = time.perf_counter(), time.process_time()
            res[k] = fn()
            c, w = time.process_time() - c, time.perf_counter() - w
            wall[k], cpu[k] = min(wall[k], w), min(cpu[k], c)
    print(f"  timings: best of {n_rep} interleaved repeats, wall / CPU   [{load()}]")
    rv = res["vines"]
    n = rv.n_impacts

    def row(label, k, per=1):
        nn = n
        print(f"  {label:<16}: {wall[k] / per * 1e3:8.2f} / {cpu[k] / per * 1e3:8.2f} ms per "
              f"trajectory  {cpu[k] / per / nn * 1e6:7.2f} us/impact (CPU)")
    row("vines", "vines")
    print(f"      ({n} impacts, KE ratio {rv.ke_ratio:.12f}, x_max {rv.xmax:.12f}, regime "
          f"{rv.regime}; periodic shortcut from t = {rv.shortcut_time:.1f})")
    rf = res["vines_full"]
    row("vines, no shortcut", "vines_full")
    print(f"      (periodic_shortcut=False: the kernel integrates every impact; |dKE ratio| = "
          f"{abs(rf.ke_ratio - rv.ke_ratio):.2e}, |dx_max| = {abs(rf.xmax - rv.xmax):.2e})")
    out = dict(n=n, wall=wall, cpu=cpu, B=B)
    if hy is not None:
        rh, rh0, rb = res["heyoka"], res["heyoka_noxmax"], res["heyoka_batch"]
        row("heyoka", "heyoka")
        row("heyoka no x_max", "heyoka_noxmax")
        print("      (impacts and KE ratio only, max |z_m| taken at impacts: a lower bound "
              "of heyoka's cost, x_max incomplete)")
        row("heyoka batch", "heyoka_batch", per=B)
        print(f"      ({B} copies of case (a) in one SIMD batch integrator; time / {B})")
        ti_v, ti_h = rv.impacts["t"], rh["t_imp"]
        same_n = ti_v.size == ti_h.size
        dt = np.max(np.abs(ti_v - ti_h)) if same_n else math.nan
        print(f"  agreement heyoka vs vines: impacts {rh['n_impacts']} vs {n} "
              f"(difference {rh['n_impacts'] - n}), |dKE ratio| = "
              f"{abs(rh['ke_ratio'] - rv.ke_ratio):.2e}, |dx_max| = "
              f"{abs(rh['xmax'] - rv.xmax):.2e}, max |d t_impact| = {dt:.2e}")
        ok_b = bool(np.all(rb["n_impacts"] == n)
                    and np.all(np.abs(rb["ke_ratio"] - rv.ke_ratio) < 1e-8)
                    and np.all(np.abs(rb["xmax"] - rv.xmax) < 1e-8))
        agree = same_n and abs(rh["ke_ratio"] - rv.ke_ratio) < 1e-8
        print(f"    batch lanes agree too: {ok_b}; no x_max run: impacts {rh0['n_impacts']}, "
              f"|dKE ratio| = {abs(rh0['ke_ratio'] - rv.ke_ratio):.2e}")
        print(f"    -> {'agree: the comparison is meaningful' if agree else 'DO NOT AGREE: timings not comparable'}")
        out["heyoka_agree"] = agree

    # DOP853
    vines.simulate(**CASE_A, t_end=20.0, t_transient=10.0, solver="rk", method="DOP853",
                   rtol=1e-10)                                     # import scipy paths
    te = 1000.0 if args.quick else T_END
    ttr = T_TR * te / T_END
    w, c = time.perf_counter(), time.process_time()
    rr = vines.simulate(**CASE_A, r=R, d=D, t_end=te, t_transient=ttr, solver="rk",
                        method="DOP853", rtol=1e-10)
    c, w = time.process_time() - c, time.perf_counter() - w
    f = T_END / te
    lab = (f" EXTRAPOLATED (--quick: measured {w * 1e3:.0f} / {c * 1e3:.0f} ms on t in "
           f"[0, 1000], x 7)") if args.quick else " (one run)"
    print(f"  {'DOP853':<16}: {w * f * 1e3:8.0f} / {c * f * 1e3:8.0f} ms per trajectory"
          f"{lab}  {c / rr.n_impacts * 1e6:7.0f} us/impact (CPU), rtol 1e-10  [{load()}]")
    rv_r = rv if not args.quick else vines.simulate(**CASE_A, r=R, d=D, t_end=te,
                                                    t_transient=ttr)
    span = "" if not args.quick else " on [0, 1000] (window [571.4, 1000])"
    print(f"  agreement DOP853 vs vines{span}: impacts {rr.n_impacts} vs {rv_r.n_impacts}, "
          f"|dKE ratio| = {abs(rr.ke_ratio - rv_r.ke_ratio):.2e}, "
          f"|dx_max| = {abs(rr.xmax - rv_r.xmax):.2e}")
    wall["dop853"], cpu["dop853"] = w * f, c * f
    return out


def case_b(args):
    budget = 1000 if args.quick else 3000
    wall = 10.0 if args.quick else 30.0
    print(f"\n== (b) chatter case eta 0.2, omega 0.9, F 0.4 (same d, r, window, start)   "
          f"[{load()}]")
    t_v, rv = best_of(lambda: vines.simulate(**CASE_B, r=R, d=D, t_end=T_END, t_transient=T_TR),
                      3)
    c_v, _ = best_of(lambda: vines.simulate(**CASE_B, r=R, d=D, t_end=T_END, t_transient=T_TR),
                     3, clock=time.process_time)
    tv = rv.impacts["t"]
    print(f"  vines   : {t_v * 1e3:8.2f} ms wall / {c_v * 1e3:.2f} ms CPU  "
          f"{c_v / rv.n_impacts * 1e6:6.2f} us/impact (CPU)  "
          f"status {rv.status}, {rv.n_impacts} impacts, {rv.n_sticks} sticking phases, "
          f"t_stuck {rv.t_stuck_whole_run:.1f} over the run ({rv.t_stuck:.1f} in the window), "
          f"regime {rv.regime}, KE ratio {rv.ke_ratio:.6f}, x_max {rv.xmax:.4f}  [{load()}]")
    if hy is None:
        print("  heyoka  : SKIPPED (heyoka not importable)")
    else:
        for cd, label in ((-1.0, "automatic cooldown"), (0.0, "cooldown 0")):
            h = HeyokaVines(diag=True, cooldown=cd)
            t = time.perf_counter()
            rh = h.run(**CASE_B, max_events=10 * budget, wall_s=wall)
            el = time.perf_counter() - t
            te = rh["t_escape"]
            n_v = int(np.sum(tv <= te)) if te is not None else None
            print(f"  heyoka ({label}; budget {10 * budget} events, {wall:g} s wall clock; "
                  f"compile {h.compile_s:.2f} s not timed): {el * 1e3:.1f} ms, "
                  f"{'stopped: ' + rh['stop'] if rh['stop'] else 'reached t = {:.1f}'.format(rh['t_last'])}"
                  f", {rh['n_impacts']} impacts (vines: {int(np.sum(tv <= rh['t_last']))} up to "
                  f"the same t), KE ratio {rh['ke_ratio']:.4g}, max |w| = {rh['wmax']:.4g}")
            if te is not None:
                ti = rh["t_imp"]
                last = ti[ti <= te]
                print(f"      -> the ball LEFT THE CAVITY (|w| > 1, no error raised) at "
                      f"t ~ {te:.3f}: impact(s) missed in an accumulation "
                      f"(last impact seen t = {last[-1] if last.size else math.nan:.6f}, "
                      f"{last.size} impacts by then; vines: {n_v}); results meaningless")
            elif rh["stop"]:
                print("      -> stalled in the accumulation of impacts (bounded by the budget)")
    for vs, label in ((V_STICK_DEFAULT, "sticking rule of the reference, "
                       "v_stick 1e-6"), (0.0, "no sticking, v_stick 0")):
        t = time.perf_counter()
        rr = vines.simulate(**CASE_B, r=R, d=D, t_end=T_END, t_transient=T_TR, solver="rk",
                            method="DOP853", rtol=1e-10, v_stick=vs, max_impacts=budget)
        el = time.perf_counter() - t
        print(f"  DOP853 rtol 1e-10 ({label}; budget {budget} impacts): {el:.2f} s, status "
              f"{rr.status}, reached t = {rr.t_last:.2f} of 7000, {rr.n_impacts} impacts "
              f"(vines: {int(np.sum(tv <= rr.t_last))} up to the same t), {rr.n_sticks} sticks, "
              f"{el / max(rr.n_impacts, 1) * 1e6:.0f} us/impact  [{load()}]")
        if rr.status == "max_impacts":
            print(f"      -> progressing slowly; at this rate the run to t = 7000 "
                  f"({rv.n_impacts} impacts) would take ~{el / rr.n_impacts * rv.n_impacts:.0f} s")
        elif rr.status == "zeno":
            print("      -> stopped at an accumulation point of impacts (Zeno) it may not "
                  "resolve without sticking")


def batch(args):
    rng = np.random.default_rng(0)
    eta = rng.uniform(0.02, 1.0, 64)
    omega = rng.uniform(0.6, 1.4, 64)
    F = rng.uniform(0.05, 0.5, 64)
    kw = dict(t_end=T_END, t_transient=T_TR)
    vines.simulate_batch(eta[:2], omega[:2], F[:2], n_threads=2, **kw)
    rep = 1 if args.quick else 2
    t1, b1 = best_of(lambda: vines.simulate_batch(eta, omega, F, n_threads=1, **kw), rep)
    t2, b2 = best_of(lambda: vines.simulate_batch(eta, omega, F, n_threads=2, **kw), rep)
    same = all(np.array_equal(b1[k], b2[k], equal_nan=b1[k].dtype.kind == "f")
               for k in b1)      # shortcut_time is NaN where the shortcut was not taken
    print(f"\n== vines.simulate_batch, 64 random points (seed 0; eta 0.02-1, omega 0.6-1.4, "
          f"F 0.05-0.5), 7000 units each, {os.cpu_count()} cores   [{load()}]")
    print(f"  1 thread : {t1:7.3f} s ({t1 / 64 * 1e3:.1f} ms/point)")
    print(f"  2 threads: {t2:7.3f} s   speed-up {t1 / t2:.2f}x   identical results: {same}  "
          f"[{load()}]")
    if os.getloadavg()[0] > (os.cpu_count() or 1) - 1:
        print("  NOTE: other jobs keep the machine busy (load above cores - 1): the second "
              "thread has no free core, so this speed-up understates the scaling")
    return t1 / t2, same


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="DOP853 on t in [0, 1000] only, time extrapolated x7 (labelled); "
                         "smaller chatter budgets, fewer repeats")
    ap.add_argument("--repeat", type=int, default=None, help="best of N for vines/heyoka")
    args = ap.parse_args()
    if args.repeat is None:
        args.repeat = 5 if args.quick else 10
    print(f"bench_peers: vines {vines.__version__} ({vines.__file__}), numpy {np.__version__}, "
          f"heyoka {hy.__version__ if hy else 'not installed'}, python "
          f"{platform.python_version()}, {os.cpu_count()} cores, {load()}"
          f"{'   [--quick]' if args.quick else ''}")
    a = case_a(args)
    case_b(args)
    sp, same = batch(args)
    print(f"\n== summary vs acceptance targets: {TARGETS}   [{load()}]")
    w, c = a["wall"], a["cpu"]

    def ratio(k, per=1, ref="vines"):
        return c[k] / per / c[ref], w[k] / per / w[ref]
    print("  ratios from CPU times (wall-time ratios in brackets):")
    if "heyoka" in c:
        rc, rw = ratio("heyoka")
        print(f"  vines vs heyoka.py (scalar)      : {rc:6.2f}x ({rw:.2f}x)   target >= 5x "
              f"(stretch 10x): {verdict(rc >= 5)}"
              f"{'' if a['heyoka_agree'] else '  (results disagree!)'}")
        rc, rw = ratio("heyoka", ref="vines_full")
        print(f"  vines without the periodic shortcut vs heyoka.py (scalar): {rc:6.2f}x "
              f"({rw:.2f}x)   target >= 6x: {verdict(rc >= 6)}")
        rc, rw = ratio("heyoka_batch", a["B"])
        print(f"  vines vs heyoka.py (batch mode)  : {rc:6.2f}x ({rw:.2f}x)")
        rc, rw = ratio("heyoka_noxmax")
        print(f"  vines vs heyoka.py, no x_max event (lower bound): {rc:6.2f}x ({rw:.2f}x)")
    else:
        print("  vines vs heyoka.py : skipped (heyoka not installed)")
    rc, rw = ratio("dop853")
    print(f"  vines vs DOP853 rtol 1e-10       : {rc:6.0f}x ({rw:.0f}x)"
          f"{' EXTRAPOLATED (--quick)' if args.quick else ''}   target >= 1000x: "
          f"{verdict(rc >= 1000)}")
    rc, rw = ratio("dop853", ref="vines_full")
    print(f"  vines without the periodic shortcut vs DOP853 rtol 1e-10: {rc:6.0f}x ({rw:.0f}x)")
    print(f"  kernel cost without the shortcut : {c['vines_full'] / a['n'] * 1e6:6.2f} us/impact "
          f"(CPU)   target <= 1.0: {verdict(c['vines_full'] / a['n'] * 1e6 <= 1.0)}")
    print(f"  batch 1 -> 2 threads (wall)      : {sp:6.2f}x   target >= 1.8x: {verdict(sp >= 1.8)}; "
          f"identical results: {same}")


if __name__ == "__main__":
    main()
