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

from ...scene.schema import TEX_GREEK

#: Greek letters by their names, as a config spells them (TeX's names)
GREEK = TEX_GREEK
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


_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")
#: precedence of the operators a formula may use (Python's): a sum binds loosest
_PRECEDENCE = {"Add": 1, "Sub": 1, "Mult": 2, "Div": 2, "USub": 3, "UAdd": 3, "Pow": 4}
#: functions written as their mathematical sign
_FUNCTION_SIGNS = {"sqrt": "√"}


#: the longest config formula :func:`formula_text` reads (a title shows at most ~48 of it)
FORMULA_PARSED_UP_TO = 120


def formula_text(text: str, coordinates) -> str | None:
    """A config's formula as plain Unicode for a title, in the author's own order:
    ``p_q**2/2 + q**4/4`` -> ``p²/2 + q⁴/4`` (with one coordinate its momentum is p),
    ``m*omega**2*x**2/2`` -> ``mω²x²/2``.  None when a name has no Unicode spelling (a
    subscript like p_y), a power is not a small whole number, or the text does not parse:
    the caller then says the system in words."""
    import ast

    coordinates, words = list(coordinates), set()
    text = " ".join(str(text).split())
    if len(text) > FORMULA_PARSED_UP_TO:
        return None  # longer than a title shows; and never a deep parse of archived text
    try:
        # parsed, never evaluated: the tree is only walked for the node types below
        tree = ast.parse(text, mode="eval").body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None

    def name(node_id: str) -> str:
        if len(coordinates) == 1 and node_id == f"p_{coordinates[0]}":
            return "p"
        out = symbol_text(node_id)
        if "_" in out:
            raise ValueError(node_id)
        head = symbol_parts(node_id)[0]
        if len(head) > 1 and head not in GREEK:  # a word: set apart from its neighbours
            words.add(out)
        return out

    def walk(node) -> tuple[str, int]:
        """(text, precedence) of a node."""
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            value = node.value
            return (str(int(value)) if float(value).is_integer() else repr(value)), 5
        if isinstance(node, ast.Name):
            return name(node.id), 5
        if isinstance(node, ast.UnaryOp) and type(node.op).__name__ in ("USub", "UAdd"):
            inner = wrap(node.operand, 3)
            return ("−" if isinstance(node.op, ast.USub) else "+") + inner, 3
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and len(node.args) == 1:
            arg = walk(node.args[0])[0]
            sign = _FUNCTION_SIGNS.get(node.func.id)
            return (f"{sign}({arg})" if sign else f"{node.func.id}({arg})"), 5
        if isinstance(node, ast.BinOp):
            op = type(node.op).__name__
            level = _PRECEDENCE.get(op)
            if level is None:
                raise ValueError(op)
            if op == "Pow":
                if not (isinstance(node.right, ast.Constant) and isinstance(node.right.value, int)
                        and 0 <= node.right.value < 10):
                    raise ValueError("power")
                return wrap(node.left, 5) + str(node.right.value).translate(_SUPERSCRIPTS), 4
            left = wrap(node.left, level)
            right = wrap(node.right, level + (op in ("Sub", "Div")))
            if op in ("Add", "Sub"):
                return f"{left} {'+' if op == 'Add' else '−'} {right}", 1
            if op == "Div":
                return f"{left}/{right}", 2
            # a product by juxtaposition; a dot before a number or around a word, a space
            # before a function (m g l cos(θ) reads as mgl cos(θ))
            if (right[:1].isdigit() or _is_div(node.left) or any(left.endswith(w) for w in words)
                    or any(right.startswith(w) for w in words)):
                joint = "·"
            elif isinstance(node.right, ast.Call) and node.right.func.id not in _FUNCTION_SIGNS:
                joint = " "
            else:
                joint = ""
            return left + joint + right, 2
        raise ValueError(type(node).__name__)

    def wrap(node, level: int) -> str:
        out, own = walk(node)
        return f"({out})" if own < level else out

    try:
        return walk(tree)[0]
    except (ValueError, RecursionError):
        return None


def _is_div(node) -> bool:
    """Whether a product's left factor is written as a quotient (a/b): juxtaposing a
    factor after it would read as dividing by the product."""
    import ast

    return isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div)


#: characters of TeX on one typeset line of a long sum (H of a double pendulum):
#: longer ones are shrunk to the column's width, unreadably
EQUATION_LINE = 200


def dot_tex(tex: str) -> str:
    """The time derivative of a symbol's TeX: the dot on the letter, not over its
    subscript (``p_{a}`` -> ``\\dot{p}_{a}``)."""
    head, sub, rest = str(tex).partition("_")
    return rf"\dot{{{head}}}_{rest}" if sub and rest.startswith("{") else rf"\dot{{{tex}}}"

def split_sum(lhs: str, tex: str, width: int = EQUATION_LINE) -> list[str]:
    """``lhs = tex`` as typeset lines: a sum too long for one line is broken between
    its terms (at + and − outside every brace and \\left…\\right), each following
    line indented and opening with its sign."""
    terms, depth, start, i = [], 0, 0, 0
    while i < len(tex):
        if tex.startswith(r"\left", i):
            depth += 1
        elif tex.startswith(r"\right", i):
            depth -= 1
        elif tex[i] in "{":
            depth += 1
        elif tex[i] in "}":
            depth -= 1
        elif depth == 0 and i > start and tex[i - 1:i + 2] in (" + ", " - "):
            terms.append(tex[start:i - 1])
            start = i
        i += 1
    terms.append(tex[start:])
    lines, line = [], f"{lhs} = {terms[0]}"
    for term in terms[1:]:
        if len(line) + len(term) > width:
            lines.append(line)
            line = r"\qquad " + term
        else:
            line += " " + term
    return lines + [line]
