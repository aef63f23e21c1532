"""Textbook ex. 4.1–4.4 for every matrix, not only for the scene's rotations: each identity
written for n × n matrices of independent symbols (n = 2, 3) and the difference of its two
sides expanded by SymPy into a polynomial, which must be 0 term by term (a proof for all
matrices of that size); each also checked numerically on random matrices, and ex. 4.4 on a
random invertible A(t) with d(A⁻¹)/dt by the complex step, which needs no formula for it.

Inverses enter without division: A⁻¹ = adj A / det A, so (AB)⁻¹ = B⁻¹A⁻¹ is the polynomial
identity adj(AB) = adj(B) adj(A) beside det(AB) = det A det B, and a similarity C = ABA⁻¹
is det(A) C = A B adj A.  Determinant and eigenvalues of a similar matrix (ex. 4.3(b), (c))
follow from the product rule det(XY) = det X det Y, proved here, applied to A(λ − B)A⁻¹.
Ex. 4.2(a)–(c), a basis that is not orthonormal, are stated in :mod:`.basis` and proved
here the same way; their numerical check is on a random basis of that kind.
"""

from __future__ import annotations

import numpy as np
import sympy

from .basis import non_orthonormal, relations


def _matrix(name: str, n: int, complex_entries: bool = False, kind: str = "") -> sympy.Matrix:
    """n × n symbols name_ij; ``kind`` "symmetric" or "antisymmetric" ties b_ji to b_ij."""
    def entry(i, j):
        if kind and i > j:
            return (1 if kind == "symmetric" else -1) * entry(j, i)
        if kind == "antisymmetric" and i == j:
            return sympy.Integer(0)
        if complex_entries:
            re, im = sympy.symbols(f"{name}r{i}{j} {name}i{i}{j}", real=True)
            return re + sympy.I * im
        return sympy.Symbol(f"{name}{i}{j}", real=True)
    return sympy.Matrix(n, n, entry)


def proved(left, right) -> bool:
    """Whether left − right (matrices or scalars) expands to exactly 0, entry by entry."""
    diff = left - right
    items = list(diff) if isinstance(diff, sympy.MatrixBase) else [diff]
    return all(sympy.expand(e) == 0 for e in items)


def _terms(*exprs) -> int:
    """Terms of the expanded expressions (matrices count each entry's)."""
    total = 0
    for e in exprs:
        for item in (list(e) if isinstance(e, sympy.MatrixBase) else [e]):
            total += len(sympy.Add.make_args(sympy.expand(item)))
    return total


def symbolic(n: int) -> dict[str, tuple[bool, int]]:
    """Each identity for n × n matrices (by key: those of
    :data:`reportgen.kinds.rotation.results.PROOF_KEYS`, stated in ``report_proofs``):
    (proved, terms), terms being those of its left side expanded."""
    A, B, C = (_matrix(x, n) for x in "abc")
    eye = sympy.eye(n)
    out = {}

    def record(key, left, right):
        out[key] = (proved(left, right), _terms(left))

    record("associative", A * (B * C), (A * B) * C)
    record("transpose", (A * B).T, B.T * A.T)
    record("determinant_product", (A * B).det(method="berkowitz"),
           A.det(method="berkowitz") * B.det(method="berkowitz"))
    record("inverse", (A * B).adjugate(), B.adjugate() * A.adjugate())
    Ac, Bc = _matrix("a", n, complex_entries=True), _matrix("b", n, complex_entries=True)
    record("hermitian", (Ac * Bc).H, Bc.H * Ac.H)
    for key, (left, right) in relations(n).items():  # ex. 4.2(a)–(c)
        record(key, left, right)
    V = sympy.Matrix(n, 1, lambda i, _: sympy.Symbol(f"v{i}", real=True))
    # V′ = AV, W = BV: W′ = AW = ABV; and A B adj(A) V′ = det(A) A B V, i.e. W′ = ABA⁻¹V′
    record("basis_change", A * B * A.adjugate() * (A * V), A.det(method="berkowitz") * A * B * V)
    record("trace", (A * B * A.adjugate()).trace(), A.det(method="berkowitz") * B.trace())
    for kind in ("symmetric", "antisymmetric"):
        S = _matrix("b", n, kind=kind)
        sign = 1 if kind == "symmetric" else -1
        record(kind, (A * S * A.T).T, sign * (A * S * A.T))
    # ex. 4.4 times det: d/dt(A adj A) = d/dt(det A · 1), entries and their rates as symbols
    t = sympy.Symbol("t", real=True)
    F = sympy.Matrix(n, n, lambda i, j: sympy.Function(f"a{i}{j}")(t))
    adj, det = F.adjugate(), F.det(method="berkowitz")
    record("derivative_of_inverse", F.diff(t) * adj + F * adj.diff(t), det.diff(t) * eye)
    return out


def numeric(n: int, seed: int) -> dict[str, float]:
    """The identities on random matrices (largest entry of the difference of the two sides,
    relative to the largest entry of either), and ex. 4.4 on a random invertible
    A(t) = A₀ + tA₁ + t²A₂ at five times, d(A⁻¹)/dt by the complex step (exact to rounding
    for a function analytic in t: no formula for the derivative of an inverse used)."""
    rng = np.random.default_rng(seed)
    A, B, C = (rng.normal(size=(n, n)) for _ in range(3))
    Ac, Bc = (rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n)) for _ in range(2))
    inv = np.linalg.inv

    def rel(left, right):
        left, right = np.asarray(left), np.asarray(right)
        return float(np.max(np.abs(left - right)) / max(np.max(np.abs(left)),
                                                           np.max(np.abs(right)), 1e-300))

    S, K = rng.normal(size=(n, n)), rng.normal(size=(n, n))
    S, K = S + S.T, K - K.T  # a symmetric and an antisymmetric B
    out = {
        "associative": rel(A @ (B @ C), (A @ B) @ C),
        "transpose": rel((A @ B).T, B.T @ A.T),
        "determinant_product": rel(np.linalg.det(A @ B), np.linalg.det(A) * np.linalg.det(B)),
        "inverse": rel(inv(A @ B), inv(B) @ inv(A)),
        "hermitian": rel((Ac @ Bc).conj().T, Bc.conj().T @ Ac.conj().T),
        "basis_change": rel(A @ (B @ C[:, 0]), (A @ B @ inv(A)) @ (A @ C[:, 0])),
        "trace": rel(np.trace(A @ B @ inv(A)), np.trace(B)),
        "symmetric": rel((A @ S @ A.T).T, A @ S @ A.T),
        "antisymmetric": rel((A @ K @ A.T).T, -(A @ K @ A.T)),
    }
    A0, A1, A2 = (rng.normal(size=(n, n)) for _ in range(3))
    A0 += n * np.eye(n)  # invertible on the times used
    h = 1e-30
    worst = 0.0
    for t in np.linspace(-0.5, 0.5, 5):
        At = A0 + t * A1 + t * t * A2
        rate = A1 + 2.0 * t * A2
        d_inverse = inv(A0 + (t + 1j * h) * A1 + (t + 1j * h) ** 2 * A2).imag / h
        worst = max(worst, rel(rate @ inv(At), -At @ d_inverse))
    out["derivative_of_inverse"] = worst
    out.update(non_orthonormal(n, seed)["errors"])  # ex. 4.2(a)–(c)
    return out


def prove(sizes, seed: int) -> dict:
    """The ``/analysis/proofs`` group: per size n, each identity proved (bool) and the terms
    of its expanded left side; the numerical checks' largest relative error as ``errors``;
    the random basis that is not orthonormal of ex. 4.2(a)–(c) as ``basis`` (its arrays
    and numbers with the suffix ``_n``)."""
    group: dict = {"sizes": np.asarray(sorted(set(sizes)), dtype=np.int64), "seed": seed,
                   "proved": {}, "terms": {}, "basis": {}}
    errors: dict[str, float] = {}
    for n in sorted(set(sizes)):
        for key, (proved, terms) in symbolic(n).items():
            group["proved"][f"{key}_{n}"] = bool(proved)
            group["terms"][f"{key}_{n}"] = int(terms)
        for key, error in numeric(n, seed).items():
            errors[f"{key}_{n}"] = error
        for key, value in non_orthonormal(n, seed).items():
            if key != "errors":
                group["basis"][f"{key}_{n}"] = value
    group["errors"] = errors
    return group
