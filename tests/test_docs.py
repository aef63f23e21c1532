"""The documentation site and the README (issue 43, item 8).

The site builds with ``mkdocs build --strict`` (any warning fails it: a broken link or
anchor, a page left out of the nav, an API object mkdocstrings cannot find); its generated
pages hold what the code declares; every heading of the old 840-line README is a heading
of the site; and the examples of the README and of the pages under ``docs/`` work:

* every ```python block runs, the blocks of one page in order in one namespace, in a
  folder holding a copy of ``configs/`` and ``my_scene.toml`` (the name the docs give a
  user's config: a copy of ``configs/pendulum_small.toml``);
* in ```sh blocks, the cheap commands run in-process: ``reportgen kinds …`` and
  ``reportgen validate …`` (with or without ``.venv/bin/``), each to exit status 0;
* every ```toml block parses, and one with a ``kind`` is a valid config.

An HTML comment on the line before a block (invisible on the page) tells the test more:
``<!-- docs-test: file NAME -->`` writes the block to ``NAME`` in that folder first (a
later ``reportgen validate NAME`` or ``reportgen.run("NAME")`` reads it);
``<!-- docs-test: skip REASON -->`` leaves the block alone (an outline, a long run).
"""

from __future__ import annotations

import html
import re
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path

import pytest

from conftest import REPO
from reportgen.kinds import KINDS

#: the ``##`` and ``###`` headings of README.md before the site took its material (the
#: working tree of 2026-12, 840 lines); each must be (part of) a heading of the site
OLD_README_HEADINGS = [
    "Two commands",
    "Using it",
    "Python API",
    "Kinds and the lecture pack",
    "A scene",
    "A system written as a formula",
    "Small oscillations from a written potential",
    "A family of runs: `[sweep]`",
    "Accuracy, cost and stability",
    "The archive",
    "Layout",
    "Adding a kind",
]
#: the old README's bold lead-ins and command lines that served as headings
OLD_README_LEAD_INS = [
    "Safe with hostile input", "Presets", "Units", "Words are facts",
    "Every page is checked", "reportgen run", "reportgen watch", "reportgen figures",
    "reportgen animate",
]

#: what the README promises (Makefile, .ci/run): kept word for word
TWO_COMMANDS = [
    "make run     # sets up .venv and runs the lecture pack: configs/ -> output/ "
    "(open output/index.html)",
    "make test    # sets up .venv with the test extras and runs the test suite",
]
README_MAX_LINES = 150

#: ``reportgen`` commands that the examples run (cheap: they integrate nothing)
CHEAP_COMMANDS = ("kinds", "validate")


# ------------------------------------------------------------------------ the site
@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site built with ``mkdocs build --strict`` into a temporary folder."""
    out = tmp_path_factory.mktemp("site")
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d", str(out)],
                          cwd=REPO, capture_output=True, text=True, timeout=300)
    seconds = time.perf_counter() - started
    assert done.returncode == 0, f"mkdocs build --strict failed:\n{done.stderr}{done.stdout}"
    warnings = [line for line in (done.stderr + done.stdout).splitlines() if "WARNING" in line]
    assert not warnings, "\n".join(warnings)
    assert seconds < 120, f"the site took {seconds:.0f} s to build"
    return out


def page_text(path: Path) -> str:
    """The visible text of a built page's main part, without white space or backticks
    (:func:`squash`): a table cell, a highlighted signature and Markdown source compare."""
    raw = path.read_text(encoding="utf-8")
    main = raw[raw.find('role="main"'):] if 'role="main"' in raw else raw
    main = re.sub(r"<script.*?</script>", " ", main, flags=re.S)
    return squash(html.unescape(re.sub(r"<[^>]+>", " ", main)))


def squash(text: str) -> str:
    return re.sub(r"[\s`]+", "", text)


def headings(site: Path) -> set[str]:
    """The text of every heading of every page of the site."""
    out = set()
    for page in site.rglob("*.html"):
        for m in re.finditer(r"<h([1-6])[^>]*>(.*?)</h\1>", page.read_text(encoding="utf-8"),
                             flags=re.S):
            words = html.unescape(re.sub(r"<[^>]+>", "", m.group(2))).replace("¶", "")
            out.add(" ".join(words.split()))
    return out


def test_every_heading_of_the_old_readme_is_a_heading_of_the_site(site):
    found = {h.lower() for h in headings(site)}
    missing = [h for h in OLD_README_HEADINGS + OLD_README_LEAD_INS
               if not any(h.replace("`", "").lower() in f for f in found)]
    assert not missing, f"headings of the old README not in the site: {missing}"


def test_every_kind_has_its_page_with_every_key_and_unit(site):
    import reportgen

    assert {p.stem for p in (site / "kinds").glob("*.html")} == {*KINDS, "index"}
    for kind in reportgen.kinds():
        text = page_text(site / "kinds" / f"{kind['name']}.html")
        for key in kind["keys"]:
            assert squash(key["key"].rsplit(".", 1)[-1]) in text, (kind["name"], key["key"])
            assert squash(key["units"]) in text, (kind["name"], key)
        for section in KINDS[kind["name"]].sections:
            assert section.name in text, (kind["name"], section.name)


def test_the_kinds_page_lists_every_preset_as_reportgen_kinds_describes_it(site):
    """Every preset with the title a config of it alone gets (as ``reportgen kinds KIND``
    prints it; this table used to be kept in the README by hand)."""
    from reportgen.scene.catalogue import preset_title

    text = page_text(site / "kinds" / "index.html")
    for cls in KINDS.values():
        for name in cls.presets:
            assert squash(f"{cls.kind} {name} {preset_title(cls, name)}") in text, name


def test_the_reference_pages_hold_the_commands_the_api_and_the_archive(site):
    from reportgen.commands.cli import build_parser

    cli = page_text(site / "reference" / "cli.html")
    commands = next(a for a in build_parser()._actions if hasattr(a, "choices")
                    and isinstance(a.choices, dict)).choices
    for name in commands:
        assert squash(f"reportgen {name}") in cli, name
    api = page_text(site / "reference" / "api.html")
    for name in ("run(", "open(", "kinds(", "verify(", "to_xarray(", "ConfigError"):
        assert name in api, name
    layout = page_text(site / "reference" / "archive-layout.html")
    assert "/config_resolved" in layout and "/sweep/values" in layout
    config = page_text(site / "reference" / "config.html")
    assert "t_end" in config and "study_budget" in config and "dop853" in config


def test_the_notebook_and_coverage_are_pages(site):
    import json

    notebook = page_text(site / "notebook.html")
    cells = json.loads((REPO / "docs" / "example.ipynb").read_text(encoding="utf-8"))["cells"]
    for cell in cells:
        first = "".join(cell["source"]).strip().splitlines()[0].lstrip("# ")
        assert squash(first) in notebook, first
    assert (site / "example.ipynb").is_file()  # offered for download
    assert squash("Coverage of the lecture notes and the textbook") in page_text(
        site / "coverage.html")


# ------------------------------------------------------------------------ the README
def test_the_readme_is_short_and_keeps_the_two_commands():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= README_MAX_LINES
    for line in TWO_COMMANDS:
        assert line in readme.splitlines(), line
    assert "CI runs `.ci/run`, which is `make test`." in readme
    for words in ("mkdocs serve", "mkdocs build", "site/"):
        assert words in readme, words
    assert "/site/" in (REPO / ".gitignore").read_text().splitlines()


# ------------------------------------------------------------------------ examples
@dataclass
class Block:
    page: str
    line: int
    language: str
    text: str
    directive: str = ""
    argument: str = ""


_FENCE = re.compile(r"^(\s*)```(\w*)\s*$")
_DIRECTIVE = re.compile(r"<!--\s*docs-test:\s*(\w+)\s*(.*?)\s*-->")


def fenced_blocks(path: Path) -> list[Block]:
    """The fenced code blocks of a Markdown file, each with the directive before it."""
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        opening = _FENCE.match(lines[i])
        if not opening or not opening.group(2):
            i += 1
            continue
        indent = len(opening.group(1))
        before = next((lines[j] for j in range(i - 1, -1, -1) if lines[j].strip()), "")
        j = i + 1
        while j < len(lines) and lines[j].strip() != "```":
            j += 1
        text = "\n".join(line[indent:] for line in lines[i + 1:j]) + "\n"
        directive = _DIRECTIVE.search(before)
        out.append(Block(str(path.relative_to(REPO)), i + 1, opening.group(2), text,
                         *(directive.groups() if directive else ())))
        i = j + 1
    return out


#: README first (a newcomer's path), then the pages under docs/
PAGES = [REPO / "README.md", *sorted((REPO / "docs").rglob("*.md"))]


@pytest.fixture(scope="module")
def examples_folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("examples")
    shutil.copytree(REPO / "configs", folder / "configs")
    shutil.copy(REPO / "configs" / "pendulum_small.toml", folder / "my_scene.toml")
    return folder


def _check_toml(block: Block, path: Path | None) -> None:
    from reportgen.kinds import load_scene
    from reportgen.scene.config import parse_config_text

    data = tomllib.loads(block.text)  # a fragment ([sweep] …) must parse too
    if "kind" in data:
        scene = load_scene(parse_config_text(block.text, path))
        scene.build_models()  # what `reportgen validate` also refuses


def _run_shell(block: Block, capsys) -> int:
    from reportgen.commands.cli import main

    ran = 0
    for line in block.text.splitlines():
        words = shlex.split(line, comments=True)
        if not words or words[0].removeprefix(".venv/bin/") != "reportgen":
            continue
        if len(words) < 2 or words[1] not in CHEAP_COMMANDS:
            continue
        code = main(words[1:])
        out, err = capsys.readouterr()
        assert code == 0, f"{block.page}:{block.line}: `{line.strip()}` exited {code}\n{err}"
        ran += 1
    return ran


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_the_examples_of_the_page_work(page, examples_folder, monkeypatch, capsys):
    monkeypatch.chdir(examples_folder)
    namespace: dict = {"__name__": "docs_example"}
    for block in fenced_blocks(page):
        where = f"{block.page}:{block.line}"
        if block.directive == "skip":
            assert block.argument, f"{where}: say why the block is skipped"
            continue
        path = None
        if block.directive == "file":
            path = examples_folder / block.argument
            path.write_text(block.text, encoding="utf-8")
        elif block.directive:
            pytest.fail(f"{where}: unknown directive docs-test: {block.directive}")
        if block.language == "toml":
            _check_toml(block, path)
        elif block.language in ("sh", "bash", "console"):
            _run_shell(block, capsys)
        elif block.language == "python":
            exec(compile(block.text, where, "exec"), namespace)  # noqa: S102 - our own docs
