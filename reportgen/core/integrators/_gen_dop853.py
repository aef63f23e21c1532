"""Write :mod:`._dop853_unrolled`: the DOP853 driver with its tableau written out.

The one template of DOP853's step: the stop tests, stages, error norm and step-size
controller (:func:`_attempt`), the interpolant (:func:`_dense_coefficients`,
:func:`_interpolate`) are written once here and generated into every DOP853 loop: the
shared driver (and its loop-vectorized twin, :mod:`.kernels`), the drivers compiled for
one model (:mod:`.specialized`), the ensemble's member
(:func:`reportgen.core.ensemble.dop853_member`), and through the shared driver the
fictitious-time runs (:mod:`.fictitious_time`).  Only :func:`.compiled.erk_adaptive`, the
driver of every other tableau, keeps its own loop (on the same compiled helpers).

``python -m reportgen.core.integrators._gen_dop853`` regenerates the module (a test
checks it is current).  The generated driver takes the same steps as
:func:`.compiled.erk_adaptive` with DOP853's tableau, bit for bit: every sum is the
generic driver's sum in the same order, with the tableau's zero terms left out (adding
``0.0 * k`` changes nothing for finite ``k``).  Written out, each stage is one loop over
the state whose body LLVM can keep in registers and vectorize, instead of a reduction
over the stages for each component: 1.5x fewer nanoseconds per step on the 6-state
heavy top (measured: 270 -> 178 us for the same 289 steps).

Every run ends as :func:`.compiled.erk_adaptive`'s does: ``max_steps`` counts attempted
steps, and the step-size test fails for a NaN step (see :mod:`.compiled`).
"""

from __future__ import annotations

from pathlib import Path

from . import _dop853_coefficients as c

TARGET = Path(__file__).with_name("_dop853_unrolled.py")
NST = c.N_STAGES


def _lit(x: float) -> str:
    return repr(float(x))


def _sum(coefs, rows, first: str | None = None) -> str:
    """``first + a_j * K[j, i] + ...`` over the nonzero a_j, in the order of ``rows``."""
    terms = [first] if first else []
    terms += [f"{_lit(a)} * K[{j}, i]" for a, j in zip(coefs, rows, strict=True) if a != 0.0]
    return " + ".join(terms) if terms else "0.0"


def _stage(s: int, ind: str, y: str, h: str, t: str) -> str:
    return (f"{ind}for i in range(d):\n"
            f"{ind}    ytmp[i] = {y}[i] + {h} * ({_sum(c.A[s, :s], range(s))})\n"
            f"{ind}rhs({t} + {_lit(c.C[s])} * {h}, ytmp, params, ftmp)\n"
            f"{ind}for i in range(d):\n"
            f"{ind}    K[{s}, i] = ftmp[i]\n")


def _extra_stages(ind: str) -> str:
    """The interpolant's three extra stages of the accepted step (t_old, t_old + hd]."""
    return "".join(_stage(s, ind, "y_old", "hd", "t_old") for s in range(NST + 1, c.A.shape[0]))


def _dense_coefficients(ind: str) -> str:
    """``hd``, the extra stages and the interpolant's coefficients ``F`` of the last
    accepted step (t_old, t] (Hairer's contd8), with their evaluations counted."""
    dense = "".join(f"{ind}    F[{3 + k}, i] = hd * ({_sum(c.D[k], range(c.D.shape[1]))})\n"
                    for k in range(c.D.shape[0]))
    return (f"{ind}hd = t - t_old\n"
            + _extra_stages(ind)
            + f"{ind}for i in range(d):\n"
            f"{ind}    dy = y[i] - y_old[i]\n"
            f"{ind}    F[0, i] = dy\n"
            f"{ind}    F[1, i] = hd * K[0, i] - dy\n"
            f"{ind}    F[2, i] = 2.0 * dy - hd * (K[{NST}, i] + K[0, i])\n"
            + dense
            + f"{ind}counters[0] += {c.A.shape[0] - NST - 1}\n")


def _interpolate(ind: str, target: str, out: str) -> str:
    """``out[i]`` = the interpolant of the last accepted step at time ``target`` (the
    nested form of :func:`.compiled.dense_eval`, the same operations)."""
    return (f"{ind}x = ({target} - t_old) / (t - t_old)\n"
            f"{ind}x1 = 1.0 - x\n"
            f"{ind}for i in range(d):\n"
            f"{ind}    {out} = x * (F[0, i] + x1 * (F[1, i] + x * (F[2, i] + x1 * (\n"
            f"{ind}        F[3, i] + x * (F[4, i] + x1 * (F[5, i] + x * F[6, i])))))) + y_old[i]\n")


def _attempt(ind: str) -> str:
    """The stop tests, then one attempt t -> t_new = t + h: stages, ``y_new``,
    ``f_new`` = f(t_new, y_new), the error norm ``err`` and the step ``factor`` (the
    step controller, in one place for every generated driver)."""
    main = "".join(_stage(s, ind, "y", "h", "t") for s in range(1, NST))
    e5 = _sum(c.E5[:NST], range(NST), first=f"{_lit(c.E5[NST])} * f_new[i]")
    e3 = _sum(c.E3[:NST], range(NST), first=f"{_lit(c.E3[NST])} * f_new[i]")
    text = f"""\
if counters[1] + counters[2] >= max_steps:
    status = MAXSTEPS
    break
if not (10.0 * EPS * max(abs(t), 1e-300) <= h < math.inf):
    status = stop_status(t + h, err)
    break
for i in range(d):
    K[0, i] = K[{NST}, i]
@MAIN@for i in range(d):
    y_new[i] = y[i] + h * ({_sum(c.B, range(NST))})
t_new = t + h
rhs(t_new, y_new, params, f_new)
counters[0] += {NST}
e5n = 0.0
e3n = 0.0
probe = 0.0
for i in range(d):
    scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
    probe += y_new[i] * 0.0
    e5 = ({e5}) / scale
    e3 = ({e3}) / scale
    e5n += e5 * e5
    e3n += e3 * e3
if e5n == 0.0 and e3n == 0.0:
    err = 0.0
else:
    err = h * e5n / math.sqrt((e5n + 0.01 * e3n) * d)
if not (math.isfinite(err) and probe == 0.0 and all_finite(f_new)):
    err = overflow_or_inf(probe, f_new)
factor = step_factor(err, err_exp, rejected)
"""
    lines = "".join(ind + line + "\n" for line in text.splitlines())
    return lines.replace(ind + "@MAIN@", main + ind)


def source(rhs_from: tuple[str, str] | None = None, dim: int | None = None,
           stamp: str = "") -> str:
    """The generic driver's module (``rhs`` its first argument, any dimension; with it
    the ensemble's member, :func:`_member`), or with ``rhs_from = (module, name)`` and
    ``dim`` a driver compiled for that one right-hand side (imported by name, so LLVM
    inlines it) and dimension (a constant, so the loops over the state unroll):
    :mod:`.specialized`.  ``stamp`` (a hash of the right-hand side's module) goes into the
    text, so a changed model never meets a stale cache."""
    if rhs_from is None:
        return (_GENERIC_HEAD + _body("rhs, ", "y.size", _GENERIC_FIRST_STEP)
                + "\n\n" + _member())
    module, name = rhs_from
    head = _SPECIAL_HEAD.format(module=module, name=name, dim=int(dim), stamp=stamp)
    return head + _body("", str(int(dim)), _SPECIAL_FIRST_STEP)


_GENERIC_HEAD = '''"""GENERATED by ``python -m reportgen.core.integrators._gen_dop853``; do not edit.

DOP853 (Hairer's dop853.f tableau, :mod:`._dop853_coefficients`) as one compiled driver
with the coefficients written out; same arguments and steps as
:func:`.compiled.erk_adaptive` with DOP853's tableau (see :mod:`._gen_dop853`).
"""

import math

import numba
import numpy as np

from .compiled import (
    EPS,
    MAXSTEPS,
    NONFINITE,
    OK,
    accept_step,
    all_finite,
    copy_into,
    crosses,
    initial_step,
    interpolant_root,
    overflow_or_inf,
    step_factor,
    stop_status,
)


'''


def _body(rhs_arg: str, dim: str, first_step: str) -> str:
    """The driver: ``rhs_arg`` ("rhs, " or "" when rhs is a global), the dimension ``dim``
    (``y.size`` or a constant) and how the first step is chosen (``first_step``)."""
    return f'''@numba.njit(cache=True)
def dop853_adaptive({rhs_arg}t_eval, i0, i1, Y, y, y_old, K, F, state, counters, params, rtol,
                    atol, max_steps):
    d = {dim}
    t = state[0]
    h = state[1]
    t_old = state[2]
    rejected = state[3] != 0.0
    dense_ready = state[4] != 0.0
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    y_new = np.empty(d)
    f_new = np.empty(d)
    span = t_eval[t_eval.size - 1] - t_eval[0]
    status = OK
    err_exp = {_lit(-1.0 / 8.0)}
    err = 0.0
    if h == 0.0:
        rhs(t, y, params, f_new)
        for i in range(d):
            K[{NST}, i] = f_new[i]
        counters[0] += 1
        if not all_finite(f_new):  # f(t0, y0) is not finite: no step can be chosen
            return NONFINITE
{first_step}        counters[0] += 1
        t_old = t
    j = i0
    while j < i1:
        while j < i1 and t_eval[j] <= t:
            if t_eval[j] == t:
                for i in range(d):
                    Y[j, i] = y[i]
            else:
                if not dense_ready:
{_dense_coefficients(" " * 20)}                    dense_ready = True
{_interpolate(" " * 16, "t_eval[j]", "Y[j, i]")}            j += 1
        if j >= i1:
            break
{_attempt(" " * 8)}        if err < 1.0:
            rejected = False
            counters[1] += 1
            t_old = t
            accept_step({NST}, y_old, y, y_new, K, f_new)
            t = t_new
            dense_ready = False
        else:
            counters[2] += 1
            rejected = True
        h *= factor
    state[0] = t
    state[1] = h
    state[2] = t_old
    state[3] = 1.0 if rejected else 0.0
    state[4] = 1.0 if dense_ready else 0.0
    return status
'''


def _member() -> str:
    """The ensemble's member (:mod:`reportgen.core.ensemble`): one run from ``t0`` to
    ``t_end`` with the driver's steps (:func:`_attempt`), the first zero crossings of one
    component located on the steps' interpolant, and outputs on a grid if asked."""
    return f'''@numba.njit(cache=True)
def dop853_member(rhs, y0, p, t0, t_end, rtol, atol, max_steps, comp, direction, terminal,
                  events, t_eval, Y, store, y_end, counters):
    """Integrate one member from ``y0`` at ``t0`` to ``t_end`` with DOP853.

    The steps are :func:`dop853_adaptive`'s with ``t_eval = [t0, ..., t_end]``: same
    initial step, error norm, controller and interpolant, so the states agree to the bit.
    After each accepted step (t_old, t]:

    * a zero crossing of ``y[comp]`` in ``direction`` (:func:`.compiled.crosses`) is
      located on the step's interpolant (:func:`.compiled.interpolant_root`) and its time
      appended to ``events`` until it is full (``terminal``: the member then stops);
    * if ``store``, the outputs ``Y[j]`` at ``t_eval[j]`` in (t_old, t] are filled.

    The interpolant's three extra stages are computed only for steps that need them.

    Parameters
    ----------
    p : (k,) the member's parameters (copied: callbacks get whole arrays).
    events : (max_events,) crossing times, written in order.
    t_eval, Y : (N,), (N, d) output grid in [t0, t_end] and its states (if ``store``).
    y_end : (d,) out: the state at ``t_end``; the last accepted state if the member
        stopped early (terminal events) or failed.
    counters : int64[3] out: (nfev, accepted steps, rejected steps), accumulated.

    Returns
    -------
    (status, number of events, time of ``y_end``)
    """
    d = y0.size
    n_out = t_eval.size if store else 0
    max_events = events.size
    y = np.empty(d)
    y_old = np.empty(d)
    y_new = np.empty(d)
    f_new = np.empty(d)
    ytmp = np.empty(d)
    ftmp = np.empty(d)
    params = np.empty(p.size)
    K = np.zeros(({c.A.shape[0]}, d))
    F = np.zeros(({c.D.shape[0] + 3}, d))
    copy_into(y, y0)
    copy_into(params, p)
    copy_into(y_end, y0)
    t = t0
    if not all_finite(y):
        return NONFINITE, 0, t
    rhs(t, y, params, f_new)
    for i in range(d):
        K[{NST}, i] = f_new[i]
    counters[0] += 1
    if not all_finite(f_new):
        return NONFINITE, 0, t
    h = initial_step(rhs, t, y, f_new, params, np.int64(8), rtol, atol, t_end - t0)
    counters[0] += 1
    t_old = t
    rejected = False
    err_exp = {_lit(-1.0 / 8.0)}
    err = 0.0
    n_ev = 0
    j = 0
    while j < n_out and t_eval[j] <= t:  # outputs at t0
        for i in range(d):
            Y[j, i] = y[i]
        j += 1
    status = OK
    while t < t_end:
{_attempt(" " * 8)}        h *= factor
        if err >= 1.0:
            counters[2] += 1
            rejected = True
            continue
        rejected = False
        counters[1] += 1
        t_old = t
        accept_step({NST}, y_old, y, y_new, K, f_new)
        t = t_new
        hit = n_ev < max_events and crosses(y_old[comp], y[comp], direction)
        if hit or t > t_end or (j < n_out and t_eval[j] < t):
{_dense_coefficients(" " * 12)}        if hit:
            xr = interpolant_root(F, y_old, comp, y_old[comp], y[comp])
            t_ev = t_old + xr * (t - t_old)
            if t_ev <= t_end:
                events[n_ev] = t_ev
                n_ev += 1
        while j < n_out and t_eval[j] <= t:
            if t_eval[j] == t:
                for i in range(d):
                    Y[j, i] = y[i]
            else:
{_interpolate(" " * 16, "t_eval[j]", "Y[j, i]")}            j += 1
        if terminal and 0 < max_events == n_ev and t < t_end:
            copy_into(y_end, y)
            return OK, n_ev, t
    if status != OK:
        copy_into(y_end, y)
        return status, n_ev, t
    if t == t_end:
        copy_into(y_end, y)
    else:
{_interpolate(" " * 8, "t_end", "y_end[i]")}    return OK, n_ev, t_end
'''

_SPECIAL_HEAD = '''"""GENERATED by reportgen.core.integrators.specialized; do not edit.

DOP853 compiled for one right-hand side, {module}.{name}, and dimension {dim}
(model module stamp {stamp}).
"""

import math

import numba
import numpy as np

from reportgen.core.integrators.compiled import (EPS, MAXSTEPS, NONFINITE, OK, accept_step,
                                                 all_finite, initial_choice, initial_guess,
                                                 overflow_or_inf, step_factor, stop_status)
from {module} import {name} as rhs


'''

# the order as an int64, not a literal 8: the same compiled initial_step as erk_adaptive's
# and the ensemble's (a literal argument is a separate specialization, compiled again)
_GENERIC_FIRST_STEP = """\
        h = initial_step(rhs, t, y, f_new, params, np.int64(8), rtol, atol, span)
"""
# rhs passed on to initial_step would be a dispatcher argument, which numba cannot cache
_SPECIAL_FIRST_STEP = """\
        h, f_norm = initial_guess(y, f_new, rtol, atol, span, ytmp, y_new)
        rhs(t + h, y_new, params, ftmp)
        h = initial_choice(f_new, ftmp, h, f_norm, ytmp, 8, span)
"""


if __name__ == "__main__":
    TARGET.write_text(source())
    print(f"wrote {TARGET}")
