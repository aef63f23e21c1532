"""Which study rows are peers' (scipy's solvers, heyoka), and ours against a peer at
matched error.  Plain data, no integrator: the report reads it from the archive's study
table (:mod:`reportgen.core.study` makes the rows; ``reportgen bench`` prints the
comparison)."""

from __future__ import annotations

#: statuses of a row whose error and time were measured (an inaccurate run's error is
#: large, not unknown)
MEASURED = ("ok", "inaccurate")


def study_rows(records) -> list[dict]:
    """A study table (the structured records of ``/study/error_vs_runtime``) as a list of
    plain dicts, its byte fields decoded."""
    def plain(value):
        value = value.item() if hasattr(value, "item") else value
        return value.decode("utf-8") if isinstance(value, bytes) else value

    return [{name: plain(r[name]) for name in records.dtype.names} for r in records]


def is_peer(method: str) -> bool:
    """Whether the study rows of ``method`` are a peer's, not ours: scipy's solve_ivp
    methods and heyoka (the registry's ``peer`` flag; a test holds the two equal)."""
    method = str(method)
    return method.startswith("scipy_") or method == "heyoka"


#: the errors over which ``reportgen bench`` compares us with heyoka (issue 34: "at each
#: error it reaches from 1e-6 to 1e-13")
PEER_ERROR_RANGE = (1e-13, 1e-6)


def against_peer(rows, peer: str = "heyoka", error_range=PEER_ERROR_RANGE) -> list[dict]:
    """Each measured run of ``peer`` whose max error lies in ``error_range``, beside our
    fastest run at least as accurate (None when none is): one dict per peer run with
    ``tolerance``, ``error_max``, ``wall_time_s``, ``compile_time_s`` (the peer's), then
    ``ours`` (our row: method, label, tolerance, h, error_max, wall_time_s) and
    ``ratio`` = the peer's time / ours (> 1: we are faster; 0 when none of ours reaches
    the error).  "Ours" are the rows of methods that are not peers (the registry's and a
    kind's own, as in :func:`reportgen.core.study.matched_error_speedup`)."""
    rows = getattr(rows, "rows", rows)  # a StudyResult or its rows
    lo, hi = error_range
    ours = [r for r in rows if r["status"] in MEASURED and not is_peer(r["method"])]
    out = []
    for p in rows:
        if p["method"] != peer or p["status"] not in MEASURED:
            continue
        if not lo <= p["error_max"] <= hi:
            continue
        good = [r for r in ours if r["error_max"] <= p["error_max"]]
        best = min(good, key=lambda r: r["wall_time_s"], default=None)
        entry = {key: p[key] for key in ("tolerance", "error_max", "wall_time_s",
                                         "compile_time_s")}
        entry["ours"] = None if best is None else {
            key: best[key] for key in ("method", "label", "tolerance", "h", "error_max",
                                       "wall_time_s")}
        entry["ratio"] = 0.0 if best is None else p["wall_time_s"] / best["wall_time_s"]
        out.append(entry)
    return out


def compared_range(reference_agreement: float = float("nan")) -> tuple[float, float]:
    """:data:`PEER_ERROR_RANGE`, its low end raised to twice the disagreement of the study's
    two reference runs where they are runs (NaN: a closed form): below it an error
    measures the reference as much as the method."""
    lo, hi = PEER_ERROR_RANGE
    if reference_agreement == reference_agreement:  # not NaN
        lo = max(lo, 2.0 * float(reference_agreement))
    return lo, hi
