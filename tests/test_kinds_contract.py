"""Every kind is a package that keeps the contract of ``reportgen/kinds/``.

- a kind is a package under ``reportgen/kinds/`` and no module there is longer than
  600 lines;
- every section it lists has its ``section_<name>`` method, and every macro of its
  template is one of its sections (or the summaries);
- its simulation's imports never reach its report, plots or matplotlib (so a caption
  edit cannot change the simulate key), and its report's imports reach core or its
  simulation only through the config's own checks (the report is a function of the
  archive alone; ``tests/test_archive_only.py`` runs it with core blocked);
- every ``/analysis`` name its report reads by a literal key is declared in its results.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from reportgen.kinds import KINDS
from reportgen.support import codestamp

KINDS_DIR = Path(codestamp.PACKAGE) / "kinds"
PACKAGED = [k for k, cls in KINDS.items() if cls.template_path() is not None]
SUMMARIES = {"summary", "sweep_summary"}


def test_every_kind_is_a_package():
    assert sorted(PACKAGED) == sorted(KINDS), (
        f"kinds still written as one module: {sorted(set(KINDS) - set(PACKAGED))}")


def test_no_module_under_kinds_is_longer_than_600_lines():
    long = {str(p.relative_to(KINDS_DIR)): n for p in KINDS_DIR.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert not long, long


@pytest.mark.parametrize("kind", PACKAGED)
def test_sections_have_methods_and_template_macros_are_sections(kind):
    cls = KINDS[kind]
    names = {s.name for s in cls.sections + cls.family_sections + cls.SWEEP_SECTIONS}
    missing = [n for n in names if not callable(getattr(cls, f"section_{n}", None))]
    assert not missing, f"{kind}: sections without a section_<name> method: {missing}"
    template = cls.template_path().read_text(encoding="utf-8")
    # a macro named with a leading underscore is the template's own helper (jinja2 does
    # not export it, so the report cannot take it for a section's prose)
    macros = set(re.findall(r"{%-?\s*macro\s+([A-Za-z]\w*)\s*\(", template))
    assert macros - names - SUMMARIES == set(), (
        f"{kind}: template macros that name no section: {macros - names - SUMMARIES}")


@pytest.mark.parametrize("kind", PACKAGED)
def test_simulation_and_report_import_only_their_side(kind):
    cls = KINDS[kind]
    simulate = {p.relative_to(codestamp.PACKAGE).as_posix()
                for p in codestamp.module_files(cls.simulation_modules())}
    drawn = [f for f in simulate if f.startswith(("plots/", "scene/report.py"))
             or re.fullmatch(rf"kinds/{kind}/(report\w*|plots\w*)\.py", f)]
    assert not drawn, f"{kind}: the simulate key would follow drawing code: {drawn}"
    drawing = [f for f in simulate if _imports_matplotlib(codestamp.PACKAGE / f)]
    assert not drawing, f"{kind}: the simulation imports matplotlib: {drawing}"
    # the config module checks a config's physics (with core, lazily); past what that
    # needs, the report reaches no core and not the simulation
    report = {p.relative_to(codestamp.PACKAGE).as_posix()
              for p in codestamp.module_files(cls.report_modules())}
    report -= {p.relative_to(codestamp.PACKAGE).as_posix()
               for p in codestamp.module_files([cls.Config.__module__])}
    physics = [f for f in report if f.startswith("core/")
               or re.fullmatch(rf"kinds/{kind}/simulation\w*\.py", f)]
    assert not physics, f"{kind}: the report imports physics: {physics}"


def _imports_matplotlib(path: Path) -> bool:
    """Whether ``path`` imports matplotlib where it runs (not under TYPE_CHECKING)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skipped = {id(n) for node in ast.walk(tree)
               if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
               for n in ast.walk(node)}
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                 else [node.module or ""] if isinstance(node, ast.ImportFrom)
                 else [node.args[0].value] if (
                     isinstance(node, ast.Call) and getattr(node.func, "id", "") == "lazy_module"
                     and node.args and isinstance(node.args[0], ast.Constant)) else [])
        if any(str(n).split(".")[0] == "matplotlib" for n in names):
            return True
    return False


def _literal_analysis_keys(path: Path) -> set[str]:
    """Names read from ``<x>.analysis`` by a literal: ``a["name"]``, ``a.get("name")``,
    where ``a`` is ``data.analysis`` or a local bound to it."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    keys: set[str] = set()
    for fn in ast.walk(tree):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        aliases = set()
        for node in ast.walk(fn):
            if (isinstance(node, ast.Assign) and len(node.targets) == 1
                    and isinstance(node.targets[0], ast.Name)
                    and isinstance(node.value, ast.Attribute) and node.value.attr == "analysis"
                    and isinstance(node.value.value, ast.Name) and node.value.value.id == "data"):
                aliases.add(node.targets[0].id)

        def is_analysis(expr, aliases=aliases) -> bool:
            return ((isinstance(expr, ast.Attribute) and expr.attr == "analysis"
                     and isinstance(expr.value, ast.Name) and expr.value.id == "data")
                    or (isinstance(expr, ast.Name) and expr.id in aliases))

        for node in ast.walk(fn):
            if (isinstance(node, ast.Subscript) and is_analysis(node.value)
                    and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, str)):
                keys.add(node.slice.value)
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and node.func.attr == "get" and is_analysis(node.func.value) and node.args
                    and isinstance(node.args[0], ast.Constant)
                    and isinstance(node.args[0].value, str)):
                keys.add(node.args[0].value)
    return keys


@pytest.mark.parametrize("kind", PACKAGED)
def test_report_reads_only_declared_results(kind):
    cls = KINDS[kind]
    if cls.schema is None:
        pytest.skip(f"{kind} declares its results per config")
    declared = set(cls.schema.all_analysis) | set(cls.schema.open_groups)
    groups = {name.split("/")[0] for name in declared}
    read = set()
    for path in (KINDS_DIR / kind).glob("report*.py"):
        read |= _literal_analysis_keys(path)
    undeclared = sorted(k for k in read if k not in declared and k not in groups)
    assert not undeclared, f"{kind}: the report reads undeclared results {undeclared}"


def test_a_misspelt_result_in_a_report_is_found(tmp_path):
    """The scan above finds a misspelt key (it would otherwise fail only when drawn)."""
    path = tmp_path / "report.py"
    path.write_text("def section_x(cls, data):\n    a = data.analysis\n"
                    "    return a['perod'], data.analysis.get('k')\n")
    assert _literal_analysis_keys(path) == {"perod", "k"}
