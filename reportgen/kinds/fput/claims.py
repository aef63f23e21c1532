"""The claim-carrying sentences of an ``fput`` report and what makes each true
(:mod:`reportgen.scene.claims`).

Every predicate measures again from the archived trajectory (positions and momenta of the
2m masses) and the archived config (m, ω), not from the stored classification that chose
the words: the oscillatory energies Iⱼ = ½(y₁ⱼ² + ω²x₁ⱼ²) (GNI eq. I.5.3), where they start,
whether the spring that starts with them hands them on, the soft springs' frequency and the
adiabatic invariant's excursion.  Imported only by the claims registry.
"""

from __future__ import annotations

import math

import numpy as np

from ...scene.claims import claim
from .config import AT_REST, EXCHANGE_SHARE, ORDER_ONE, STIFF_RATIO


def _measured(data) -> dict:
    """The chain's energies and time scales, from the archived run and config alone."""
    run = data.runs["main"]
    m, omega = int(data.config["params"]["m"]), float(data.config["params"]["omega"])
    y = np.asarray(run.y, dtype=float)
    q, p = y[:, :2 * m], y[:, 2 * m:]
    x1 = (q[:, 1::2] - q[:, 0::2]) / math.sqrt(2.0)
    y1 = (p[:, 1::2] - p[:, 0::2]) / math.sqrt(2.0)
    energies = 0.5 * (y1**2 + omega**2 * x1**2)
    total = energies.sum(axis=1)
    padded = np.pad(q, ((0, 0), (1, 1)))
    soft = padded[:, 1::2] - padded[:, 0::2]
    h0 = 0.5 * float(np.sum(p[0]**2)) + 0.25 * omega**2 * float(np.sum((q[0, 1::2]
                                                                        - q[0, 0::2])**2)) \
        + float(np.sum(soft[0]**4))
    first = int(np.argmax(energies[0]))
    return {"m": m, "omega": omega, "energies": energies, "total": total, "first": first,
            "at_rest": bool(total[0] <= AT_REST * max(abs(h0), 1e-300)),
            "share": float(energies[0, first] / total[0]) if total[0] > 0 else math.nan,
            "ratio": omega / max(math.sqrt(24.0 * float(np.mean(soft**2))), 1e-300),
            "excursion": (omega * float(np.max(np.abs(total - total[0]))) / total[0]
                          if total[0] > 0 else math.nan)}


@claim("fput: stiff springs at rest", r"the stiff springs start at rest")
def at_rest(data) -> bool | str:
    """the stiff springs' oscillatory energy is zero at t = 0"""
    got = _measured(data)
    if not got["at_rest"]:
        return f"I(0) = {got['total'][0]:.3g}: the stiff springs are moving"
    return True


@claim("fput: a single stiff spring",
       r"one stiff spring, which holds all|there is a single stiff spring")
def single(data) -> bool | str:
    """the archived chain has one stiff spring (two masses)"""
    if _measured(data)["m"] != 1:
        return f"the chain has {_measured(data)['m']} stiff springs"
    return True


@claim("fput: energy starts in one spring",
       r"the energy put into stiff spring \d+|the energy starts in stiff spring \d+")
def concentrated(data) -> bool | str:
    """the spring holding most of I(0) holds at least EXCHANGE_SHARE of it, and the report
    names that spring"""
    got = _measured(data)
    if got["at_rest"] or not got["share"] >= EXCHANGE_SHARE:
        return f"the largest share of I(0) is {got['share']:.3g}"
    if int(data.analysis["first_spring"]) != got["first"] + 1:
        return f"spring {got['first'] + 1} holds most of I(0)"
    return True


@claim("fput: energy starts spread",
       r"the oscillatory energy starts spread|the energy starts spread over the stiff springs")
def spread(data) -> bool | str:
    """no spring holds EXCHANGE_SHARE of I(0)"""
    got = _measured(data)
    if got["at_rest"] or got["share"] >= EXCHANGE_SHARE:
        return f"spring {got['first'] + 1} holds {got['share']:.3g} of I(0)"
    return True


@claim("fput: energy handed on",
       r"is handed on from t ≈|is handed on to the others|hands its energy on")
def handed_on(data) -> bool | str:
    """the spring that starts with the energy holds less than EXCHANGE_SHARE of I at some
    archived sample, at the archived exchange time first"""
    got = _measured(data)
    j = got["first"]
    below = got["energies"][:, j] < EXCHANGE_SHARE * got["total"]
    if got["at_rest"] or not np.any(below):
        return f"spring {j + 1} keeps at least {EXCHANGE_SHARE:.0%} of I over the run"
    t = float(np.asarray(data.runs["main"].t)[int(np.argmax(below))])
    if not math.isclose(t, float(data.analysis["exchange_time"]), rel_tol=1e-12,
                        abs_tol=1e-12):
        return f"spring {j + 1} first drops below {EXCHANGE_SHARE:.0%} at t = {t:.6g}"
    return True


@claim("fput: energy stays", r"stays there over the run|over this run it is not handed on")
def stays(data) -> bool | str:
    """the spring that starts with the energy keeps at least EXCHANGE_SHARE of I at every
    archived sample"""
    got = _measured(data)
    j = got["first"]
    low = float(np.min(got["energies"][:, j] / got["total"]))
    if low < EXCHANGE_SHARE:
        return f"spring {j + 1} falls to {low:.3g} of I"
    return True


@claim("fput: two time scales",
       r"two time\s+scales\)|force explicit methods to\s+resolve the period")
def two_time_scales(data) -> bool | str:
    """ω is at least STIFF_RATIO times the soft springs' typical frequency √(24⟨Δ²⟩),
    measured on the archived positions"""
    ratio = _measured(data)["ratio"]
    if ratio < STIFF_RATIO:
        return f"ω is {ratio:.3g} times the soft springs' frequency"
    return True


@claim("fput: comparable time scales",
       r"comparable time scales|ω is not large\s+against the soft springs")
def comparable(data) -> bool | str:
    """ω is below STIFF_RATIO times the soft springs' typical frequency"""
    ratio = _measured(data)["ratio"]
    if ratio >= STIFF_RATIO:
        return f"ω is {ratio:.3g} times the soft springs' frequency"
    return True


@claim("fput: adiabatic excursion of order one",
       r"is of order one or\s+less|this stays of order one here")
def order_one(data) -> bool | str:
    """ω·max|I − I(0)|/I(0), from the archived trajectory, is below ORDER_ONE"""
    excursion = _measured(data)["excursion"]
    if not excursion < ORDER_ONE:
        return f"ω·max|I − I(0)|/I(0) = {excursion:.3g}"
    return True


@claim("fput: adiabatic excursion beyond order one",
       r"larger than order one|grows beyond order one here")
def beyond_order_one(data) -> bool | str:
    """ω·max|I − I(0)|/I(0), from the archived trajectory, is at least ORDER_ONE"""
    excursion = _measured(data)["excursion"]
    if not excursion >= ORDER_ONE:
        return f"ω·max|I − I(0)|/I(0) = {excursion:.3g}"
    return True
