"""Where reportgen's files are: the configs a batch finds, per scene the output folder's
report stamp, and the report templates.  Standard library only, so the command line can
look before it imports anything heavy."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from .errors import ReportError, UsageError

#: the report formats
FORMATS = ("html", "pdf")

TEMPLATE_DIRS = (
    Path(__file__).resolve().parent / "templates",  # installed wheel
    Path(__file__).resolve().parent.parent / "templates",  # source checkout
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


def template_dir() -> Path:
    """The jinja2 templates of the reports."""
    for d in TEMPLATE_DIRS:
        if (d / "scene.html.j2").exists():
            return d
    raise ReportError("templates/ not found next to the reportgen package")
