r"""Textbook ex. 4.2(a)–(c): components of a vector in a basis that is not orthonormal.

The exercise (its opening lines and the markers of parts (a)–(c) are lost in the text
extraction of the textbook; what survives defines the new basis and asks for part (d))
ties an orthonormal basis êᵢ to a basis e′ᵢ that is not orthonormal by
êᵢ = Σⱼ Aⱼᵢ e′ⱼ, A invertible.  Then

(a) e′ⱼ = Σᵢ (A⁻¹)ᵢⱼ êᵢ,   as Σᵢ (A⁻¹)ᵢⱼ êᵢ = Σₖ (A A⁻¹)ₖⱼ e′ₖ;
(b) V′ᵢ = Σⱼ Aᵢⱼ Vⱼ,       as V = Σⱼ Vⱼ êⱼ = Σᵢ (Σⱼ Aᵢⱼ Vⱼ) e′ᵢ and components in a
                           basis are unique;
(c) Vᵢ = Σⱼ (A⁻¹)ᵢⱼ V′ⱼ,   (b) solved for V.

:func:`relations` writes each as a polynomial identity (times det A, with A⁻¹ = adj A /
det A: no division) between the Cartesian components of n × n matrices of independent
symbols, for any two bases so related; :mod:`.proofs` expands them.
:func:`non_orthonormal` builds one random basis e′ that is not orthonormal and checks the
three relations against what the geometry alone gives: the components V′ from the Gram
equations G V′ = (e′ᵢ · V), G = (e′ᵢ · e′ⱼ), and e′ from the defining relation by an LU
solve.

References
----------
Textbook pp. 119–120, exercise 4.2 (part (d) is proved in :mod:`.proofs`).
"""

from __future__ import annotations

import numpy as np
import sympy

#: the three relations, by the keys :data:`.results.PROOF_STATEMENTS` gives them
RELATIONS = ("basis_vectors", "components", "components_back")
#: a random A is drawn again until its condition number is below this: the relations'
#: residuals then stay a few rounding units
CONDITION_BELOW = 20.0


def _symbols(name: str, rows: int, cols: int) -> sympy.Matrix:
    return sympy.Matrix(rows, cols, lambda i, j: sympy.Symbol(f"{name}{i}{j}", real=True))


def relations(n: int) -> dict[str, tuple[sympy.Matrix, sympy.Matrix]]:
    """(left, right) of each relation of :data:`RELATIONS` for n × n symbols: the columns
    of P are any basis e′ⱼ (Cartesian components), A any n × n matrix, and the columns
    of H the êᵢ = Σⱼ Aⱼᵢ e′ⱼ written out; v and w the components V and V′.

    * (a), times det A: Σᵢ adj(A)ᵢⱼ êᵢ = det A e′ⱼ, i.e. H adj A = det A P;
    * (b): Σᵢ (Σⱼ Aᵢⱼ Vⱼ) e′ᵢ = Σⱼ Vⱼ êⱼ, i.e. P (A v) = H v;
    * (c), times det A: with V = Σⱼ V′ⱼ e′ⱼ, Σᵢ (adj A w)ᵢ êᵢ = det A V, i.e.
      H (adj A w) = det A P w.
    """
    P, A = _symbols("p", n, n), _symbols("a", n, n)
    H = sympy.Matrix(n, n, lambda k, i: sum(A[j, i] * P[k, j] for j in range(n)))
    v, w = _symbols("v", n, 1), _symbols("w", n, 1)
    det, adj = A.det(method="berkowitz"), A.adjugate()
    return {"basis_vectors": (H * adj, det * P),
            "components": (P * (A * v), H * v),
            "components_back": (H * (adj * w), det * (P * w))}


def _relative(left, right) -> float:
    """Largest entry of left − right over the largest entry of either."""
    left, right = np.asarray(left, dtype=float), np.asarray(right, dtype=float)
    return float(np.max(np.abs(left - right))
                 / max(np.max(np.abs(left)), np.max(np.abs(right)), 1e-300))


def _orthonormal(rng, n: int) -> np.ndarray:
    """A random right-handed orthonormal basis (columns): Q of the QR factors of a normal
    matrix, its columns' signs fixed by R's diagonal."""
    Q, R = np.linalg.qr(rng.normal(size=(n, n)))
    Q = Q * np.sign(np.diag(R))
    if np.linalg.det(Q) < 0:
        Q[:, 0] = -Q[:, 0]
    return Q


def on_basis(hat, A, V) -> dict:
    """The relations (a)–(c) on one basis: ``hat`` (n, n) the orthonormal êᵢ (columns),
    ``A`` (n, n) invertible, ``V`` (n,) a vector (Cartesian components).

    Returns ``hat``, ``matrix`` A, ``prime`` (columns e′ⱼ solved from êᵢ = Σⱼ Aⱼᵢ e′ⱼ,
    i.e. Aᵀ e′ᵀ = êᵀ), ``gram`` G = (e′ᵢ · e′ⱼ) and ``gram_distance`` max |G − 1| (0 for
    an orthonormal basis), ``condition`` (of A, 2-norm), ``vector`` V, its ``components``
    Vᵢ = êᵢ · V, its ``components_prime`` V′ solving G V′ = (e′ᵢ · V), the ``projections``
    e′ᵢ · V (which are not the V′ᵢ for a basis that is not orthonormal) and
    ``projection_gap``, their largest distance from V′ relative to the largest entry; and
    ``errors`` by relation (relative to the largest entry compared):

    * basis_vectors: max of |e′A − ê| (the definition) and |êᵀe′ − A⁻¹| (with ê
      orthonormal, (a) says (A⁻¹)ᵢⱼ = êᵢ · e′ⱼ);
    * components: |V′ − A V| and |Σᵢ V′ᵢ e′ᵢ − V| (b);
    * components_back: |V − A⁻¹ V′| (c).
    """
    hat, A, V = (np.asarray(x, dtype=float) for x in (hat, A, V))
    n = len(V)
    prime = np.linalg.solve(A.T, hat.T).T
    gram = prime.T @ prime
    components = hat.T @ V
    projections = prime.T @ V
    components_prime = np.linalg.solve(gram, projections)
    A_inv = np.linalg.inv(A)
    errors = {
        "basis_vectors": max(_relative(prime @ A, hat), _relative(hat.T @ prime, A_inv)),
        "components": max(_relative(components_prime, A @ components),
                          _relative(prime @ components_prime, V)),
        "components_back": _relative(components, A_inv @ components_prime),
    }
    return {"hat": hat, "matrix": A, "prime": prime, "gram": gram,
            "gram_distance": float(np.max(np.abs(gram - np.eye(n)))),
            "condition": float(np.linalg.cond(A)), "vector": V, "components": components,
            "components_prime": components_prime, "projections": projections,
            "projection_gap": _relative(projections, components_prime), "errors": errors}


def non_orthonormal(n: int, seed: int) -> dict:
    """:func:`on_basis` for a random n × n case (generator seeded by (seed, n)): ê a
    random right-handed orthonormal basis, A a normal random matrix drawn again until its
    condition number is below :data:`CONDITION_BELOW`, V normal random.  Such an A is not
    orthogonal, so e′ is not orthonormal (``gram_distance`` tells how far)."""
    rng = np.random.default_rng((seed, n))
    hat = _orthonormal(rng, n)
    A = rng.normal(size=(n, n))
    while np.linalg.cond(A) >= CONDITION_BELOW:
        A = rng.normal(size=(n, n))
    return on_basis(hat, A, rng.normal(size=n))
