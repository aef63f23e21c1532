"""Declared results: every stored quantity of a kind, once, with its symbol and unit.

A kind declares what its simulation stores (``kinds/<kind>/results.py``) as
:class:`Quantity` objects gathered in a :class:`ResultsSchema`.  The declaration is the
one source of

* the archive's CF attributes on every dataset (``units``, ``long_name``, ``symbol``),
  so that xarray shows them;
* the check at write time: a result the schema does not declare, a declared result
  that is missing, or one of the wrong shape is an error when the archive is written,
  not when a figure is drawn (:meth:`ResultsSchema.problems`);
* axis labels, table headers and captions (:meth:`Quantity.label`,
  :meth:`Quantity.text`): "$\\dot\\theta$ [rad/s]", never a config key.

Units are written as pint and UDUNITS read them ("rad/s", "kg m^2/s", "1" for a
dimensionless number, "" for text); :func:`unit_text` gives the typeset form ("kg m²/s").
"""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

#: the value types a quantity may have
VALUE_TYPES = ("float", "int", "bool", "str")

_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


#: a number inside a unit ("u Å/(4.074598 fs)": a multiple of a unit)
_UNIT_FACTOR = re.compile(r"(?<![\w^.\-])(\d+\.\d+(?:[eE][+-]?\d+)?)(?=\s)")


def unit_text(unit: str) -> str:
    """A unit as printed on a page: ``kg m^2/s`` -> ``kg m²/s``; "1" -> "dimensionless";
    a multiple of a unit to 4 digits ("4.074598 fs" -> "4.075 fs")."""
    if unit in ("1", ""):
        return "dimensionless" if unit == "1" else ""
    unit = _UNIT_FACTOR.sub(lambda m: f"{float(m.group(1)):.4g}", unit)
    return re.sub(r"\^(-?\d+)", lambda m: m.group(1).translate(_SUPERSCRIPT),
                  unit).replace("*", " ")


def cf_units(unit: str) -> tuple[str, float | None]:
    """A declared unit as the archive's CF ``units`` attribute, which pint and UDUNITS read:
    (the unit, None), or for a multiple of a unit ("4.074598 fs", "u Å/(4.074598 fs)")
    (the plain unit, the CF ``scale_factor`` that turns a stored number into it: a value
    stored in τ = 4.0746 fs reads 4.0746 × value in "fs"; "u Å/fs" and 1/4.0746).  A
    factor in a denominator is one after "/(" or "/"."""
    factor = 1.0
    found = False

    def drop(m: re.Match) -> str:
        nonlocal factor, found
        found = True
        value = float(m.group(1))
        below = re.search(r"/\(?\s*$", unit[:m.start()]) is not None
        factor = factor / value if below else factor * value
        return ""

    plain = _UNIT_FACTOR.sub(drop, unit)
    if not found:
        return unit, None
    plain = " ".join(plain.replace("( ", "(").split())
    return re.sub(r"\(([^()\s*/]+)\)", r"\1", plain), factor


@dataclass(frozen=True)
class Quantity:
    """One stored result.

    Parameters
    ----------
    name : str
        Its path below ``/analysis`` ("period", "phase_portrait/theta"), or a run
        column or invariant name.
    symbol : str
        TeX without dollars (``r"\\dot{\\theta}"``); "" when the quantity has none.
    unit : str
        pint/UDUNITS text ("rad/s"); "1" dimensionless; "" for text and flags.
    description : str
        One line, lower case: the CF ``long_name``.
    dims : tuple of str
        Names of its dimensions; () for a scalar.  A dimension ``t`` must have the
        main run's number of samples; other names must agree within one archive.
    kind : str
        "float", "int", "bool" or "str".
    optional : bool
        Stored only in some cases (a boundary-value problem when one is configured).
    own_units : str
        For a number in the config's own units (unit "1"): what it measures in them,
        "config units of time"; the archive says so in the attribute ``config_units``
        (``units`` stays a unit pint reads).  "" for a physical or a pure number; a
        schema's :attr:`ResultsSchema.own_units` gives it for every "1" of a kind that
        works in the config's units.
    """

    name: str
    symbol: str
    unit: str
    description: str
    dims: tuple[str, ...] = ()
    kind: str = "float"
    optional: bool = False
    own_units: str = ""

    def __post_init__(self):
        if self.kind not in VALUE_TYPES:
            raise ValueError(f"quantity {self.name!r}: kind must be one of {VALUE_TYPES}")

    @property
    def math(self) -> str:
        """The symbol for a figure's mathtext, or the description if none.  A time
        derivative ``\\dot{x}`` is written ``dx/dt`` there: with text kept as text in the
        SVG, the dot accent is a combining character that the PDF engine draws as a dotted
        circle."""
        if not self.symbol:
            return self.description
        # a subscript after the derivative belongs to all of it: (dθ/dt)₀, not dθ/dt₀
        symbol = re.sub(r"\\dot\{([^{}]*)\}(_\{[^{}]*\}|_\w)",
                        r"(\\mathrm{d}\1/\\mathrm{d}t)\2", self.symbol)
        symbol = re.sub(r"\\dot\{([^{}]*)\}", r"\\mathrm{d}\1/\\mathrm{d}t", symbol)
        return f"${symbol}$"

    @property
    def text(self) -> str:
        """The symbol as page text (Unicode: "θ₀", "φ̇₀"), or the description when it has
        none or one that plain text cannot show."""
        return (symbol_text(self.symbol) if self.symbol else None) or self.description

    def label(self, unit: str | None = None) -> str:
        """Axis label: symbol and unit, "$\\dot{\\theta}$ [rad/s]" (``unit`` overrides)."""
        text = unit_text(self.unit if unit is None else unit)
        return f"{self.math} [{text}]" if text else self.math

    @property
    def cf_attrs(self) -> dict[str, Any]:
        """The CF attributes written on its dataset: ``long_name``, ``symbol`` and, for a
        number, ``units`` as pint reads it (a multiple of a unit with its ``scale_factor``,
        :func:`cf_units`), ``config_units`` for one in the config's own units; text has no
        ``units`` (CF)."""
        out: dict[str, Any] = {"long_name": self.description, "symbol": self.symbol}
        if self.kind == "str":
            return out
        units, factor = cf_units(self.unit)
        out["units"] = units
        if factor is not None:
            out["scale_factor"] = factor
        if self.own_units:
            out["config_units"] = self.own_units
        return out

    def with_name(self, name: str) -> Quantity:
        return replace(self, name=name)


def key_owner(model, path: str) -> tuple[type, str] | None:
    """(the pydantic model whose field the dotted config key ``path`` names, that field's
    name): ``path``'s tables walked down from ``model`` (a table declared ``X | None``
    included); None when one of them is not a declared table (a table of free keys)."""
    *tables, name = path.split(".")
    for part in tables:
        field = (getattr(model, "model_fields", None) or {}).get(part)
        if field is None:
            return None
        model = field.annotation
        for arg in getattr(model, "__args__", ()) or ():  # X | None
            if hasattr(arg, "model_fields"):
                model = arg
    return (model, name) if hasattr(model, "model_fields") else None


def config_quantity(model, path: str, symbol: str = "") -> Quantity:
    """The config key ``path`` ("initial.theta") of the pydantic ``model`` as a quantity,
    for a figure's label: its field's description cut to the quantity, the unit in its
    description's brackets ("... [rad]"), and ``symbol`` (TeX).  Without ``symbol``, a
    description that ends in one ("precession rate φ̇0 [rad/s] (or give `steady`)")
    gives it (``\\dot{\\varphi}_{0}``); what follows the unit (a note on other values,
    a condition) is not part of the quantity.  A key the model does not declare field by
    field (a table of free keys) has no description or unit.  A key in the config's own
    units ("[config units of length]") is stored as a pure number, unit "1", as the kinds
    that work in them declare their results; one whose unit another key chooses ("[per
    `units`: kg or m₀]") has none here (the kind knows it from the config)."""
    owner = key_owner(model, path)
    field = owner[0].model_fields.get(owner[1]) if owner is not None else None
    text = (field.description or "") if field is not None else ""
    description, unit, found = quantity_of_description(text)
    if unit.startswith(OWN_UNITS):
        unit = "1"
    elif CHOSEN_BY.fullmatch(unit):
        unit = ""
    return Quantity(path, symbol or found, unit, description or path.rsplit(".", 1)[-1])


#: a declared unit beginning so is the config's own ("[config units of length]")
OWN_UNITS = "config units"
#: a declared unit beginning so is chosen by another key ("[per `units`: kg or m₀]")
CHOSEN_BY = re.compile(r"per `([\w.]+)`:\s*(.*)")
#: the unit of a config field's description: "[rad/s]" after a space (not a list "[ω1, ω2]")
_UNIT_BRACKET = re.compile(r"(?:^|\s)\[([^\[\],]+)\]")
#: a trailing condition on the value: ", 0 ≤ θ < π"
_CONDITION = re.compile(r",\s*[^,]*[=<>≤≥][^,]*$")
#: a symbol as config descriptions write it: a letter, an accent, a numeric subscript
_TEXT_SYMBOL = re.compile(r"([A-Za-zα-ωΑ-Ωϑϕϵ])([\u0307\u0308]?)([0-9₀-₉]*)")


def split_unit(text: str) -> tuple[str, str]:
    """(the text without its unit bracket, the unit) of a config field's description:
    "precession rate φ̇0 [rad/s] (or give `steady`)" -> ("precession rate φ̇0 (or give
    `steady`)", "rad/s"); ("…", "") when it declares none."""
    found = _UNIT_BRACKET.search(text)
    if found is None:
        return text, ""
    return " ".join((text[:found.start()] + text[found.end():]).split()), found.group(1).strip()


def quantity_of_description(text: str) -> tuple[str, str, str]:
    """(the quantity in words, its unit, its TeX symbol or "") of a config field's
    description: "precession rate φ̇0 [rad/s] (or give `steady`)" -> ("precession rate
    φ̇0", "rad/s", ``\\dot{\\varphi}_{0}``); "spin ω3 = ψ̇ + φ̇ cos θ [rad/s]" -> ("spin
    ω3", "rad/s", ``\\omega_{3}``); "tilt …, 0 ≤ θ < π [rad]" -> ("tilt …", "rad", "")."""
    found = _UNIT_BRACKET.search(text)
    head, unit = (text[:found.start()], found.group(1).strip()) if found else (text, "")
    head = _CONDITION.sub("", head.strip()).strip()
    defined = re.fullmatch(r"(.+?) = [^,]*", head)  # "spin ω3 = ψ̇ + φ̇ cos θ": spin ω3
    for name in ([defined.group(1)] if defined else []) + [head]:
        words = name.rsplit(" ", 1)
        token = words[-1]
        # a symbol: "φ̇0", "ω3", "ω", not a lone Latin letter ("velocity, x", "power law V")
        if (_TEXT_SYMBOL.fullmatch(token) and not (len(token) == 1 and token.isascii())
                and (len(words) == 1 or not words[0].endswith(","))):
            return name, unit, tex_of_text_symbol(token)
    return head, unit, ""


_GREEK_LETTERS = {
    "α": "alpha", "β": "beta", "γ": "gamma", "δ": "delta", "ε": "varepsilon", "ϵ": "epsilon",
    "ζ": "zeta", "η": "eta", "θ": "theta", "ϑ": "vartheta", "ι": "iota", "κ": "kappa",
    "λ": "lambda", "μ": "mu", "ν": "nu", "ξ": "xi", "π": "pi", "ρ": "rho", "σ": "sigma",
    "τ": "tau", "υ": "upsilon", "φ": "varphi", "ϕ": "phi", "χ": "chi", "ψ": "psi",
    "ω": "omega", "Γ": "Gamma", "Δ": "Delta", "Θ": "Theta", "Λ": "Lambda", "Ξ": "Xi",
    "Π": "Pi", "Σ": "Sigma", "Φ": "Phi", "Ψ": "Psi", "Ω": "Omega"}
#: Greek letters by their TeX names (``theta`` -> θ; ``phi`` and ``varphi`` both -> φ):
#: also how a formula config spells them (kinds/hamiltonian/symbols.py)
TEX_GREEK = {tex: char for char, tex in _GREEK_LETTERS.items()} | {"phi": "φ", "epsilon": "ε"}
_TEX_WORDS = {"langle": "⟨", "rangle": "⟩", "infty": "∞", "cdot": "·", "times": "×",
              "ell": "ℓ", "hbar": "ħ", "nabla": "∇", "partial": "∂", "min": "min",
              "max": "max", "cos": "cos", "sin": "sin", "ln": "ln", "exp": "exp"}
_SUBSCRIPT_CHARS = str.maketrans("0123456789+-−=()aehijklmnoprstuvx",
                                 "₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ")
_SUPERSCRIPT_CHARS = str.maketrans("0123456789+-−=()in", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾ⁱⁿ")
_ACCENTS = {"dot": "\u0307", "ddot": "\u0308", "hat": "\u0302", "bar": "\u0304",
            "tilde": "\u0303", "vec": "\u20d7"}


def tex_of_text_symbol(token: str) -> str:
    """A symbol as config descriptions write it, as TeX for a figure's mathtext: "φ̇0" ->
    ``\\dot{\\varphi}_{0}``, "ω3" -> ``\\omega_{3}``, "x" -> ``x``."""
    m = _TEXT_SYMBOL.fullmatch(token)
    if m is None:
        return ""
    base, accent, sub = m.groups()
    tex = f"\\{_GREEK_LETTERS[base]}" if base in _GREEK_LETTERS else base
    if accent:
        tex = ("\\dot" if accent == "\u0307" else "\\ddot") + "{" + tex + "}"
    if sub:
        tex += "_{" + sub.translate(str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")) + "}"
    return tex


def symbol_text(tex: str) -> str | None:
    """A TeX symbol as page text, in Unicode: ``\\theta_0`` -> θ₀, ``\\dot{\\phi}_0`` ->
    φ̇₀, ``v_{x,0}`` -> vₓ,₀, ``\\langle\\dot{\\varphi}\\rangle`` -> ⟨φ̇⟩; None when it
    holds what plain text cannot show (a fraction, a subscript letter Unicode lacks)."""
    s = str(tex).strip().strip("$").strip()
    if not s:
        return None
    s = re.sub(r"\\([A-Za-z]+)",
               lambda m: TEX_GREEK.get(m.group(1), _TEX_WORDS.get(m.group(1), m.group(0))), s)
    s = re.sub(r"\\(?:mathrm|mathit|text|operatorname|mathbf)\{([^{}]*)\}", r"\1", s)
    s = s.replace("\\,", " ").replace("\\ ", " ").replace("\\!", "")
    for _ in range(3):  # accents, innermost first
        s = re.sub(r"\\(dot|ddot|hat|bar|tilde|vec)\s*(?:\{([^{}]*)\}|(\S))",
                   lambda m: (m.group(2) if m.group(2) is not None else m.group(3))
                   + _ACCENTS[m.group(1)], s)
    failed = False

    def script(m: re.Match, table) -> str:
        nonlocal failed
        body = m.group(1) if m.group(1) is not None else m.group(2)
        out = body.translate(table)
        shown = {chr(c) for c in table.values()} | {",", " "}
        if not set(out) <= shown:  # a character Unicode has no sub/superscript of
            failed = True
        return out

    s = re.sub(r"_(?:\{([^{}]*)\}|(\w))", lambda m: script(m, _SUBSCRIPT_CHARS), s)
    s = re.sub(r"\^(?:\{([^{}]*)\}|(\w))", lambda m: script(m, _SUPERSCRIPT_CHARS), s)
    s = s.replace("{", "").replace("}", "")
    if failed or "\\" in s or "_" in s or "^" in s:
        return None
    return s


#: the time axis of every run
TIME = Quantity("t", "t", "s", "time", ("t",))

#: results the shared machinery stores for every kind (sweeps, the study's horizon)
COMMON = (
    Quantity("study_t_end", "t_{study}", "s", "end of the error-against-run-time study's "
             "integration", optional=True),
    Quantity("sweep_members", "M", "1", "members of the sweep", kind="int", optional=True),
    Quantity("sweep_ok", "", "1", "members of the sweep that ended ok", kind="int",
             optional=True),
    Quantity("sweep_members_per_s", "", "1/s", "members run per second of wall time",
             optional=True),
)


@dataclass(frozen=True)
class ResultsSchema:
    """What a kind stores: run columns, invariants and ``/analysis`` results.

    ``columns`` and ``invariants`` apply to every run of the kind (``/runs/<name>``);
    ``analysis`` to ``/analysis``, nested groups by "/" in the name.  ``time`` is the
    runs' time axis (seconds unless the kind works in scaled units).
    """

    columns: tuple[Quantity, ...] = ()
    invariants: tuple[Quantity, ...] = ()
    analysis: tuple[Quantity, ...] = ()
    time: Quantity = TIME
    #: analysis groups whose members the kind does not declare one by one (a
    #: user-named observable, say): name -> the quantity each member is
    open_groups: Mapping[str, Quantity] = field(default_factory=dict)
    #: a kind that works in the config's own units: what its numbers declared "1" are
    #: ("config units (the formula's own)"), written as each one's ``config_units``
    #: attribute unless the quantity says more (:attr:`Quantity.own_units`); "" for a kind
    #: in physical units
    own_units: str = ""
    #: dimensions numbered as the report numbers them, 1 … n, rather than indexed from 0:
    #: name -> what the number counts (the archive's coordinate of that dimension)
    numbered: Mapping[str, str] = field(default_factory=dict)

    def __post_init__(self):
        seen: set[str] = set()
        for q in self.analysis:
            if q.name in seen:
                raise ValueError(f"result {q.name!r} declared twice")
            seen.add(q.name)

    # ------------------------------------------------------------ look-ups
    @functools.cached_property
    def all_analysis(self) -> dict[str, Quantity]:
        """Every ``/analysis`` result by name: the kind's and the shared ones (:data:`COMMON`).
        Looked up for every dataset written, so built once."""
        return {q.name: q for q in (*COMMON, *self.analysis)}

    def column(self, name: str) -> Quantity:
        return _find(name, self.columns, "run column")

    def invariant(self, name: str) -> Quantity:
        return _find(name, self.invariants, "invariant")

    def result(self, name: str) -> Quantity:
        """The declared ``/analysis`` result ``name`` (KeyError with a suggestion)."""
        found = self.all_analysis.get(name)
        if found is not None:
            return found
        group, _, member = name.rpartition("/")
        if group in self.open_groups:
            return self.open_groups[group].with_name(name)
        spread = re.fullmatch(r"(.+)_(\d+)", name)  # a sweep's frequencies_2: element 2
        if spread and spread.group(1) in self.all_analysis:
            q = self.all_analysis[spread.group(1)]
            return Quantity(name, f"{{{q.symbol}}}_{{{spread.group(2)}}}" if q.symbol else "",
                            q.unit, f"{q.description}, element {spread.group(2)}")
        return _find(name, tuple(self.all_analysis.values()), "result")

    def quantity(self, name: str) -> Quantity:
        """A column, invariant, the time or a result by name (that order)."""
        if name == self.time.name:
            return self.time
        for group in (self.columns, self.invariants):
            for q in group:
                if q.name == name:
                    return q
        return self.result(name)

    def label(self, name: str) -> str:
        return self.quantity(name).label()

    def cf_attrs(self, q: Quantity) -> dict[str, Any]:
        """The CF attributes of ``q`` in an archive of this schema (:attr:`Quantity.cf_attrs`,
        with :attr:`own_units` for a number declared "1")."""
        if self.own_units and q.unit == "1" and q.kind != "str" and not q.own_units:
            q = replace(q, own_units=self.own_units)
        return q.cf_attrs

    def merged(self, other: ResultsSchema) -> ResultsSchema:
        """This schema with ``other``'s declarations added (a family's, say)."""
        return ResultsSchema(columns=_union(self.columns, other.columns),
                             invariants=_union(self.invariants, other.invariants),
                             analysis=_union(self.analysis, other.analysis), time=self.time,
                             open_groups={**self.open_groups, **other.open_groups},
                             own_units=self.own_units or other.own_units,
                             numbered={**other.numbered, **self.numbered})

    # --------------------------------------------------------------- checks
    def problems(self, results) -> list[str]:
        """Every way ``results`` (:class:`~reportgen.scene.results.Results`) departs from
        the declaration: undeclared or missing results, wrong kinds and shapes."""
        out: list[str] = []
        sizes: dict[str, int] = {}
        main = results.runs.get("main")
        if main is not None:
            sizes["t"] = len(main.t)
        flat = dict(flatten(results.analysis))
        declared = self.all_analysis
        for name, value in flat.items():
            q = declared.get(name)
            if q is None:
                group = name.rpartition("/")[0]
                if group in self.open_groups:
                    q = self.open_groups[group].with_name(name)
                else:
                    close = difflib.get_close_matches(name, declared, n=1)
                    hint = f" (did you mean {close[0]!r}?)" if close else ""
                    out.append(f"/analysis/{name}: not a declared result{hint}")
                    continue
            out.extend(_value_problems(f"/analysis/{name}", q, value, sizes))
        family = getattr(results, "sweep", None) is not None  # /analysis: the family's
        for name, q in declared.items():
            if not family and not q.optional and name not in flat:
                out.append(f"/analysis/{name}: declared result missing")
        columns = {q.name for q in self.columns}
        invariants = {q.name for q in self.invariants}
        for run_name, run in results.runs.items():
            for c in run.columns:
                if c not in columns:
                    out.append(f"/runs/{run_name}: column {c!r} not declared")
            for c in run.invariants:
                if c not in invariants:
                    out.append(f"/runs/{run_name}/invariants/{c}: not declared")
            for c in run.reference:
                if c not in columns:
                    out.append(f"/runs/{run_name}/reference/{c}: not a declared column")
        return out


def _value_problems(where: str, q: Quantity, value: Any, sizes: dict[str, int]) -> list[str]:
    if q.kind == "str":
        ok = isinstance(value, str) or (isinstance(value, (list, tuple, np.ndarray)) and q.dims
                                        and all(isinstance(v, str) for v in np.ravel(value)))
        return [] if ok else [f"{where}: expected text, got {type(value).__name__}"]
    if isinstance(value, str):
        return [f"{where}: expected a {q.kind} number, got text {value[:40]!r}"]
    arr = np.asarray(value)
    if arr.dtype == object or arr.dtype.kind not in "biuf":
        return [f"{where}: expected {q.kind} values, got dtype {arr.dtype}"]
    if q.kind in ("int", "bool") and arr.dtype.kind == "f":
        return [f"{where}: expected {q.kind} values, got floats"]
    if arr.ndim != len(q.dims):
        return [f"{where}: expected {len(q.dims)} dimension(s) {q.dims}, got shape {arr.shape}"]
    out = []
    for dim, n in zip(q.dims, arr.shape, strict=True):
        if dim in sizes and sizes[dim] != n:
            out.append(f"{where}: dimension {dim!r} has {n} points, expected {sizes[dim]}")
        sizes.setdefault(dim, n)
    return out


def flatten(mapping: Mapping[str, Any], prefix: str = "") -> Iterable[tuple[str, Any]]:
    """(path, leaf) of a nested results mapping, groups joined by "/"."""
    for key, value in mapping.items():
        path = f"{prefix}{key}"
        if isinstance(value, Mapping):
            yield from flatten(value, path + "/")
        else:
            yield path, value


def _find(name: str, quantities: tuple[Quantity, ...], what: str) -> Quantity:
    for q in quantities:
        if q.name == name:
            return q
    names = [q.name for q in quantities]
    close = difflib.get_close_matches(name, names, n=1)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise KeyError(f"{name!r} is not a declared {what}{hint}")


def _union(a: tuple[Quantity, ...], b: tuple[Quantity, ...]) -> tuple[Quantity, ...]:
    names = {q.name for q in a}
    return a + tuple(q for q in b if q.name not in names)
