"""Names as symbols: a formula system's config names its coordinates, momenta (p_<q>),
observables and constants with identifiers; its report and figures show them as the
symbols they stand for.  One reading of a name, three spellings: TeX (figures' mathtext,
typeset equations and table cells), Unicode text (titles, captions) and words (a momentum
is "the momentum conjugate to q").

Reading: ``theta`` -> θ; trailing digits index (``theta1`` -> θ₁, ``m2`` -> m₂); what
follows the first ``_`` is a subscript, itself a name (``p_phi`` -> p_φ, ``A_xx`` ->
A_xx); a capital letter and x, y or z is a component (``Lz`` -> L_z); ``<q>_dot`` -> q̇.
"""

from __future__ import annotations

import re
import unicodedata

#: Greek letters by their names, as a config spells them
GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ",
         "eta": "η", "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ",
         "nu": "ν", "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ",
         "upsilon": "υ", "phi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω", "Gamma": "Γ",
         "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ",
         "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω"}
#: the characters Unicode has a subscript of (no b, c, d, f, g, q, w, y, z, nor θ)
_SUBSCRIPTS = str.maketrans("0123456789,aehijklmnoprstuvxβγρφχ",
                            "₀₁₂₃₄₅₆₇₈₉,ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓᵦᵧᵨᵩᵪ")
_REPRESENTABLE = frozenset("0123456789,aehijklmnoprstuvxβγρφχ")


def symbol_parts(name: str) -> tuple[str, list[str], bool]:
    """A config name read as a symbol: (its letter or word, its subscripts -- each a
    name or an index --, whether it carries a dot): ``p_theta1`` -> ("p", ["theta1"],
    False), ``theta1`` -> ("theta", ["1"], False), ``Lz`` -> ("L", ["z"], False),
    ``a_dot`` -> ("a", [], True)."""
    dot = name.endswith("_dot") and len(name) > len("_dot")
    if dot:
        name = name[:-len("_dot")]
    head, _, tail = name.partition("_")
    subs = []
    indexed = re.fullmatch(r"([A-Za-z]+?)(\d+)", head)
    if indexed and (indexed.group(1) in GREEK or len(indexed.group(1)) == 1):
        head, subs = indexed.group(1), [indexed.group(2)]
    elif re.fullmatch(r"[A-Z][xyz]", head):  # a vector's component: Lx, Lz
        head, subs = head[0], [head[1]]
    return head, subs + ([tail] if tail else []), dot


def symbol_tex(name: str, index: bool = False) -> str:
    """A config name as TeX for mathtext: ``p_phi`` -> ``p_{\\phi}``, ``A_xx`` ->
    ``A_{xx}``, ``Lz`` -> ``L_{z}``, ``theta1`` -> ``\\theta_{1}``, ``energy`` ->
    ``\\mathrm{energy}`` (a word; in a subscript, ``index``, letters are indices)."""
    head, subs, dot = symbol_parts(name)
    tex = (f"\\{head}" if head in GREEK else head if len(head) == 1 or index
           else f"\\mathrm{{{head}}}")
    if dot:
        tex = f"\\dot{{{tex}}}"
    if subs:
        tex += "_{" + ",".join(s if s.isdigit() else symbol_tex(s, True) for s in subs) + "}"
    return tex


def symbol_text(name: str) -> str:
    """A config name as plain Unicode, for text that cannot be typeset (a title, a
    caption): ``theta1`` -> θ₁, ``p_phi`` -> pᵩ, ``Lx`` -> Lₓ, ``a_dot`` -> ȧ; a subscript
    Unicode has no letters for stays behind an underscore (``p_y``), so prose should
    say such a symbol in words (:func:`symbol_words`) or typeset it."""
    head, subs, dot = symbol_parts(name)
    # the dot composed where Unicode has the letter (ȧ): a PDF font may lack the combining one
    text = unicodedata.normalize("NFC", GREEK.get(head, head) + ("\u0307" if dot else ""))
    if not subs:
        return text
    sub = ",".join(s if s.isdigit() else symbol_text(s) for s in subs)
    return text + (sub.translate(_SUBSCRIPTS) if set(sub) <= _REPRESENTABLE else "_" + sub)


def symbol_words(name: str, coordinates) -> str:
    """A state column in words for prose: a coordinate as its symbol (θ₁), a momentum
    ``p_<q>`` as "the momentum conjugate to q"."""
    if name.startswith("p_") and name[2:] in list(coordinates):
        return f"the momentum conjugate to {symbol_text(name[2:])}"
    return symbol_text(name)
