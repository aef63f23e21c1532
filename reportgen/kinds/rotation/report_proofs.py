"""``rotation`` report, the proofs section: textbook ex. 4.1–4.4 for all 2 × 2 and 3 × 3
matrices (SymPy expanded each difference to 0) and on random ones, from ``/analysis/proofs``
alone; and R(t) rebuilt from ω(t) by the time-ordered exponential of notes (8.36)–(8.37),
from ``/analysis/euler/time_ordered`` (the angular-velocity section's tables)."""

from __future__ import annotations

from ...scene.content import SectionContent, Table, fmt, fmt_err
from .results import CONTRAST, PROOF_STATEMENTS, TOLERANCE


def _cell(group, key: str, n: int) -> str:
    """"proved (N terms)" when SymPy expanded the difference to 0, else "not proved"."""
    name = f"{key}_{n}"
    if name not in group["proved"]:
        return "—"
    if not bool(group["proved"][name]):
        return "not proved"
    return f"proved ({int(group['terms'][name])} terms)"


class ProofsSection:
    """The proofs section (mixed into :class:`.report.RotationReport`)."""

    @classmethod
    def section_matrix_proofs(cls, data):
        g = data.analysis["proofs"]
        sizes = [int(n) for n in g["sizes"]]
        rows = []
        for key, exercise, statement in PROOF_STATEMENTS:
            errors = [float(g["errors"][f"{key}_{n}"]) for n in sizes
                      if f"{key}_{n}" in g["errors"]]
            rows.append([f"{statement} (textbook ex. {exercise})", *(_cell(g, key, n) for n in sizes),
                         fmt_err(max(errors)) if errors else "—"])
        table = Table(
            caption="Each identity of textbook ex. 4.1–4.4 for n × n matrices of independent "
                    "symbols: the difference of its two sides expanded by SymPy (proved: "
                    "every term cancels; the count is that of the left side's terms), and the "
                    "largest relative error on random matrices (for the derivative of the "
                    "inverse, textbook ex. 4.4: a random invertible A(t), dA⁻¹/dt by the "
                    "complex step)",
            header=["identity (exercise)", *(f"{n} × {n}" for n in sizes),
                    "random matrices"], rows=rows)
        every = all(bool(v) for v in g["proved"].values())
        facts = [("identities proved for every size asked",
                  f"{sum(bool(v) for v in g['proved'].values())} of {len(g['proved'])}"),
                 ("largest error on random matrices",
                  fmt_err(max(float(v) for v in g["errors"].values())))]
        notes = []
        if every and bool(g["proved"].get(f"determinant_product_{sizes[-1]}", False)):
            notes.append("With the product rule det(XY) = det X det Y proved, textbook ex. "
                         "4.3(b) and (c) follow for any invertible A: the determinant, "
                         "det(ABA⁻¹) = det A det B det A⁻¹ = det B, and the eigenvalues, as "
                         "det(λ − ABA⁻¹) = det(A(λ − B)A⁻¹) = det(λ − B): similar matrices have "
                         "the same characteristic polynomial.")
        return SectionContent(facts=facts, tables=[table, *basis_tables(g, sizes)], notes=notes)


#: textbook ex. 4.2(a)–(c) on the random basis: (key of ``errors``, the row's words)
BASIS_ROWS = (
    ("basis_vectors", "textbook ex. 4.2(a): the basis e′ solved from êᵢ = Σⱼ Aⱼᵢ e′ⱼ, and "
                      "êᵢ · e′ⱼ = (A⁻¹)ᵢⱼ"),
    ("components", "textbook ex. 4.2(b): the components V′ from the Gram equations "
                   "G V′ = (e′ᵢ · V) against AV, and Σᵢ V′ᵢ e′ᵢ against V"),
    ("components_back", "textbook ex. 4.2(c): the components Vᵢ = êᵢ · V against A⁻¹V′"),
)


def basis_tables(g, sizes) -> list[Table]:
    """Textbook ex. 4.2(a)–(c) on a random basis that is not orthonormal, one column per
    size (``/analysis/proofs/basis``; none for an archive without it)."""
    b = g.get("basis")
    shown = [n for n in sizes if b is not None and f"gram_distance_{n}" in b]
    if not shown:
        return []
    gram = [float(b[f"gram_distance_{n}"]) for n in shown]
    gap = [float(b[f"projection_gap_{n}"]) for n in shown]
    errors = [float(g["errors"][f"{key}_{n}"]) for key, _ in BASIS_ROWS for n in shown]
    failed = sum(1 for e in errors if not e <= TOLERANCE)
    held = (f"all {len(errors)} checks of textbook ex. 4.2(a)–(c) on the basis e′ hold"
            if not failed else
            f"{failed} of {len(errors)} checks of textbook ex. 4.2(a)–(c) on the basis e′ fail")
    orthonormal = ("e′ is not orthonormal, its Gram matrix not 1" if min(gram) > CONTRAST else
                   "e′ is orthonormal here to 10⁻⁹" if max(gram) <= CONTRAST else
                   "e′ is orthonormal here to 10⁻⁹ for some size")
    projections = ("the projections e′ᵢ · V are not the components V′ᵢ" if min(gap) > CONTRAST
                   else "the projections e′ᵢ · V are the components V′ᵢ here" if max(gap) <= CONTRAST
                   else "the projections e′ᵢ · V are the components V′ᵢ here for some size")
    rows = [["max |G − 1|, G = (e′ᵢ · e′ⱼ) the Gram matrix of the basis e′ (0 when "
             "orthonormal)", *(fmt(x, 3) for x in gram)],
            ["condition number of A", *(fmt(float(b[f"condition_{n}"]), 3) for n in shown)],
            *([words, *(fmt_err(float(g["errors"][f"{key}_{n}"])) for n in shown)]
              for key, words in BASIS_ROWS),
            ["the projections e′ᵢ · V against the components V′ᵢ (not a check)",
             *(fmt(x, 3) for x in gap)]]
    return [Table(
        caption=f"A random basis e′ for each size (seed {int(g['seed'])}): êᵢ a random "
                "orthonormal basis, A a random matrix with condition number below 20 and "
                f"e′ solved from êᵢ = Σⱼ Aⱼᵢ e′ⱼ; {orthonormal}, "
                f"{projections}. Largest relative errors against the bound "
                f"{fmt(TOLERANCE)}: {held}.",
        header=["", *(f"{n} × {n}" for n in shown)], rows=rows)]


def time_ordered_tables(a) -> list[Table]:
    """R(t_end) rebuilt from ω(t) by the series (8.37) and by Magnus's method, each against
    the Euler matrix (an empty list for an archive without them)."""
    k = a.get("time_ordered")
    if k is None:
        return []
    orders, err, term, bound = (k[n] for n in ("orders", "series_error", "series_term",
                                                "series_bound"))
    shown = [i for i in range(len(orders)) if int(orders[i]) in (1, 2, 4) or
             int(orders[i]) % 8 == 0]
    series = Table(
        caption="R(t) rebuilt from ω(t) alone, notes (8.36)–(8.37): the partial sums S_K of "
                "the time-ordered exponential's series at the end of the path, against the "
                "Euler matrix there (largest entry of the difference), with the largest entry "
                "of the K-th term and the bound (|ω|t)ᴷ⁺¹/(K + 1)! of the terms left out",
        header=["order K", "max |S_K R(0) − R(t)|", "largest entry of term K",
                "(|ω|t)ᴷ⁺¹/(K + 1)!"],
        rows=[[str(int(orders[i])), fmt_err(float(err[i])), fmt(float(term[i]), 3),
               fmt_err(float(bound[i]))] for i in shown])
    steps, magnus = k["magnus_steps"], k["magnus_error"]
    stepping = Table(
        caption="The same by Magnus's fourth-order method, an exact rotation per step: the "
                "error at the end against the number of steps",
        header=["steps", "max |R − R(t)|"],
        rows=[[str(int(n)), fmt_err(float(e))] for n, e in zip(steps, magnus, strict=True)])
    return [series, stepping]


def time_ordered_notes(a) -> list[str]:
    """What the two rebuilds show, in words chosen by their stored numbers."""
    k = a.get("time_ordered")
    if k is None:
        return []
    best, largest = float(k["series_best"]), float(k["series_largest_term"])
    text = (f"Summed to order {int(k['orders'][-1])}, the series of the time-ordered "
            f"exponential, notes (8.37), reaches "
            f"R(t) to {fmt_err(best)} here (|ω|t = {fmt(float(k['omega_t']), 3)}); ")
    text += (f"its terms first grow to {fmt(largest, 3)}, and the digits lost in their "
             "cancellation set that floor." if largest > 10.0 else
             "its terms never grow past order one, so nothing is lost to cancellation.")
    order = float(k["magnus_order"])
    if order == order:  # not NaN
        fourth = abs(order - 4.0) <= 0.2
        text += (f" Magnus's method converges at order {fmt(order, 3)} ("
                 + ("fourth, as it should" if fourth else "not the fourth it should") + ").")
    return [text]
