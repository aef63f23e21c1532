"""Where reportgen's files are: the configs a batch finds, per scene the output folder's
report stamp, and the report templates.  Standard library only, so the command line can
look before it imports anything heavy."""

from __future__ import annotations

import os
import re
import unicodedata
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..errors import ConfigError, ReportError, UsageError
from .fsutil import read_json_back

#: the report formats
FORMATS = ("html", "pdf")

TEMPLATE_DIRS = (
    Path(__file__).resolve().parent.parent / "templates",  # installed wheel
    Path(__file__).resolve().parent.parent.parent / "templates",  # source checkout
)


def collect_configs(paths: Iterable[str | Path]) -> list[Path]:
    """Config files named directly, or every ``*.toml`` below a folder, in sorted order."""
    found: list[Path] = []
    for raw in paths:
        path = Path(raw)
        if path.is_dir():
            found.extend(sorted(p for p in path.rglob("*.toml") if p.is_file()))
        elif path.is_file():
            found.append(path)
        else:
            raise UsageError(f"{path}: no such file or folder")
    unique = list({p.resolve(): p for p in reversed(found)}.values())[::-1]
    if not unique:
        raise UsageError("no *.toml config found in " + ", ".join(str(p) for p in paths))
    return unique


#: names an output folder keeps for itself: a scene may not take them as its folder's name
#: (compared case-insensitively: on a case-insensitive file system they would collide)
RESERVED_NAMES = frozenset({"index.html", "audit"})


def scene_name_problem(name: str) -> str | None:
    """Why ``name`` (a config's file name without ``.toml``) cannot name a scene folder
    under ``--out``, or None when it can: the folder must stay inside ``--out``, be a
    folder of its own and read safely on a terminal and in a link."""
    if name in ("", ".", ".."):
        return "must not be empty, '.' or '..' (the folder would not be inside --out)"
    if name.startswith("."):
        return "must not start with '.' (hidden names are the output folder's own files)"
    if "/" in name or "\\" in name or "\0" in name:
        return "must not contain a path separator"
    if name.lower() in RESERVED_NAMES:
        return (f"is reserved for the output folder's own files "
                f"({', '.join(sorted(RESERVED_NAMES))})")
    try:
        name.encode("utf-8")
    except UnicodeEncodeError:
        return "is not valid UTF-8"
    if any(unicodedata.category(c) in ("Cc", "Zl", "Zp") or c in _BIDI for c in name):
        return "must not contain control characters or bidirectional overrides"
    return None


def scene_name(path: Path) -> str:
    """The scene name of the config file ``path`` (its stem), checked
    (:func:`scene_name_problem`); a bad name is a ConfigError naming the file and the rule."""
    name = Path(path).stem
    problem = scene_name_problem(name)
    if problem is not None:
        raise ConfigError([f"{printable(str(path))}: scene name {printable(repr(name))} "
                           f"(the file name without .toml) {problem}"])
    return name


_BIDI = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\u200e\u200f")


def printable(text: str, newlines: bool = True) -> str:
    """``text`` safe to print on a terminal: control characters (ANSI escapes among them),
    bidirectional overrides and lone surrogates shown as ``\\xNN``/``\\uNNNN`` escapes
    instead of acted on; line breaks kept only when ``newlines``."""
    out = []
    for c in str(text):
        if (c == "\n" and newlines) or c == "\t":
            out.append(c)
        elif unicodedata.category(c) in ("Cc", "Cs") or c in _BIDI:
            code = ord(c)
            out.append(f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}")
        else:
            out.append(c)
    return "".join(out)


#: what a page shows as an escape rather than acts on, as :func:`printable` does on a
#: terminal: C0 and C1 controls but tab, line feed and a carriage return before a line
#: feed (a config written on Windows: white space to HTML), bidirectional overrides and
#: isolates, lone surrogates
_INVISIBLE = re.compile("[\x00-\x08\x0b-\x0c\x0e-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e"
                        "\u2066-\u2069\ud800-\udfff]|\r(?!\n)")


def visible_controls(text: str) -> str:
    """``text`` for a page: control characters and bidirectional overrides shown as
    ``\\xNN``/``\\uNNNN`` (as :func:`printable` shows them on a terminal), so a title
    cannot reverse or hide the text around it."""
    def shown(m: re.Match) -> str:
        code = ord(m.group(0))
        return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"

    return _INVISIBLE.sub(shown, text)


def report_stamp(folder: Path) -> Path:
    """The file naming the archive content a scene folder's reports were rendered from."""
    return Path(folder) / ".report-stamp.json"


def edited_count(configs: list[Path], out_root: str | Path) -> int:
    """How many configs look edited since their report was rendered (a file newer than
    its report stamp, or no stamp): a hint for starting work early, never a decision."""
    count = 0
    for path in configs:
        stamp = report_stamp(Path(out_root) / path.stem)
        try:
            count += path.stat().st_mtime_ns > stamp.stat().st_mtime_ns
        except OSError:
            count += 1
    return count


#: the figures stage's manifest in a scene folder's ``figures/``
SECTIONS_FILE = "sections.json"
#: the figure files a manifest may name, by format
FIGURE_SUFFIXES = {"svg": ".svg", "pdf": ".pdf", "png": ".png"}
#: larger manifests are not read back
MAX_MANIFEST_BYTES = 20_000_000
#: larger figure files are not read back (matplotlib's largest of ours: ~1 MB)
MAX_FIGURE_BYTES = 100_000_000


def figure_manifest(out_dir: Path) -> dict[str, Any] | None:
    """The figures stage's manifest ``out_dir/figures/sections.json``, validated, or None
    when it is missing or not one this reportgen wrote: a JSON object with a text ``key``
    and a list of ``sections``, each with text ``name``/``title``/``description``,
    ``figures`` whose ``files`` are existing files of their format inside ``figures/``
    (relative, no ``..``, no symbolic link leading out), and ``content`` lists.  An
    invalid manifest is simply not reused: the figures are drawn again."""
    figures = Path(out_dir) / "figures"
    index = figures / SECTIONS_FILE
    stored = read_json_back(index, MAX_MANIFEST_BYTES)
    if not (isinstance(stored, dict) and isinstance(stored.get("key"), str)
            and isinstance(stored.get("sections"), list)):
        return None
    try:
        root = os.path.realpath(figures)
    except (OSError, ValueError):
        return None
    for section in stored["sections"]:
        if not _valid_section(section, Path(out_dir), root):
            return None
    return stored


def drawn_svg_figures(out_dir: Path) -> list[dict[str, Any]]:
    """The figures of ``out_dir``'s validated manifest (:func:`figure_manifest`) that have
    an SVG file, in report order; [] when there is no valid manifest."""
    stored = figure_manifest(out_dir)
    return [fig for section in (stored["sections"] if stored is not None else ())
            for fig in section["figures"] if "svg" in fig["files"]]


def _texts(value, size: int | None = None) -> bool:
    return (isinstance(value, list) and (size is None or len(value) == size)
            and all(isinstance(v, str) for v in value))


def _scalars(value, size: int | None = None) -> bool:
    """A list (of ``size`` items) of JSON scalars: what a table row or a fact holds (the
    template escapes them)."""
    return (isinstance(value, list) and (size is None or len(value) == size)
            and all(v is None or isinstance(v, (str, int, float)) for v in value))


def _valid_section(section, out_dir: Path, root: str) -> bool:
    if not isinstance(section, dict):
        return False
    if not all(isinstance(section.get(k), str) for k in ("name", "title", "description")):
        return False
    content = section.get("content")
    if not isinstance(content, dict):
        return False
    facts, tables = content.get("facts", []), content.get("tables", [])
    if not (isinstance(facts, list) and all(_scalars(f, 2) for f in facts)
            and _texts(content.get("notes", []))
            and isinstance(content.get("equations", []), list)
            and all(_texts(e, 2) for e in content.get("equations", []))
            and isinstance(tables, list)):
        return False
    for t in tables:
        if not (isinstance(t, dict) and isinstance(t.get("caption"), str)
                and _scalars(t.get("header")) and isinstance(t.get("rows"), list)
                and all(_scalars(r) for r in t["rows"])):
            return False
    figures = section.get("figures")
    if not isinstance(figures, list):
        return False
    for fig in figures:
        if not (isinstance(fig, dict) and isinstance(fig.get("id"), str)
                and isinstance(fig.get("caption"), str) and isinstance(fig.get("files"), dict)
                and "svg" in fig["files"]):
            return False
        for fmt, rel in fig["files"].items():
            if not figure_file_ok(out_dir, root, fmt, rel):
                return False
    return True


def figure_file_ok(out_dir: Path, root: str, fmt, rel) -> bool:
    """Whether ``rel`` (a manifest's file of format ``fmt``, relative to the scene folder
    ``out_dir``) is an existing regular file of that format inside ``root`` (the real
    path of ``out_dir/figures``), reached without leaving it."""
    if not (isinstance(fmt, str) and fmt in FIGURE_SUFFIXES and isinstance(rel, str)):
        return False
    parts = rel.split("/")
    if (len(parts) != 2 or parts[0] != "figures" or parts[1] in ("", ".", "..")
            or "\\" in rel or "\0" in rel or not parts[1].endswith(FIGURE_SUFFIXES[fmt])):
        return False
    path = Path(out_dir) / rel
    try:
        real = os.path.realpath(path)
        if os.path.dirname(real) != root or not path.is_file():
            return False
        return path.stat().st_size <= MAX_FIGURE_BYTES
    except (OSError, ValueError):
        return False


def template_dir() -> Path:
    """The jinja2 templates of the reports."""
    for d in TEMPLATE_DIRS:
        if (d / "scene.html.j2").exists():
            return d
    raise ReportError("templates/ not found next to the reportgen package")
