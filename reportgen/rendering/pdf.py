"""The PDF stage: WeasyPrint's rendering of a report's HTML, in this process or in a
worker process started ahead of time.

WeasyPrint costs about three quarters of a second to import (most of it loading Pango,
HarfBuzz and fontconfig) and a few tenths more on a process's first document.  The edit
loop's one scene therefore hands its PDF to a :class:`PdfWorker` forked when the command
starts, which pays both while the scene is validated, simulated and drawn.  This module
imports only the standard library at first, so that fork comes early.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from ..errors import ReportError
from ..support.forked import JobProcess, serve
from ..support.fsutil import atomic_write
from ..support.layout import edited_count

__all__ = ["write_pdf", "PdfWorker", "edit_loop_worker"]


def prepare_html(html_text: str, folder: Path, slim_cache: Path | None = None,
                 used: set[Path] | None = None) -> str:
    """The HTML WeasyPrint gets: each inline ``<svg>`` figure becomes an ``<img>`` of a
    slimmed copy (still vector, text still text), so the HTML parser and the CSS cascade
    never walk the figures' nodes and the SVG drawer has fewer of them.  The copies are
    taken from (or made into) ``slim_cache`` when given, recording the ones used in
    ``used``, else written into ``folder``.  report.html keeps the SVG as saved."""
    from .svgslim import inline_svgs_as_images

    return inline_svgs_as_images(html_text, folder=folder, cache=slim_cache, used=used)


def render_pdf(html_for_pdf: str, target: Path, base_url: Path) -> list[str]:
    """WeasyPrint's PDF of prepared HTML, written atomically to ``target``; returns the
    document gate's findings on the laid-out pages (:func:`.gate.page_findings`, read
    between layout and writing, a few milliseconds)."""
    import gc
    import logging

    import weasyprint

    from .gate import page_findings

    logging.getLogger("weasyprint").setLevel(logging.ERROR)
    logging.getLogger("fontTools").setLevel(logging.ERROR)
    # WeasyPrint allocates hundreds of thousands of short-lived objects; at the default
    # gen-0 threshold (700) the cyclic collector takes a tenth of the PDF time.
    gc_thresholds = gc.get_threshold()
    gc.set_threshold(max(10_000, gc_thresholds[0]), *gc_thresholds[1:])
    try:
        fonts, font_config = _font_faces()
        html = weasyprint.HTML(string=html_for_pdf, base_url=str(base_url))
        document = html.render(stylesheets=[fonts], font_config=font_config)
        findings = page_findings(document)
        for layout in _fill_layouts() if _short_pages(findings) else ():
            # a page under a quarter full (the configuration's last lines alone, say): the
            # appended configuration set another way, kept if it leaves fewer short pages
            other = html.render(stylesheets=[fonts, layout], font_config=font_config)
            other_findings = page_findings(other)
            if _short_pages(other_findings) < _short_pages(findings):
                document, findings = other, other_findings
            if not _short_pages(findings):
                break
        pdf = document.write_pdf()
    finally:
        gc.set_threshold(*gc_thresholds)
    atomic_write(target, pdf)
    return findings


def _short_pages(findings: list[str]) -> int:
    """How many of the gate's findings are pages less than a quarter full."""
    return sum(": fill: " in f for f in findings)


#: other layouts, tried in turn when the first leaves a page less than a quarter full:
#: the appended configuration in two columns (its tail then fits the page before); a
#: section's introduction free to end a page (kept with its figure, a long one can push
#: both overleaf); both; the configuration starting a page of its own, with and without
#: (WeasyPrint takes these as user style sheets, below the page's own: hence !important)
_COMPACT_CONFIG = ("pre.config { column-count: 2 !important; column-gap: 1.5em !important; "
                   "font-size: 0.7em !important; orphans: 4 !important; "
                   "widows: 4 !important; }")
_LOOSE_KEEPS = ("h2 + p, h2 + p + dl.facts { break-after: auto !important; "
                "break-inside: auto !important; }")
_CONFIG_PAGE = "#config { break-before: page !important; }"
FILL_LAYOUTS = (_COMPACT_CONFIG, _LOOSE_KEEPS, _COMPACT_CONFIG + _LOOSE_KEEPS, _CONFIG_PAGE,
                _CONFIG_PAGE + _LOOSE_KEEPS)
_LAYOUTS = None


def _fill_layouts():
    global _LAYOUTS
    if _LAYOUTS is None:
        from weasyprint import CSS

        _LAYOUTS = [CSS(string=css) for css in FILL_LAYOUTS]
    return _LAYOUTS


#: the fonts matplotlib ships that a report uses (family -> {(weight, style): file}): STIX
#: for its body, its figures' words and their mathtext, embedded in the PDF from these
#: files whatever the machine has installed
_SHIPPED_FONTS = {
    "STIXGeneral": {("normal", "normal"): "STIXGeneral.ttf",
                    ("normal", "italic"): "STIXGeneralItalic.ttf",
                    ("bold", "normal"): "STIXGeneralBol.ttf",
                    ("bold", "italic"): "STIXGeneralBolIta.ttf"},
    "STIXNonUnicode": {("normal", "normal"): "STIXNonUni.ttf",
                       ("normal", "italic"): "STIXNonUniIta.ttf",
                       ("bold", "normal"): "STIXNonUniBol.ttf",
                       ("bold", "italic"): "STIXNonUniBolIta.ttf"},
    **{f"STIXSize{n}Sym": {("normal", "normal"): f"STIXSiz{n}SymReg.ttf"}
       for n in ("One", "Two", "Three", "Four", "Five")},
    # the fallback for a character STIX's face lacks (‖ in bold, say): a serif that
    # matplotlib ships too, so that no machine's own fonts decide it
    "DejaVu Serif": {("normal", "normal"): "DejaVuSerif.ttf",
                     ("normal", "italic"): "DejaVuSerif-Italic.ttf",
                     ("bold", "normal"): "DejaVuSerif-Bold.ttf",
                     ("bold", "italic"): "DejaVuSerif-BoldItalic.ttf"},
}


def font_face_css() -> str:
    """``@font-face`` rules for the STIX fonts in matplotlib's data folder (found without
    importing matplotlib); "" where they are not there."""
    import importlib.util

    spec = importlib.util.find_spec("matplotlib")
    if spec is None or not spec.submodule_search_locations:
        return ""
    folder = Path(spec.submodule_search_locations[0]) / "mpl-data" / "fonts" / "ttf"
    rules = []
    for family, faces in _SHIPPED_FONTS.items():
        for (weight, style), name in faces.items():
            path = folder / name
            if path.is_file():
                rules.append(f'@font-face {{ font-family: "{family}"; font-weight: {weight}; '
                             f'font-style: {style}; src: url("{path.as_uri()}"); }}')
    return "\n".join(rules)


_FONTS = None


def _font_faces():
    """(stylesheet, font configuration) of :func:`font_face_css`, made once per process:
    WeasyPrint loads each font file when a document first uses it."""
    global _FONTS
    if _FONTS is None:
        from weasyprint import CSS
        from weasyprint.text.fonts import FontConfiguration

        config = FontConfiguration()
        _FONTS = (CSS(string=font_face_css(), font_config=config), config)
    return _FONTS


def write_pdf(html_text: str, target: Path, base_url: Path,
              slim_cache: Path | None = None, render=render_pdf) -> list[str]:
    """``target``: the PDF of a report's HTML (figures as vector images).  ``slim_cache``:
    the folder of the figures' slim copies (kept for the next render, pruned to this one's).
    ``render(html_for_pdf, target, base_url)`` does the rendering (a worker's, say) and
    returns the document gate's findings on the pages, which this returns."""
    used: set[Path] = set()
    with tempfile.TemporaryDirectory(prefix="reportgen-pdf-") as folder:
        findings = render(prepare_html(html_text, Path(folder), slim_cache, used), target,
                          base_url)
    if slim_cache is not None and Path(slim_cache).is_dir():
        from .svgslim import prune_cache

        prune_cache(slim_cache, used)
    return list(findings or ())


class PdfWorker(JobProcess):
    """A forked process that imports WeasyPrint at once, warms it up on a one-page
    document unless a job is already waiting, and renders PDFs when asked.

    The figures are slimmed here, in the asking process, while the worker may still be
    importing; the worker only renders."""

    def __init__(self):
        super().__init__(_worker_main)
        self._used = self._closed = False
        #: started on a guess (:func:`edit_loop_worker`): the batch stops it when unused
        self.speculative = False

    @property
    def alive(self) -> bool:
        """Whether the worker can still take a job."""
        return not self._closed and self.proc.is_alive()

    def write_pdf(self, html_text: str, target: Path, base_url: Path,
                  slim_cache: Path | None = None) -> list[str]:
        """Render like :func:`write_pdf`, in the worker; raise what it raised, else return
        the pages' gate findings."""
        if self._closed:
            raise ReportError(f"{target}: the PDF process was already stopped")
        self._used = True
        return write_pdf(html_text, target, base_url, slim_cache, render=self._render)

    def _render(self, html_for_pdf: str, target: Path, base_url: Path) -> list[str]:
        try:
            self.jobs.send((html_for_pdf, str(target), str(base_url)))
            error, findings = self.results.recv()
        except (EOFError, OSError):
            error = f"PDF process ended without a result (exit code {self.proc.exitcode})"
        if error is not None:
            raise ReportError(f"{target}: {error}")
        return findings

    def close(self) -> None:
        """Stop the worker: at once if it never rendered (it writes nothing before a job),
        else once it has finished.  Closing twice is harmless."""
        if self._closed:
            return
        self._closed = True
        self.stop(graceful=self._used)


def edit_loop_worker(configs: list[Path], out_root, formats=None, jobs: int | None = None,
                     force: bool = False, scheduler: str | None = None) -> PdfWorker | None:
    """A :class:`PdfWorker` when this run looks like the edit loop's (one scene to render,
    locally, with a PDF, and a second core to prepare it on), else None.  Only a head start:
    the worker is stopped unused if the guess was wrong."""
    if scheduler or (formats is not None and "pdf" not in formats) or jobs == 1:
        return None
    if not (len(configs) == 1 if force else edited_count(configs, out_root) == 1):
        return None
    worker = PdfWorker()
    worker.speculative = True
    return worker


#: how long an imported worker waits for its job before warming up on a document of its
#: own (~0.1 s, which the first real document would otherwise pay): a title edit's HTML
#: arrives about when the import ends, and should not wait for a warm-up
_JOB_GRACE_S = 0.3


def _worker_main(jobs, results) -> None:
    try:
        import weasyprint  # noqa: F401 - the import is most of a cold worker's cost
    except ImportError:
        pass  # the job reports it
    if not jobs.poll(_JOB_GRACE_S):
        try:
            _warm_up()
        except Exception:  # noqa: BLE001 - only a head start; the job reports real problems
            pass
    serve(jobs, results, _render_job)


def _render_job(job) -> tuple[str | None, list[str]]:
    """A job of the worker: (None, the pages' gate findings) once rendered, else (what went
    wrong, []) (the parent raises)."""
    html_for_pdf, target, base_url = job
    try:
        findings = render_pdf(html_for_pdf, Path(target), Path(base_url))
    except Exception as exc:  # noqa: BLE001 - sent to the parent, which raises it
        return f"{type(exc).__name__}: {exc}", []
    return None, findings


#: a figure-like SVG for the warm-up: clipped path, dashes, text in the figures' font
_WARM_UP_SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="120pt" height="60pt" '
    'viewBox="0 0 120 60"><defs><clipPath id="c"><rect x="0" y="0" width="120" '
    'height="60"/></clipPath></defs><g clip-path="url(#c)"><path d="M 0 50 L 40 10 '
    'L 80 30 L 120 5" fill="none" stroke="#1f77b4" stroke-width="1.5" '
    'stroke-dasharray="5.55,2.4"/></g><text x="4" y="58" font-family="STIXGeneral" '
    'font-size="8">−0.5 1e-10 θ ω <tspan font-style="italic">t</tspan></text></svg>')


def _warm_up() -> None:
    """Render a one-page document in the report's stylesheet with one SVG figure: the
    first document of a process pays for font loading and binding setup, so the real
    one does not."""
    import base64

    from ..support.layout import template_dir

    css = (template_dir() / "style.css.j2").read_text(encoding="utf-8")  # no template syntax
    svg = base64.b64encode(_WARM_UP_SVG.encode("utf-8")).decode("ascii")
    html_text = (f"<html><head><style>{css}</style></head><body><h1>Warm-up α</h1>"
                 "<p>Text <b>bold</b> <i>italic</i> <code>code</code> ω₃ θ₁</p>"
                 "<dl class='facts'><dt>a</dt><dd>1.0</dd></dl>"
                 "<table><tr><th>x</th><td>1e-10</td></tr></table><pre>t_end = 1</pre>"
                 f"<figure><img src='data:image/svg+xml;base64,{svg}'>"
                 "<figcaption>caption</figcaption></figure></body></html>")
    with tempfile.TemporaryDirectory(prefix="reportgen-pdf-") as folder:
        render_pdf(html_text, Path(folder) / "warm-up.pdf", Path(folder))
