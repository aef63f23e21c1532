"""``reportgen bench``: the Pythagorean three-body problem against REBOUND's IAS15, same run.

Burrau's problem (Szebehely & Peters 1967, AJ 72, 876): masses 3, 4, 5 at rest at the
vertices of a 3-4-5 triangle, G = 1, integrated to t = 70 through several close
encounters of the bodies of mass 4 and 5 (down to ~4e-4) until they form a binary and the
lightest body escapes.  Rows: our DOP853 on the Cartesian equations
(:mod:`.core.models.nbody`), DOP853 on the equations with that pair KS-regularized
(:mod:`.core.models.three_body_ks`, in physical and in fictitious time), and IAS15.

The energy error is measured in physical variables (positions and velocities) with the
same :func:`.core.models.nbody.energy` for every row.  The problem is chaotic: runs agree
on the final positions only to the accuracy that survives the encounters' amplification.

This is a benchmark, not a test: the numbers depend on the machine.
"""

from __future__ import annotations

import builtins

import numpy as np

from ..support.timing import best_time

G = 1.0
MASSES = (3.0, 4.0, 5.0)
#: each body opposite the side of its own length; the centre of mass is at the origin
POSITIONS = ((1.0, 3.0, 0.0), (-2.0, -1.0, 0.0), (1.0, -1.0, 0.0))
#: the pair with the close encounters (0-based: the bodies of mass 4 and 5)
CLOSE_PAIR = (1, 2)


def initial_state() -> np.ndarray:
    """Cartesian state (18,) of :mod:`.core.models.nbody`, in the centre-of-mass frame."""
    pos = np.asarray(POSITIONS)
    m = np.asarray(MASSES)
    pos = pos - m @ pos / m.sum()
    return np.concatenate([pos.ravel(), np.zeros(9)])


def _timed(run, repeats=3):
    """(min wall time of ``repeats`` calls of ``run``, the last result); warm up first."""
    run()
    return best_time(run, repeats)


def _energy_errors(y):
    from ..core.models import nbody

    e0 = nbody.energy(initial_state(), G, MASSES)[0]
    return np.abs(nbody.energy(y, G, MASSES) / e0 - 1.0)


def _row(method, y, final, wall, outputs_note=""):
    de = _energy_errors(y)
    return {"method": method, "error": float(np.max(de)),
            "error_end": float(_energy_errors(final[None, :])[0]), "wall_time_s": wall,
            "final": np.asarray(final, dtype=float), "outputs": outputs_note}


def cartesian_run(t, rtol):
    from ..core.integrators import integrate
    from ..core.models import nbody

    sol = integrate(nbody.model(G, MASSES), initial_state(), t, method="dop853", rtol=rtol,
                    atol=rtol * 1e-2)
    return sol.y


def ks_physical_time_run(t, rtol):
    """KS pair in physical time: outputs at the times ``t``; Cartesian states (N, 18)."""
    from ..core.integrators import integrate
    from ..core.models import three_body_ks as ks

    reg = ks.model(G, MASSES, CLOSE_PAIR, fictitious_time=False)
    z0 = ks.to_regularized(initial_state(), G, MASSES, CLOSE_PAIR, t=t[0])
    sol = integrate(reg, z0, t, method="dop853", rtol=rtol, atol=rtol * 1e-2)
    return ks.to_cartesian(reg, sol.y)[0]


def ks_fictitious_time_run(t_end, rtol, n_per_chunk=100, ds=None):
    """KS pair in fictitious time s (dt/ds = r of the pair).

    Outputs are uniform in s (``ds``; default: the output spacing of ``t_end/700`` at the
    initial separation), integrated chunk by chunk until t passes ``t_end``; then Newton
    steps in s from the last output before ``t_end`` land on it (|t − t_end| ≤ 1e-14 t_end).
    Returns (Cartesian states at the outputs, final Cartesian state at ``t_end``, the
    physical times of the outputs).
    """
    from ..core.integrators import integrate
    from ..core.models import three_body_ks as ks

    reg = ks.model(G, MASSES, CLOSE_PAIR)
    z = ks.to_regularized(initial_state(), G, MASSES, CLOSE_PAIR)
    r0 = float(z[:4] @ z[:4])
    ds = ds if ds is not None else t_end / 700 / r0
    grid = ds * np.arange(n_per_chunk + 1)
    chunks = [z[None, :]]
    while z[15] < t_end:
        sol = integrate(reg, z, grid, method="dop853", rtol=rtol, atol=rtol * 1e-2,
                        max_steps=10**8)
        if sol.status != "ok":
            raise RuntimeError(sol.message)
        chunks.append(sol.y[1:])
        z = sol.y[-1]
    states = np.concatenate(chunks)
    states = states[states[:, 15] <= t_end]
    base = z = states[-1]
    span = 0.0
    for _ in range(20):  # Newton on the span in s from the base state, always forward
        gap = t_end - z[15]
        if abs(gap) <= 1e-14 * t_end:
            break
        span += gap / float(z[:4] @ z[:4])  # dt/ds = r
        sol = integrate(reg, base, np.array([0.0, span]), method="dop853", rtol=rtol,
                        atol=rtol * 1e-2)
        z = sol.y[-1]
    cart, times = ks.to_cartesian(reg, states)
    return cart, ks.to_cartesian(reg, z[None, :])[0][0], times


def rebound_ias15_run(t):
    """IAS15 with exact_finish_time at the times ``t``; Cartesian states (N, 18)."""
    import rebound

    sim = rebound.Simulation()
    sim.G = G
    for m, p in zip(MASSES, POSITIONS, strict=True):
        sim.add(m=m, x=p[0], y=p[1], z=p[2])
    sim.integrator = "ias15"
    sim.move_to_com()
    y = np.empty((len(t), 2, 3, 3))  # time, (position, velocity), body, xyz
    for n, tt in enumerate(t):
        if n:
            sim.integrate(tt, exact_finish_time=1)
        sim.serialize_particle_data(xyz=y[n, 0], vxvyvz=y[n, 1])
    return y.reshape(len(t), 18)


def pythagorean_against_rebound(t_end=70.0, outputs=701, target=1e-13, repeats=3,
                                print=builtins.print) -> dict:
    """Energy error and wall time of our integrators and of REBOUND IAS15 (when installed)
    on the Pythagorean problem to ``t_end``, and the difference of their final positions.

    Rows: method, max |ΔE/E| over the outputs, |ΔE/E| at ``t_end``, wall time (min of
    ``repeats`` after a warm-up: compile excluded), final positions.  Returns ``{"rows":
    [...], "ias15": row or None, "met": [methods meeting the target faster than IAS15]}``.
    """
    t = np.linspace(0.0, t_end, outputs)
    rows = []
    for rtol in (1e-13, 1e-14):
        wall, y = _timed(lambda rtol=rtol: cartesian_run(t, rtol), repeats)
        rows.append(_row(f"dop853 rtol {rtol:.0e}", y, y[-1], wall))
    for rtol in (1e-15,):
        wall, y = _timed(lambda rtol=rtol: ks_physical_time_run(t, rtol), repeats)
        rows.append(_row(f"KS pair (t) dop853 rtol {rtol:.0e}", y, y[-1], wall))
    for rtol in (1e-14, 1e-15):
        wall, (y, final, times) = _timed(
            lambda rtol=rtol: ks_fictitious_time_run(t_end, rtol), repeats)
        rows.append(_row(f"KS pair (s) dop853 rtol {rtol:.0e}", y, final, wall,
                         f"{len(times)} outputs uniform in s"))
    try:
        import rebound  # noqa: F401
    except ImportError:
        print("  REBOUND not installed (pip install 'reportgen[rebound]'): no peer baseline")
        ias = None
    else:
        wall, y = _timed(lambda: rebound_ias15_run(t), repeats)
        ias = _row("REBOUND IAS15", y, y[-1], wall)
        rows.append(ias)
    print(f"Pythagorean three-body problem to t = {t_end:g}: |ΔE/E| max over {outputs} "
          f"outputs (uniform in t unless noted) and at the end; P2 target ≤ {target:.0e} in "
          "less time than IAS15; wall time = min of 3 after a warm-up")
    met = []
    for r in rows:
        line = (f"  {r['method']:<30} |ΔE/E| max {r['error']:.1e} end {r['error_end']:.1e} in "
                f"{r['wall_time_s'] * 1e3:7.2f} ms")
        if ias is not None:
            r["ias15_time_ratio"] = r["wall_time_s"] / ias["wall_time_s"]
            r["final_position_difference"] = float(np.max(np.abs(r["final"][:9]
                                                                 - ias["final"][:9])))
            line += (f" = {r['ias15_time_ratio']:5.2f}× IAS15's time, final positions "
                     f"differ from IAS15's by {r['final_position_difference']:.1e}")
            if r is not ias:
                ok = max(r["error"], r["error_end"]) <= target and r["ias15_time_ratio"] < 1
                line += f"; P2 {'met' if ok else 'not met'}"
                if ok:
                    met.append(r["method"])
        if r["outputs"]:
            line += f" ({r['outputs']})"
        print(line)
    if ias is not None:
        print(f"  P2 met by: {', '.join(met) if met else 'none'} (the problem is chaotic: "
              "final positions agree only to what the close encounters leave)")
    return {"rows": rows, "ias15": ias, "met": met}
