"""``hamiltonian`` report, the tables whose cells are symbols (the conserved quantities
with what each drift is relative to, the Poisson brackets, the separated constants) and the
names of the config's quantities as TeX, from the archive alone."""

from __future__ import annotations

import math

import numpy as np

from ...scene.content import fmt, fmt_err
from .symbols import symbol_tex


class SymbolTables:
    """Mixed into :class:`.report.HamiltonianReport`."""

    @classmethod
    def symbol_tables(cls, data) -> dict[str, list[dict]]:
        """The tables whose cells are symbols or brackets, by section, for the kind's
        template to typeset (``symbol_table``: the columns ``tex`` hold TeX): a section's
        own tables are printed as text, where p_y and A_xy have no spelling.  Each table:
        ``header``, ``rows``, ``caption``, ``tex``."""
        a, run = data.analysis, data.runs.get("main")
        tables: dict[str, list[dict]] = {"invariants": [], "brackets": [], "hamilton_jacobi": []}
        if run is not None:
            tables["invariants"].append({
                "header": ["quantity", "initial value", "max |I(t) − I(0)| / scale",
                           "scale: what the drift is relative to"],
                "rows": [[cls.name_tex(data, n), fmt(float(v[0])),
                          fmt_err(run.attrs.get(f"drift_{n}", math.nan)),
                          cls.scale_words(data, n)]
                         for n, v in run.invariants.items()],
                "caption": "Conserved quantities: the largest drift of each, divided by its "
                           "scale, the size of what it is built from, never by its own "
                           "initial value (which may be 0). A numerically stable run keeps "
                           f"it ≤ {fmt_err(run.attrs.get('drift_bound', math.nan))}.",
                "tex": [0]})
        observables = [k[len("poisson_"):] for k in a
                       if k.startswith("poisson_") and not k.endswith(("_latex", "_max"))
                       and f"{k}_latex" in a]  # a first-order L's reduced bracket: no table
        if observables:
            tables["brackets"].append({
                "header": ["observable f", "{f, H}", "conserved", "max |{f, H}| on the run"],
                "rows": [[cls.name_tex(data, f), cls.cell_tex(a[f"poisson_{f}_latex"]),
                          "yes" if a[f"conserved_{f}"] else "no",
                          fmt_err(a[f"poisson_{f}_max"])] for f in observables],
                "caption": "{f, H} = Σ ∂f/∂q ∂H/∂p − ∂f/∂p ∂H/∂q, simplified by SymPy "
                           "(the archive holds it whole); f is conserved when {f, H} + ∂f/∂t "
                           "vanishes, with the named constants at their values. "
                           "The last column evaluates {f, H} along the run.",
                "tex": [0, 1]})
        pairs = a.get("pair_brackets")
        if pairs and "latex" in pairs:
            tables["brackets"].append({
                "header": ["bracket", "simplified"],
                "rows": [[rf"\{{{cls.name_tex(data, f)}, {cls.name_tex(data, g)}\}}",
                          cls.cell_tex(b)]
                         for f, g, b in zip(pairs["f"], pairs["g"], pairs["latex"],
                                            strict=True)],
                "caption": "Brackets between the observables, simplified.",
                "tex": [0, 1]})
        if "hj_constants" in a:
            tables["hamilton_jacobi"].append({
                "header": ["constant", "value", "max relative drift"],
                "rows": [[cls.name_tex(data, k), fmt(v), fmt_err(a["hj_constant_drift"][k])]
                         for k, v in a["hj_constants"].items()],
                "caption": "The separated constants at t = 0 and their relative drift along "
                           "the integration.",
                "tex": [0]})
        return tables

    #: a scale at or below this is the simulation's floor (1e-300): nothing to measure by
    NO_SCALE = 1e-290

    @classmethod
    def scale_words(cls, data, name: str) -> str:
        """What the drift of the invariant ``name`` is relative to, in words, with the
        archived scale: chosen by what the quantity is (H, an observable conserved by the
        bracket test, a cyclic momentum, a Noether charge), from the archive."""
        a, run = data.analysis, data.runs["main"]
        scale = run.attrs.get(f"scale_{name}")
        if scale is None:
            values = np.asarray(run.invariants[name], dtype=float)
            return f"its own size, max |I| = {fmt(float(np.max(np.abs(values))), 3)}"
        size = fmt(float(scale), 3)
        if float(scale) <= cls.NO_SCALE:
            return ("none: what it is built from vanishes along the run (an equilibrium), so "
                    "the drift is absolute")
        if name == "H" and a.get("first_order", False):
            return f"max(|V(0)|, the sum of the sizes of V's terms at t = 0) = {size}"
        if name == "H":
            return f"the energy scale max(|H(0)|, |T(0)|, |V(0)|) = {size}"
        if name == "noether_charge" or f"conserved_{name}" in a:
            return f"the largest sum of the sizes of its terms along the run, {size}"
        if name.startswith("p_") and name[2:] in [str(c) for c in a.get("cyclic", [])]:
            return f"the largest |momentum| along the run, {size}"
        return f"its declared scale, {size}"

    @classmethod
    def cell_tex(cls, tex) -> str:
        """A bracket's TeX for a table cell; one too long to read typeset (a cell does not
        wrap) is said to be so: the archive holds it whole."""
        tex = str(tex)
        return tex if len(tex) <= cls.LONGEST_EQUATION // 2 else r"\mathrm{(too\ long;\ archived)}"

    #: what the names of a preset (or of a separation's constants) mean beyond their
    #: spelling: the central potential's ``L2`` is L², not L with index 2
    NAMED_SYMBOLS = {"central_potential": {"L2": "L^{2}"}, "central": {"L2": "L^{2}"}}

    @classmethod
    def name_tex(cls, data, name: str) -> str:
        """A name's TeX (:func:`symbol_tex`), unless the scene's preset or separation gives
        it a meaning of its own (:attr:`NAMED_SYMBOLS`)."""
        if str(name) == "noether_charge":  # the declared symmetry's charge, not a config name
            return r"Q_{\mathrm{N}}"
        for key in (getattr(data.config, "preset", None), data.analysis.get("hj_separation")):
            if key is not None and str(name) in cls.NAMED_SYMBOLS.get(str(key), {}):
                return cls.NAMED_SYMBOLS[str(key)][str(name)]
        return symbol_tex(str(name))

    #: the drift figure's axis: each quantity divided by its own scale (the table's)
    DRIFT_AXIS = "drift (I(t) − I(0))/scale, each scale in the table (dimensionless)"

    @classmethod
    def relabel_drift(cls, content) -> None:
        """The drift figure's y label: divided by each quantity's scale, not by |I|."""
        for spec in content.figures:
            if spec.name == "invariants":
                for ax in spec.figure.axes:
                    ax.set_ylabel(cls.DRIFT_AXIS)
