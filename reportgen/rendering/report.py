"""Reports: the only module that touches jinja2 and the PDF engine.

The report step reads an archive and nothing else: the scene is rebuilt from
the config text stored in the archive, its sections draw their figures from the
archived arrays, and one jinja2 environment renders one context dict.  The PDF
is WeasyPrint's rendering of the same HTML.
"""

from __future__ import annotations

import dataclasses
import hashlib
import io
import json
import math
import os
import re
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup

from .. import __version__
from ..archive.audit import read_audit
from ..archive.h5io import LIBRARIES
from ..archive.store import ArchiveData, read_archive
from ..errors import ReportError
from ..kinds import get_kind
from ..lazy import lazy_module
from ..scene.content import FigureSpec, SectionContent, fmt, fmt_err
from ..scene.report import method_words
from ..scene.schema import unit_text
from ..scene.sources import with_sources
from ..scene.typeset import plain_text, typeset_html, visible_text
from ..support.forked import JobProcess, serve
from ..support.fsutil import atomic_write, read_back
from ..support.layout import MAX_FIGURE_BYTES, template_dir, visible_controls
from ..support.svgsafe import SvgRefused, clean_svg, svg_safe
from .equations import equation_html
from .gate import gate_findings, write_gate
from .pdf import PdfWorker, write_pdf  # noqa: F401 - part of this module's interface

# Drawing libraries load on first use: a report whose figures are current (a title edit)
# renders without importing matplotlib.
matplotlib = lazy_module("matplotlib")
audit_plots = lazy_module("reportgen.rendering.plots.audit")


_ENV: jinja2.Environment | None = None


def environment() -> jinja2.Environment:
    """The single jinja2 environment (autoescape on, undefined variables are errors)."""
    global _ENV
    if _ENV is None:
        _ENV = jinja2.Environment(
            loader=jinja2.ChoiceLoader([jinja2.FunctionLoader(_kind_template),
                                        jinja2.FileSystemLoader(template_dir())]),
            autoescape=True,
            undefined=jinja2.StrictUndefined,
            trim_blocks=True,
            lstrip_blocks=True,
            bytecode_cache=_template_cache(),
        )
        _ENV.filters["num"] = fmt
        _ENV.filters["err"] = fmt_err
        _ENV.filters["eq"] = equation_html  # {% filter eq %}TeX{% endfilter %}
        _ENV.filters["cell"] = table_cell
        _ENV.filters["eq_display"] = display_equation
        _ENV.filters["prose"] = prose_text
        _ENV.filters["plain"] = plain_text  # typeset in Unicode alone (an attribute)
    return _ENV


def _kind_template(name: str):
    """The jinja2 source of ``kinds/<kind>.html.j2`` from the kind's package, or None (then
    the shared templates folder is looked in)."""
    found = re.fullmatch(r"kinds/(\w+)\.html\.j2", name)
    try:
        path = get_kind(found.group(1)).template_path() if found else None
    except KeyError:
        return None
    if path is None:
        return None
    mtime = path.stat().st_mtime_ns
    return (path.read_text(encoding="utf-8"), str(path),
            lambda: path.exists() and path.stat().st_mtime_ns == mtime)


def _template_cache() -> jinja2.BytecodeCache | None:
    """The templates compiled once per machine (``$XDG_CACHE_HOME/reportgen/jinja``; jinja2
    keys each by its source's checksum): compiling the report's templates again cost every
    report ~0.1 s.  None where the folder cannot be made (a read-only home, say)."""
    from ..support.cache import cache_root

    folder = cache_root() / "jinja"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return jinja2.FileSystemBytecodeCache(str(folder))


def display_equation(tex: str) -> Markup:
    """A displayed equation from the archive (TeX that SymPy printed): typeset, or -- when
    mathtext cannot parse it -- shown as its TeX source in code type."""
    try:
        return equation_html(tex)
    except ValueError:
        return Markup("<code>") + str(tex) + Markup("</code>")


#: a path inside the archive quoted in prose ("/study/error_vs_runtime", "/runs/main")
_ARCHIVE_PATH = re.compile(r"(?<![\w/.])/(?:study|runs|analysis|sweep|config|checks|provenance)"
                           r"(?:/[\w.\-]*\w)*")


def prose_text(value) -> Markup:
    """A note or caption from the archive's report face, escaped, with every archive path
    it quotes ("/study/error_vs_runtime") set as code, kept on one line."""
    text = str(value)
    if isinstance(value, Markup):
        return value
    out, start = Markup(""), 0
    for m in _ARCHIVE_PATH.finditer(text):
        out += text[start:m.start()] + Markup('<code class="path">{}</code>').format(m.group(0))
        start = m.end()
    return out + text[start:]


def table_cell(value) -> Markup:
    """A table cell (or header) that wraps between its parts, never inside a number:
    "5.1e-12 (rtol 1e-12)" may break before the parenthesis, "ω3 [rad/s]" before the
    bracket, "rtol 1e-11: 3.9e-10 in 0.09 ms" after the colon, "0.54, 0.46" and "1.2 /
    3.4" after the comma or slash (outside brackets only), so that a wide table fits the
    page.  A part with a digit, or a [unit], is kept whole (a minus sign, an exponent or a
    unit is never a line break); a part of words alone wraps freely."""
    text, parts, start, depth = str(value), [], 0, 0
    for i, ch in enumerate(text):
        depth += {"(": 1, "[": 1, ")": -1, "]": -1}.get(ch, 0)
        if ch != " " or i == start:
            continue
        if (text[i + 1:i + 2] in ("(", "[") and depth == 0) or (
                depth == 0 and (text[i - 1] in ",:;" or text[i - 2:i] == " /")):
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return Markup(" ").join(Markup('<span class="nw">{}</span>').format(p)
                            if p.startswith("[") or any(c.isdigit() for c in p) else p
                            for p in parts)


# ------------------------------------------------------------------- figures
@dataclass
class SavedFigure:
    id: str
    caption: str
    svg: Markup
    files: dict[str, str]  # format -> file name relative to the report
    #: the document gate's findings on the drawn figure (:func:`.gate.figure_findings`)
    gate: tuple[str, ...] = ()


_SVG_HEAD = re.compile(r"^.*?(?=<svg)", re.S)


#: figure files a report writes unless asked for more: the SVG it inlines
DEFAULT_FIGURE_FORMATS = ("svg",)
FIGURE_FORMATS = ("svg", "pdf", "png")


def save_figure(spec: FigureSpec, fig_id: str, folder: Path,
                formats: tuple[str, ...] = DEFAULT_FIGURE_FORMATS) -> SavedFigure:
    """Save one figure as SVG (always: the HTML inlines it) and as the other ``formats``
    asked for (PDF, PNG), with reproducible bytes.

    Standalone PDF/PNG files are made only on request (``[report] figure_formats``): a
    PDF export embeds and subsets its fonts, which costs more than drawing the figure.
    The document gate reads the figure as saved (a few milliseconds): its findings come
    with the result.
    """
    from .gate import figure_findings
    from .plots.finish import finish_figure

    folder.mkdir(parents=True, exist_ok=True)
    finish_figure(spec.figure)
    files = {}
    svg_text = ""
    gate: list[str] = []
    wanted = ["svg", *(f for f in FIGURE_FORMATS if f in formats and f != "svg")]
    for fmt_name in wanted:
        data = figure_bytes(spec.figure, fig_id, fmt_name)
        name = f"{fig_id}.{fmt_name}"
        atomic_write(folder / name, data)
        files[fmt_name] = f"{folder.name}/{name}"
        if fmt_name == "svg":
            svg_text = _SVG_HEAD.sub("", data.decode("utf-8"), count=1)
            gate = figure_findings(spec.figure, dpi=72)  # as the SVG was just laid out
    return SavedFigure(id=fig_id, caption=spec.caption, svg=Markup(svg_text), files=files,
                       gate=tuple(gate))


def figure_bytes(figure, fig_id: str, fmt: str, dpi=None) -> bytes:
    """One file format of a figure, with reproducible bytes: no dates or software names,
    SVG ids salted with the figure's id (so figures inlined on one page never clash).
    ``dpi``: None for the style's savefig.dpi, "figure" for the figure's own."""
    metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None},
                "png": {"Software": None}}[fmt]
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.hashsalt": fig_id, "svg.id": fig_id}):
        figure.savefig(buf, format=fmt, metadata=metadata, dpi=dpi)
    return buf.getvalue()


def figure_formats(data: ArchiveData) -> tuple[str, ...]:
    """The figure files the archived config asks for: ``[report] figure_formats`` (and
    the older ``png = true``), always with SVG first."""
    report = data.config.get("report", {}) or {}
    asked = set(report.get("figure_formats", DEFAULT_FIGURE_FORMATS))
    if report.get("png", False):
        asked.add("png")
    return tuple(f for f in FIGURE_FORMATS if f in asked or f == "svg")


# ------------------------------------------------------------------- context
def kind_of_archive(data: ArchiveData):
    """The scene kind that draws this archive (its report-side classmethods)."""
    if data.format_version < 2:
        raise ReportError(f"{data.path}: written by format_version {data.format_version}, which "
                          "does not hold the curves and references a report draws; run its "
                          "config again (reportgen run) to rebuild it")
    try:
        return get_kind(data.kind)
    except KeyError:
        raise ReportError(f"{data.path}: kind {data.kind!r} is unknown to this reportgen") \
            from None


#: bump when the figure drawing changes in a way a cached figure set must not survive
FIGURES_FORMAT = 3


def figures_key(data: ArchiveData, formats: tuple[str, ...]) -> str:
    """Content key of the figures stage: what the archive's numbers are, which sections
    are drawn, the reportgen version and the kind's drawing code
    (:meth:`~reportgen.scene.base.Scene.report_code`).
    A title edit leaves it unchanged."""
    scene = kind_of_archive(data)
    blob = json.dumps({"physics": data.attrs.get("physics_key", ""),
                       "sections": [s.name for s in scene.chosen_sections(data)],
                       "files": list(formats), "reportgen": __version__,
                       "code": scene.report_code(), "format": FIGURES_FORMAT},
                      sort_keys=True)
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


def draw_sections(data: ArchiveData, out_dir: Path,
                  formats: tuple[str, ...] = DEFAULT_FIGURE_FORMATS,
                  jobs: int = 1, for_pdf: bool = False,
                  helper: FigureHelper | None = None) -> list[dict[str, Any]]:
    """The figures stage: draw every chosen section of the archive into ``out_dir/figures``.

    Returns the sections as plain dicts (title, facts, tables, notes, figure files); they
    are kept in ``figures/sections.json`` with the stage's key, so a later report whose
    archive numbers and section list are unchanged reuses them without drawing.
    ``jobs > 1`` (the edit loop's single scene) draws with a second process, ``helper``
    if one was started ahead (:class:`FigureHelper`), else one forked now; this process
    and the helper take the sections one at a time, so neither waits on the other's
    share: the helper from the first section on, this process from the last back (the
    first sections are the headline ones and often the heaviest, and this process may
    still pay its first figure's imports).  Each figure's bytes depend only on the
    archive and its id, not on who drew it.
    ``for_pdf``: also make the figures' slim copies for the PDF (:func:`slim_cache`).
    """
    scene = kind_of_archive(data)
    chosen = list(scene.chosen_sections(data))
    if helper is None and (jobs <= 1 or len(chosen) <= 1 or not data.path):
        return [_draw_section(scene, section, data, out_dir, formats, for_pdf)
                for section in chosen]
    own = helper is None
    if own:
        helper = FigureHelper(warm=False)
    try:
        helper.start(data.path, out_dir, formats, for_pdf, len(chosen))
        drawn = {}
        while (i := helper.claim_last()) >= 0:
            drawn[i] = _draw_section(scene, chosen[i], data, out_dir, formats, for_pdf)
        drawn.update(helper.result())
    finally:
        if own:
            helper.close()
    return [drawn[i] for i in range(len(chosen))]


class FigureHelper(JobProcess):
    """A forked process that draws sections of a scene's figures next to this one.

    Started before the scene simulates (``warm=True``), it imports matplotlib and draws
    a throwaway figure with mathtext meanwhile, at low priority (the simulation's timed
    runs keep their core); by the figures stage it draws at full speed, without the
    first-figure cost (~0.4 s) a process forked then would pay.  It reads the archive
    itself: what it draws is a function of the archive alone, as everywhere."""

    def __init__(self, warm: bool = True):
        from multiprocessing import get_context

        # shared: [first, end) of the sections nobody draws yet
        self._left = get_context("fork").Array("i", 2)
        super().__init__(_figure_helper_main, self._left, warm)
        self._closed = False
        #: the sections the helper drew (their indices), job by job
        self.result_indices: list[list[int]] = []

    def start(self, archive: str, out_dir: Path, formats, for_pdf: bool,
              sections: int) -> None:
        """Hand the helper one archive's ``sections`` sections."""
        with self._left.get_lock():
            self._left[0], self._left[1] = 0, sections
        self.jobs.send((str(archive), str(out_dir), tuple(formats), for_pdf))

    def claim_last(self) -> int:
        """The index of the last section nobody draws yet, or -1 when none is left."""
        return _claim(self._left, last=True)

    def result(self) -> dict[int, dict[str, Any]]:
        """The sections the helper drew, by index; raises what it raised."""
        try:
            result = self.results.recv()
        except EOFError:
            result = RuntimeError(f"figure process ended without a result "
                                  f"(exit code {self.proc.exitcode})")
        if isinstance(result, BaseException):
            raise result
        self.result_indices.append(sorted(result))
        return result

    def close(self) -> None:
        """Stop the helper (at once if idle; twice is harmless)."""
        if self._closed:
            return
        self._closed = True
        self.stop()


def _claim(left, last: bool = False) -> int:
    """The first (or ``last``) index of the range ``left`` = [first, end) of sections
    nobody draws yet, taken out of it; -1 when it is empty."""
    with left.get_lock():
        if left[0] >= left[1]:
            return -1
        if last:
            left[1] -= 1
            return left[1]
        left[0] += 1
        return left[0] - 1


def _figure_helper_main(jobs, results, left, warm: bool) -> None:
    if warm:
        try:
            os.nice(10)
        except OSError:
            pass
        try:
            _warm_up_drawing()
        except Exception:  # noqa: BLE001 - only a head start; the job reports real problems
            pass

    def draw(job):
        archive, out_dir, formats, for_pdf = job
        try:
            data = read_archive(Path(archive))
            scene = kind_of_archive(data)
            chosen = list(scene.chosen_sections(data))
            mine = {}
            while (i := _claim(left)) >= 0:
                mine[i] = _draw_section(scene, chosen[i], data, Path(out_dir), formats,
                                        for_pdf)
            return mine
        except BaseException as exc:  # noqa: BLE001 - re-raised in the parent
            return RuntimeError(f"{type(exc).__name__}: {exc}")

    serve(jobs, results, draw)


def _warm_up_drawing() -> None:
    """What a process's first figure pays once: the style, fonts, mathtext's parser and
    the SVG writer."""
    from .plots.style import new_figure

    fig, ax = new_figure()
    ax.plot([0.0, 1.0], [0.0, 1.0], label=r"$\theta_1$")
    ax.set_xlabel(r"$t$ [s]")
    ax.set_ylabel(r"$\omega^2 - \dot\phi$ [rad/s]")
    ax.legend()
    figure_bytes(fig, "warm-up", "svg")
    fig.clear()


def slim_cache(out_dir: Path) -> Path:
    """The folder of the figures' slim copies that the PDF renders (made by the figures
    stage when a PDF is wanted, else by the first PDF)."""
    return Path(out_dir) / ".pdf-figures"


def _draw_section(scene, section, data: ArchiveData, out_dir: Path,
                  formats: tuple[str, ...], for_pdf: bool = False) -> dict[str, Any]:
    content: SectionContent = getattr(scene, f"section_{section.name}")(data)
    figures = []
    for spec in content.figures:
        saved = save_figure(spec, f"{section.name}-{spec.name}", out_dir / "figures", formats)
        figures.append({"id": saved.id, "caption": saved.caption, "files": saved.files,
                        "gate": list(saved.gate)})
        spec.figure.clear()
        if for_pdf:  # here, in the drawing processes, rather than in the PDF stage
            from .svgslim import warm_cache

            warm_cache(str(saved.svg), slim_cache(out_dir))
    return _section_record(section, content, figures)


def _section_record(section, content: SectionContent, figures: list[dict]) -> dict[str, Any]:
    """A drawn section as the plain dict the figures manifest keeps and the page renders."""
    return {
        "name": section.name, "title": section.title, "description": section.description,
        "figures": figures,
        "content": {"facts": [list(f) for f in content.facts],
                    "tables": [{"caption": t.caption, "header": list(t.header),
                                "rows": [list(r) for r in t.rows]} for t in content.tables],
                    "notes": list(content.notes),
                    "equations": [list(e) for e in content.equations]},
    }


def report_text(data: ArchiveData) -> str:
    """What a reader of the scene's report reads, as one line of text: its page's visible
    text (typeset, without the appended configuration and the footer) followed by the
    words of every figure (titles, axis labels, legend entries, annotations).  The figures
    are drawn but not saved, and nothing is written: what the claims test reads
    (:mod:`reportgen.scene.claims`)."""
    from .plots.finish import figure_words

    scene = kind_of_archive(data)
    sections, words = [], []
    for section in scene.chosen_sections(data):
        content: SectionContent = getattr(scene, f"section_{section.name}")(data)
        figures = []
        for spec in content.figures:
            words += figure_words(spec.figure)
            figures.append({"id": f"{section.name}-{spec.name}", "caption": spec.caption,
                            "files": {}, "svg": Markup("")})
            spec.figure.clear()
        sections.append(_section_record(section, content, figures))
    page = render_html(build_context(data, None, sections=sections, inline=False))
    return visible_text(page) + " " + " ".join(" ".join(w.split()) for w in words)


def cached_sections(out_dir: Path, key: str) -> list[dict[str, Any]] | None:
    """The figures stage's stored result if its key is ``key`` and every file is there.

    The manifest is read back from the output folder, so it is validated first
    (:func:`reportgen.support.layout.figure_manifest`: its shape, and every file a figure of its
    format inside ``figures/``) and so is every SVG the report would inline: the sanitizer
    (:func:`reportgen.support.svgsafe.svg_safe`) must find nothing to leave out; anything
    else is not reused: the figures are drawn again, over it."""
    from ..support.layout import figure_manifest

    stored = figure_manifest(out_dir)
    if stored is None or stored["key"] != key:
        return None
    for section in stored["sections"]:
        for fig in section["figures"]:
            try:
                svg = read_back(out_dir / fig["files"]["svg"], MAX_FIGURE_BYTES,
                                follow_links=True)  # a link inside figures/: checked above
            except OSError:
                return None
            if not svg_safe(svg):
                return None
    return stored["sections"]


SECTIONS_FILE = "sections.json"


def figures_stage(data: ArchiveData, out_dir: Path, formats: tuple[str, ...] | None = None,
                  force: bool = False, jobs: int = 1, for_pdf: bool = False,
                  helper: FigureHelper | None = None) -> tuple[list[dict[str, Any]], bool]:
    """(sections, drawn?): reuse the stored figures when current, else draw them.

    ``formats``: the figure files to write; default from the archived config.
    ``jobs``, ``helper``: see :func:`draw_sections`."""
    formats = figure_formats(data) if formats is None else formats
    key = figures_key(data, formats)
    if not force:
        cached = cached_sections(out_dir, key)
        if cached is not None:
            return cached, False
    sections = draw_sections(data, out_dir, formats, jobs, for_pdf, helper)
    (out_dir / "figures").mkdir(parents=True, exist_ok=True)
    atomic_write(out_dir / "figures" / SECTIONS_FILE, json.dumps(
        {"key": key, "sections": sections}, ensure_ascii=False,
        indent=1).encode("utf-8"))
    return sections, True


def _with_inline_svg(sections: list[dict[str, Any]], out_dir: Path) -> list[dict[str, Any]]:
    """The sections with each figure's SVG drawing, read from ``out_dir/figures`` only (a
    file named outside it, through ``..``, an absolute path or a link, is a ReportError)
    and inlined as the sanitizer writes it (:func:`reportgen.support.svgsafe.clean_svg`)."""
    figures_dir = os.path.realpath(out_dir / "figures")
    out = []
    for section in sections:
        figures = []
        for fig in section["figures"]:
            path = out_dir / fig["files"]["svg"]
            if os.path.dirname(os.path.realpath(path)) != figures_dir:
                raise ReportError(f"{path}: not a figure file inside {out_dir / 'figures'}; "
                                  "not read")
            try:
                svg = clean_svg(read_back(path, MAX_FIGURE_BYTES, follow_links=True)).svg
            except (OSError, SvgRefused) as exc:
                raise ReportError(f"{path}: not a figure to inline ({exc})") from None
            figures.append({**fig, "svg": Markup(svg)})
        out.append({**section, "figures": figures})
    return out


def build_context(data: ArchiveData, out_dir: Path | None,
                  sections: list[dict[str, Any]] | None = None,
                  inline: bool = True) -> dict[str, Any]:
    """The one plain dict the scene template renders.  ``inline``: read each figure's
    SVG from ``out_dir/figures`` (else the sections carry their own ``svg``)."""
    scene = kind_of_archive(data)
    if sections is None:
        sections, _ = figures_stage(data, out_dir)
    if inline:
        sections = _with_inline_svg(sections, out_dir)
    runs = []
    labels = method_labels(data)
    for name, run in data.runs.items() if data.sweep is None else ():  # members: their section
        a = run.attrs
        runs.append({"name": name, "method": a.get("method"),
                     "method_label": labels.get(str(a.get("method")),
                                                method_words(str(a.get("method", "")))),
                     "reason": a.get("method_reason", ""),
                     "nfev": a.get("nfev"), "nsteps": a.get("nsteps"),
                     "nreject": a.get("nreject"), "wall_time_s": a.get("wall_time_s"),
                     "compile_time_s": a.get("compile_time_s"), "status": a.get("status"),
                     "message": a.get("message", ""), "samples": len(run.t),
                     "rtol": _setting_value(a.get("rtol")), "atol": _setting_value(a.get("atol")),
                     "step": _step_text(a.get("h"), scene.schema.time.unit
                                        if scene.schema is not None else "s")})
    return {
        "title": data.title,
        "kind": scene.kind,
        "kind_summary": scene.summary,
        "description": scene.subtitle(data),
        "case": scene.prose_case(data),
        "scene_name": data.attrs.get("scene", ""),
        "status": data.status,
        "message": data.message,
        "checks": [dataclasses.replace(c, quantity=scene.check_words(data, c.quantity),
                                       source=scene.check_words(data, c.source))
                   for c in data.checks],
        "behaviour": scene.behaviour(data),  # physical behaviour, beside the status (issue 31)
        "headline": (scene.sweep_headline(data) if data.sweep is not None
                     else scene.headline(data)),
        "sweep": data.sweep is not None,
        "runs": runs,
        "wall_time_s": float(data.attrs.get("wall_time_s", 0.0)),
        "sections": sections,
        "config_text": data.config_text,
        "study_methods": ([] if data.study is None
                          else list(dict.fromkeys(str(m) for m in data.study["method"]))),
        "study_calls": _library_calls(data),
        "cached_machines": _cached_machines(data),
        "attrs": data.attrs,
        # the colophon names the software; the processor and code hashes are for inspect
        "provenance": {k: data.provenance[k] for k in LIBRARIES if k in data.provenance},
        "version": __version__,
    }


def _setting_value(value) -> str | None:
    """A run's tolerance as the colophon lists it ("1e-12"), None where it has none."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return f"{value:g}" if math.isfinite(value) and value > 0 else None


#: the library routine each peer of the study calls (named in the colophon, not the body)
_PEER_CALLS = {"scipy": "scipy.integrate.solve_ivp", "heyoka": "heyoka.taylor_adaptive",
               "rebound": "rebound.Simulation"}


def _library_calls(data: ArchiveData) -> list[str]:
    """The library routines the study's peer runs went through."""
    if data.study is None:
        return []
    methods = {str(m) for m in data.study["method"]}
    return [call for prefix, call in _PEER_CALLS.items()
            if any(m == prefix or m.startswith(prefix + "_") for m in methods)]


def _cached_machines(data: ArchiveData) -> list[str]:
    """Where the study's rows taken from the peer cache were measured (the colophon's)."""
    study = data.study
    if study is None or "cached" not in (study.dtype.names or ()):
        return []
    cached = study[study["cached"].astype(bool)]
    return sorted({f"{str(r['machine'])}, {str(r['measured_at'])}" for r in cached})


def _step_text(h, unit: str) -> str:
    """"step h = 0.6 s" of a fixed-step run (the step it took, from the archive), else ""."""
    try:
        h = float(h)
    except (TypeError, ValueError):
        return ""
    if not math.isfinite(h) or h <= 0:
        return ""
    shown = unit_text(unit)
    return f"step h = {fmt(h)}" + (f" {shown}" if shown not in ("", "dimensionless") else "")


def method_labels(data: ArchiveData) -> dict[str, str]:
    """Each integrator's label as the archive's study table names it ("scipy RK45")."""
    study = data.study
    if study is None or len(study) == 0 or "label" not in (study.dtype.names or ()):
        return {}
    return {str(m): str(lab) for m, lab in zip(study["method"], study["label"], strict=True)}


def render_html(context: dict[str, Any]) -> str:
    """The scene's report page, ending with the documents its text cites, typeset
    (:func:`reportgen.scene.typeset.typeset_html`), its control characters and
    bidirectional overrides shown, not acted on (:func:`~reportgen.support.layout.visible_controls`)."""
    return visible_controls(typeset_html(with_sources(
        environment().get_template("scene.html.j2").render(**context))))


def build_report(archive_path: Path, formats=("html", "pdf"), out_dir: Path | None = None,
                 figure_files: tuple[str, ...] | None = None,
                 force_figures: bool = False,
                 timings: dict[str, float] | None = None, jobs: int = 1,
                 pdf_worker: PdfWorker | None = None,
                 figure_helper: FigureHelper | None = None) -> list[Path]:
    """The figures and report stages of one archive, next to it (or into ``out_dir``).

    Figures are redrawn only when their key changed (or ``force_figures``);
    ``figure_files`` overrides the config's ``[report] figure_formats``.  ``timings``,
    if given, receives the seconds spent on figures, html and pdf; ``jobs`` processes
    draw the figures (with ``figure_helper`` if one was started ahead); ``pdf_worker``
    renders the PDF."""
    archive_path = Path(archive_path)
    data = read_archive(archive_path)
    out_dir = Path(out_dir) if out_dir is not None else archive_path.parent
    out_dir.mkdir(parents=True, exist_ok=True)
    timings = {} if timings is None else timings
    t0 = time.perf_counter()
    sections, _ = figures_stage(data, out_dir, figure_files, force=force_figures, jobs=jobs,
                                for_pdf="pdf" in formats, helper=figure_helper)
    timings["figures"] = time.perf_counter() - t0
    context = build_context(data, out_dir, sections=sections)
    pages: list[str] = []
    written = write_formats(render_html(context), out_dir, formats, timings, pdf_worker, pages)
    write_gate(out_dir, gate_findings(sections, pages))
    return written


def write_formats(html_text: str, out_dir: Path, formats,
                  timings: dict[str, float] | None = None,
                  pdf_worker: PdfWorker | None = None,
                  gate: list[str] | None = None) -> list[Path]:
    """``report.html`` and/or ``report.pdf`` (WeasyPrint's rendering of the same HTML);
    ``gate``, if given, receives the document gate's findings on the PDF's pages."""
    timings = {} if timings is None else timings
    written = []
    if "html" in formats:
        t0 = time.perf_counter()
        atomic_write(out_dir / "report.html", html_text.encode("utf-8"))
        written.append(out_dir / "report.html")
        timings["html"] = time.perf_counter() - t0
    if "pdf" in formats:
        t0 = time.perf_counter()
        found = (pdf_worker.write_pdf if pdf_worker is not None else write_pdf)(
            html_text, out_dir / "report.pdf", out_dir, slim_cache=slim_cache(out_dir))
        if gate is not None:
            gate.extend(found)
        written.append(out_dir / "report.pdf")
        timings["pdf"] = time.perf_counter() - t0
    return written


def build_index(out_dir: Path, groups: list[dict[str, Any]]) -> Path:
    """``index.html``: the gallery of every scene in ``out_dir`` (written atomically);
    ``groups``: the cards by kind (:func:`reportgen.pipeline.stages.gallery_groups`)."""
    text = visible_controls(typeset_html(environment().get_template("index.html.j2").render(
        groups=groups, count=sum(len(g["entries"]) for g in groups), version=__version__,
        created=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"))))
    path = Path(out_dir) / "index.html"
    atomic_write(path, text.encode("utf-8"))
    return path


def build_audit_report(audit_path: Path, formats=("html", "pdf")) -> list[Path]:
    """Render the audit table and the figures of every case that is not ok."""
    audit_path = Path(audit_path)
    data = read_audit(audit_path)
    out_dir = audit_path.parent
    figures = [save_figure(FigureSpec("overview", audit_plots.overview(data["table"]),
                                      "Every run of every case: invariant drift against "
                                      "disagreement with the reference."),
                           "audit-overview", out_dir / "figures")]
    flagged = []
    for i, case in enumerate(data["cases"]):
        if case["verdict"] == "ok" or not case["runs"]:
            continue
        fig = audit_plots.case_drift(case["runs"])
        saved = save_figure(FigureSpec(f"case{i}", fig, f"{case['name']}: {case['reason']}"),
                            f"audit-case{i}", out_dir / "figures")
        flagged.append({"case": case, "figure": saved})
    rows = [{name: row[name] for name in data["table"].dtype.names} for row in data["table"]]
    html_text = visible_controls(typeset_html(environment().get_template("audit.html.j2").render(
        rows=rows, cases=data["cases"], overview=figures[0], flagged=flagged,
        attrs=data["attrs"], provenance=data["provenance"], version=__version__)))
    return write_formats(html_text, out_dir, formats)
