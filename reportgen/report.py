"""Reports: the only module that touches jinja2 and the PDF engine.

The report step reads an archive and nothing else: the scene is rebuilt from
the config text stored in the archive, its sections draw their figures from the
archived arrays, and one jinja2 environment renders one context dict.  The PDF
is WeasyPrint's rendering of the same HTML.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import jinja2
import matplotlib
from markupsafe import Markup

from . import __version__
from .archive import ArchiveData, read_archive
from .config import ConfigError, parse_config_text
from .fsutil import atomic_write
from .scenes import get_kind
from .scenes.base import FigureSpec, SectionContent, fmt, fmt_err

TEMPLATE_DIRS = (
    Path(__file__).resolve().parent / "templates",  # installed wheel
    Path(__file__).resolve().parent.parent / "templates",  # source checkout
)


class ReportError(Exception):
    pass


def _template_dir() -> Path:
    for d in TEMPLATE_DIRS:
        if (d / "scene.html.j2").exists():
            return d
    raise ReportError("templates/ not found next to the reportgen package")


_ENV: jinja2.Environment | None = None


def environment() -> jinja2.Environment:
    """The single jinja2 environment (autoescape on, undefined variables are errors)."""
    global _ENV
    if _ENV is None:
        _ENV = jinja2.Environment(
            loader=jinja2.FileSystemLoader(_template_dir()),
            autoescape=True,
            undefined=jinja2.StrictUndefined,
            trim_blocks=True,
            lstrip_blocks=True,
        )
        _ENV.filters["num"] = fmt
        _ENV.filters["err"] = fmt_err
    return _ENV


# ------------------------------------------------------------------- figures
@dataclass
class SavedFigure:
    id: str
    caption: str
    svg: Markup
    files: dict[str, str]  # format -> file name relative to the report


_SVG_HEAD = re.compile(r"^.*?(?=<svg)", re.S)


def save_figure(spec: FigureSpec, fig_id: str, folder: Path, png: bool = False) -> SavedFigure:
    """Save one figure as SVG and PDF (PNG on request) with reproducible bytes."""
    folder.mkdir(parents=True, exist_ok=True)
    files = {}
    svg_text = ""
    formats = ("svg", "pdf", "png") if png else ("svg", "pdf")
    with matplotlib.rc_context({"svg.hashsalt": fig_id, "svg.id": fig_id}):
        for fmt_name in formats:
            buf = io.BytesIO()
            metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None},
                        "png": {"Software": None}}[fmt_name]
            spec.figure.savefig(buf, format=fmt_name, metadata=metadata)
            data = buf.getvalue()
            name = f"{fig_id}.{fmt_name}"
            atomic_write(folder / name, data)
            files[fmt_name] = f"{folder.name}/{name}"
            if fmt_name == "svg":
                svg_text = _SVG_HEAD.sub("", data.decode("utf-8"), count=1)
    return SavedFigure(id=fig_id, caption=spec.caption, svg=Markup(svg_text), files=files)


# ------------------------------------------------------------------- context
def scene_from_archive(data: ArchiveData):
    """Rebuild the scene object from the config text stored in the archive."""
    source = parse_config_text(data.config_text, path=None)
    source = type(source)(path=data.path, text=source.text, data=source.data)
    try:
        return get_kind(data.kind).from_source(source)
    except ConfigError as exc:
        raise ReportError(f"{data.path}: stored config no longer validates: {exc}") from None


def build_context(data: ArchiveData, out_dir: Path, png: bool = False) -> dict[str, Any]:
    """The one plain dict the scene template renders."""
    scene = scene_from_archive(data)
    sections = []
    for section in scene.chosen_sections():
        if section.integrates and "main" not in data.runs:
            continue
        content: SectionContent = getattr(scene, f"section_{section.name}")(data)
        figures = []
        for spec in content.figures:
            figures.append(save_figure(spec, f"{section.name}-{spec.name}", out_dir / "figures",
                                       png=png))
            spec.figure.clear()
        sections.append({"name": section.name, "title": section.title, "content": content,
                         "figures": figures, "description": section.description})
    runs = []
    for name, run in data.runs.items():
        a = run.attrs
        runs.append({"name": name, "method": a.get("method"), "reason": a.get("method_reason", ""),
                     "nfev": a.get("nfev"), "nsteps": a.get("nsteps"),
                     "nreject": a.get("nreject"), "wall_time_s": a.get("wall_time_s"),
                     "compile_time_s": a.get("compile_time_s"), "status": a.get("status"),
                     "message": a.get("message", ""), "samples": len(run.t)})
    return {
        "title": scene.title,
        "kind": scene.kind,
        "kind_summary": scene.summary,
        "scene_name": data.attrs.get("scene", ""),
        "status": data.status,
        "message": data.message,
        "checks": data.checks,
        "headline": scene.headline(data),
        "runs": runs,
        "wall_time_s": float(data.attrs.get("wall_time_s", 0.0)),
        "sections": sections,
        "config_text": data.config_text,
        "attrs": data.attrs,
        "provenance": data.provenance,
        "version": __version__,
    }


def render_html(context: dict[str, Any]) -> str:
    return environment().get_template("scene.html.j2").render(**context)


def write_pdf(html_text: str, target: Path, base_url: Path) -> None:
    import logging

    import weasyprint

    logging.getLogger("weasyprint").setLevel(logging.ERROR)
    logging.getLogger("fontTools").setLevel(logging.ERROR)
    pdf = weasyprint.HTML(string=html_text, base_url=str(base_url)).write_pdf()
    atomic_write(target, pdf)


def build_report(archive_path: Path, formats=("html", "pdf"), out_dir: Path | None = None,
                 png: bool | None = None) -> list[Path]:
    """Render the report(s) of one archive next to it (or into ``out_dir``)."""
    archive_path = Path(archive_path)
    data = read_archive(archive_path)
    out_dir = Path(out_dir) if out_dir is not None else archive_path.parent
    out_dir.mkdir(parents=True, exist_ok=True)
    if png is None:
        png = _config_wants_png(data)
    context = build_context(data, out_dir, png=png)
    return write_formats(render_html(context), out_dir, formats)


def write_formats(html_text: str, out_dir: Path, formats) -> list[Path]:
    """``report.html`` and/or ``report.pdf`` (WeasyPrint's rendering of the same HTML)."""
    written = []
    if "html" in formats:
        atomic_write(out_dir / "report.html", html_text.encode("utf-8"))
        written.append(out_dir / "report.html")
    if "pdf" in formats:
        write_pdf(html_text, out_dir / "report.pdf", out_dir)
        written.append(out_dir / "report.pdf")
    return written


def _config_wants_png(data: ArchiveData) -> bool:
    try:
        return bool(parse_config_text(data.config_text).data.get("report", {}).get("png", False))
    except (ConfigError, AttributeError):
        return False


def build_index(out_dir: Path, entries: list[dict[str, Any]]) -> Path:
    """``index.html`` linking every scene of a batch."""
    text = environment().get_template("index.html.j2").render(
        entries=entries, version=__version__,
        created=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"))
    path = Path(out_dir) / "index.html"
    atomic_write(path, text.encode("utf-8"))
    return path


def build_audit_report(audit_path: Path, formats=("html", "pdf")) -> list[Path]:
    """Render the audit table and the figures of every case that is not ok."""
    from .archive import read_audit
    from .plots import audit as audit_plots
    from .scenes.base import FigureSpec

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
    html_text = environment().get_template("audit.html.j2").render(
        rows=rows, cases=data["cases"], overview=figures[0], flagged=flagged,
        attrs=data["attrs"], provenance=data["provenance"], version=__version__)
    return write_formats(html_text, out_dir, formats)
