"""What a kind shows of a scene in the output folder's gallery (``index.html``).

The index stage runs after every batch over every archive in the folder, so it reads
no arrays: a kind's :meth:`~reportgen.scene.report.Report.gallery_headline` gets a
*light* :class:`~reportgen.archive.store.ArchiveData` (attrs, resolved config, the
scalar results and the small arrays of ``/analysis``, the checks; no runs, no sweep)
and answers one line in words for a student: the quantity, how far it is from what,
and what that reference is ("period 3.2959 s, 4e-12 from the exact 4K(k)√(l/g)").
Never a config key, never "rel. error".

This module holds the defaults every kind may fall back to: a line from the summary
checks (:func:`check_headline`) and one for a sweep's archive (:func:`family_headline`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import TYPE_CHECKING

from .content import fmt, fmt_err

if TYPE_CHECKING:
    from ..archive.store import ArchiveData

#: a config path with its value in a check's name or source ("(initial.theta = 3.09)")
_CONFIG_PART = re.compile(r"\s*\([^()]*\b[a-z_]+\.[a-z_]+\b[^()]*\)")
_CONFIG_KEY = re.compile(r"\b[a-z_]+\.[a-z_]+\b")
#: a citation in a reference's source, kept for the report, not the card: a parenthesis
#: naming a book, a section or an equation, or a trailing ", DLMF 22.19.4"
_CITATION = re.compile(r"\s*\((?:[^()]|\([^()]*\))*?(?:§|eq\.|notes|Goldstein|Landau|DLMF|Danby|"
                       r"Herzberg|Hairer|Chenciner|Squire|exercise)(?:[^()]|\([^()]*\))*\)"
                       r"|,\s*(?:DLMF|Goldstein|Landau|Danby|Herzberg)\b[^,;]*")


def is_family(data: ArchiveData) -> bool:
    """Whether the archive is a sweep's (a family of runs): its analysis counts members."""
    return "sweep_members" in data.analysis


def plain(text: str) -> str:
    """``text`` without the config keys a check's name or source may quote: a
    parenthesis naming one is dropped ("period of the worst member (initial.theta = 3)"
    -> "period of the worst member"), and so is a config path left bare."""
    text = _CONFIG_PART.sub("", str(text))
    return re.sub(r"\s{2,}", " ", _CONFIG_KEY.sub("", text)).strip(" ,;:")


def run_end_words(text: str, data: ArchiveData, unit: str = "", space: str = " ") -> str:
    """``text`` with the config key ``t_end`` said as the time it stands for, "t = 10"
    (with ``unit`` if given): "θ(t_end)" -> "θ(t = 10 s)".  ``space`` joins its parts (a
    no-break space keeps them on one line of a table cell)."""
    t_end = getattr(getattr(getattr(data, "config", None), "run", None), "t_end", None)
    if "t_end" not in text or t_end is None:
        return text
    words = space.join(["t", "=", fmt(float(t_end), 4)] + ([unit] if unit else []))
    return re.sub(r"(?<![\w.])t_end(?!\w)", words, text)


def reference_words(source: str) -> str:
    """A check's source as the card says it: no config key, no citation, the first
    clause only ("4K(k)·√(l/g), DLMF 22.19.4" -> "4K(k)·√(l/g)")."""
    text = _CITATION.sub("", plain(source))
    return re.sub(r"\s{2,}", " ", text.split(";")[0].split(", vs ")[0]).strip(" ,;:")


def distance(rel: float) -> str:
    """A relative error in words: "2e-16"-style text (one figure), "0" for none."""
    if not math.isfinite(rel):
        return "no error known"
    return "0" if rel == 0 else fmt(float(f"{rel:.0e}"), 1)


def from_reference(rel: float, reference: str) -> str:
    """"2e-16 from <reference>", or "equal to <reference>" when it is exactly."""
    return (f"equal to {reference}" if rel == 0 else
            f"{distance(rel)} from {reference}")


def check_headline(data: ArchiveData, words: Callable[[str], str] | None = None) -> str:
    """The default line: the first summary check (a kind lists its headline quantity
    first) in words, "<quantity> <value> <unit>, <error> from <reference>"; a check
    against zero (an error itself) reads "<quantity> <value> <unit>".  ``words``: how the
    report says a check's archived name (:meth:`Report.check_words`: "θ(t_end)" ->
    "θ(t = 10 s)"); default :func:`run_end_words` alone."""
    if is_family(data):
        return family_headline(data)
    checks = [c for c in data.checks if math.isfinite(c.value)]
    if not checks:
        return ""
    c = checks[0]
    words = words or (lambda text: run_end_words(text, data))
    name = words(plain(c.quantity))
    unit = f" {c.unit}" if c.unit and "unit" not in c.unit else ""
    if c.reference == 0:
        return f"{name}: {fmt_err(abs(c.value))}{unit}"
    return f"{name} {fmt(c.value, 5)}{unit}, {from_reference(c.rel_error, reference_words(c.source))}"


def family_headline(data: ArchiveData, members_are: str = "runs", each: str = "one") -> str:
    """A sweep's line: how many members ran ok and the largest error of the family's
    checks, "2000 amplitudes, all ok; every period within 1e-10 of 4K(k)·√(l/g)"."""
    a = data.analysis
    members, ok = int(a.get("sweep_members", 0)), int(a.get("sweep_ok", 0))
    text = f"{members} {members_are}, " + ("all ok" if ok == members else f"{ok} ok")
    finite = [c for c in data.checks if math.isfinite(c.rel_error) and c.reference != 0]
    if finite:
        worst = max(finite, key=lambda c: c.rel_error)
        words = reference_words(worst.source)
        text += (f"; every {each} within {distance(worst.rel_error)} of {words}" if words
                 else f"; every {each} within {distance(worst.rel_error)} of its reference")
    return text


def worst_check(data: ArchiveData, *words: str):
    """The check with the largest relative error among those whose name holds one of
    ``words`` (all checks if none given); None when there is none."""
    found = [c for c in data.checks if math.isfinite(c.rel_error)
             and (not words or any(w in c.quantity for w in words))]
    return max(found, key=lambda c: c.rel_error) if found else None


def signature_figures(figure_ids: list[str], preferred: tuple[str, ...]) -> list[int]:
    """Indices in ``figure_ids`` (the manifest's ``<section>-<name>`` ids, in report
    order) of every drawn figure among ``preferred``, in the order of ``preferred`` (a
    preference is a figure's name, as given to ``Report.figure``, or a full id); else
    [0], the report's first figure; [] when nothing is drawn."""
    picked: list[int] = []
    for want in preferred:
        picked += [i for i, fid in enumerate(figure_ids)
                   if (fid == want or fid.partition("-")[2] == want) and i not in picked]
    return picked or ([0] if figure_ids else [])


def chosen_figure(figure_ids: list[str], preferred: tuple[str, ...]) -> int | None:
    """Index of the gallery card's figure: the first of :func:`signature_figures`; None
    when nothing is drawn."""
    found = signature_figures(figure_ids, preferred)
    return found[0] if found else None
