"""``rotation`` report, the proofs section: textbook ex. 4.1–4.4 for all 2 × 2 and 3 × 3
matrices (SymPy expanded each difference to 0) and on random ones; from ``/analysis/proofs``
alone (the statements are :data:`reportgen.kinds.rotation.proofs.IDENTITIES`, repeated here
so that the report imports no SymPy)."""

from __future__ import annotations

from ...scene.content import SectionContent, Table, fmt_err

#: (key, exercise, statement) as proofs.IDENTITIES
STATEMENTS = (
    ("associative", "4.1(a)", "associative: A(BC) = (AB)C"),
    ("transpose", "4.1(b)", "transpose of a product: (AB)ᵀ = BᵀAᵀ"),
    ("determinant_product", "4.1(c)", "the inverse of AB exists with A⁻¹ and B⁻¹: "
                                      "det(AB) = det A det B"),
    ("inverse", "4.1(c)", "inverse of a product: (AB)⁻¹ = B⁻¹A⁻¹, as adj(AB) = adj(B) adj(A)"),
    ("hermitian", "4.1(d)", "hermitian conjugate, complex entries: (AB)† = B†A†"),
    ("basis_change", "4.2(d)", "change of basis: W = BV and V′ = AV give W′ = ABA⁻¹V′"),
    ("trace", "4.3(a)", "trace: tr(ABA⁻¹) = tr B"),
    ("symmetric", "4.3(d)", "symmetric B = Bᵀ stays symmetric: (ABAᵀ)ᵀ = ABAᵀ (Aᵀ = A⁻¹ for "
                            "an orthogonal A)"),
    ("antisymmetric", "4.3(d)", "antisymmetric B = −Bᵀ stays antisymmetric: (ABAᵀ)ᵀ = −ABAᵀ"),
    ("derivative_of_inverse", "4.4", "derivative of the inverse: Ȧ A⁻¹ = −A dA⁻¹/dt"),
)


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
        for key, exercise, statement in STATEMENTS:
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
        return SectionContent(facts=facts, tables=[table], notes=notes)
