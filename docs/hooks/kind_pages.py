"""The kind pages, the kinds overview and the configuration reference, generated from the
kinds' declarations when the site is built.

Everything here is read off the code, as ``reportgen kinds`` reads it
(:mod:`reportgen.scene.catalogue`): each kind's config model (keys, types and rules,
defaults, units), its presets and the title each gets, its report sections and its
declared results.  A key, preset or section added to a kind appears on its page at the
next build; nothing here names a kind.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from mdtext import code, table, text

from reportgen.kinds import KINDS
from reportgen.scene.catalogue import key_rows, preset_settings, preset_title, shared_rows
from reportgen.scene.schema import split_unit, symbol_text

#: the repository (configs/ holds the lecture pack)
REPO = Path(__file__).resolve().parents[2]

#: who takes the tables every kind shares (the rows say what they hold)
SHARED_TABLES = {
    "run": "Required by every kind that integrates (the listing of each kind says which); "
           "a kind that works in its config's own units takes its times in them.",
    "report": "Every kind accepts it.",
}

#: what the first line of every generated page says about itself
GENERATED = ("*Generated from the kinds' declarations when the site is built (what "
             "`reportgen kinds` prints); do not edit: change the kind's code.*")


# ------------------------------------------------------------------ key tables
def _unit_cell(unit: str) -> str:
    """A unit as written in a config value (``"9.81 m/s^2"``), or the bracket's words."""
    if not unit:
        return ""
    return text(unit) if " " in unit and ("units" in unit or "per" in unit) else code(unit)


def _default_cell(default: str) -> str:
    return code(default.removeprefix("default ")) if default.startswith("default ") else default


def _key_table(rows) -> str:
    body = []
    for _, key, kind, default, meaning in rows:
        description, unit = split_unit(meaning)
        body.append([code(key), text(kind), _default_cell(default), _unit_cell(unit),
                     text(description)])
    return table(["key", "type and rule", "default", "unit", "meaning"], body)


def _shared_link(header: str, meaning: str, to_reference: str) -> str | None:
    """A table every kind shares (``[run]``, ``[report]``): a line linking to it
    (``to_reference`` "": on the configuration reference itself)."""
    if "at the end" not in meaning:
        return None
    name = header.strip("[]")
    status = meaning.split(" table", 1)[0]
    where = (f"in the [configuration reference]({to_reference}#{name})" if to_reference
             else f"[above](#{name})")
    return f"{code(header)} ({status}): the keys every kind shares, {where}."


def key_sections(rows, level: str, to_reference: str) -> list[str]:
    """A kind's key rows (:func:`reportgen.scene.catalogue.key_rows`) as Markdown: the
    top-level keys, then a heading and a table per table of the config."""
    out: list[str] = []
    group: list = []
    title = "Top-level keys"
    note = ""
    links: list[str] = []

    def flush():
        if group:
            out.extend([f"{level} {title}", ""] + ([note, ""] if note else [])
                       + [_key_table(group), ""])

    for row in rows:
        _, key, kind, default, meaning = row
        if kind or default:
            group.append(row)
            continue
        link = _shared_link(key, meaning, to_reference)
        if link is not None:
            links.append(link)
            continue
        flush()
        group, title, note = [], code(key), text(meaning[:1].upper() + meaning[1:])
    flush()
    if links:
        out[2:2] = [*(f"- {link}" for link in links), ""]
    return out


# ---------------------------------------------------------------------- presets
def _preset_table(cls) -> str:
    rows = []
    for name in cls.presets:
        keys = ", ".join(code(f"{k} = {v}") for k, v in preset_settings(cls, name))
        rows.append([code(name), text(preset_title(cls, name)), keys])
    return table(["preset", "what it shows (the title of the preset alone)", "keys it sets"],
                 rows)


# --------------------------------------------------------------------- sections
def _section_table(sections, defaults=None) -> str:
    """Sections as a table: whether each is shown by default (not for a family, whose
    sections are all shown), whether it needs a trajectory, what it holds (if any says)."""
    headers = ["section", "title"] + (["shown"] if defaults is not None else []) + [
        "needs a trajectory"]
    described = any(s.description for s in sections)
    rows = []
    for s in sections:
        row = [code(s.name), text(s.title)]
        if defaults is not None:
            row.append("by default" if s.name in defaults else "on request")
        row.append("yes" if s.integrates else "")
        rows.append(row + ([text(s.description)] if described else []))
    return table(headers + (["what it holds"] if described else []), rows)


# ---------------------------------------------------------------------- results
def _symbol(tex: str) -> str:
    if not tex:
        return ""
    shown = symbol_text(tex)
    return text(shown) if shown else code(tex)


def _results_table(quantities) -> str:
    rows = [[code(q.name), _symbol(q.symbol), code(q.unit) if q.unit else "",
             text(", ".join(q.dims)), text(q.description + (" (optional)" if q.optional
                                                            else ""))]
            for q in quantities]
    return table(["name", "symbol", "unit", "dimensions", "meaning"], rows)


def _results(cls) -> list[str]:
    schema = cls.schema
    if schema is None:
        return []
    groups = [("Columns of each run (`/runs/<name>/y`)", schema.columns),
              ("Invariants (`/runs/<name>/invariants/<q>`)", schema.invariants),
              ("Results (`/analysis`)", schema.analysis)]
    count = sum(len(q) for _, q in groups)
    out = ["## Declared results", "",
           "Each stored quantity, declared once with its symbol and unit; the archive's "
           "`units`, `long_name` and `symbol` attributes and every label of the report "
           "come from these declarations. A kind whose columns are named by the config "
           "declares those when it runs, so they are not listed here.", "",
           f'<details markdown="1"><summary>{count} declared quantities</summary>', ""]
    for title, quantities in groups:
        if quantities:
            out += [f"### {title}", "", _results_table(quantities), ""]
    return out + ["</details>", ""]


# ---------------------------------------------------------------------- configs
def shipped_configs() -> dict[str, list[tuple[str, str]]]:
    """kind -> [(config file name, title)] of the lecture pack ``configs/``."""
    out: dict[str, list[tuple[str, str]]] = {}
    for path in sorted((REPO / "configs").glob("*.toml")):
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (OSError, tomllib.TOMLDecodeError):
            continue
        out.setdefault(str(data.get("kind", "")), []).append(
            (path.name, str(data.get("title", ""))))
    return out


def _figure_note(cls, configs) -> list[str]:
    figures = ", ".join(code(f) for f in getattr(cls, "gallery_figures", ()))
    example = configs[0][0] if configs else f"{cls.kind}.toml"
    return ["## Figures", "",
            "The site is built without running anything, so this page draws no figure. "
            "`make run` runs the lecture pack; its gallery `output/index.html` shows every "
            "scene with its kind's signature figure"
            + (f" (for this kind: {figures})" if figures else "")
            + f", and `reportgen figures configs/{example} --size slide` writes a scene's "
            "figures as files ([Figures and animations](../figures.md)).", ""]


# ------------------------------------------------------------------------ pages
def kind_page(cls, configs: list[tuple[str, str]]) -> str:
    defaults = cls.default_section_names or tuple(s.name for s in cls.sections)
    out = [f"# {cls.kind}", "", GENERATED, "", text(cls.summary[:1].upper() + cls.summary[1:])
           + ".", "",
           f"`reportgen kinds {cls.kind}` prints the same in a terminal; "
           f"[the lecture pack](../lecture-pack.md) says what its shipped configs show.", ""]
    out += ["## Presets", ""]
    if cls.presets:
        out += ['`preset = "name"` starts from the keys below; keys given in the config '
                "override them.", "", _preset_table(cls), ""]
    else:
        out += ["This kind has no presets.", ""]
    out += ["## Keys", "",
            "Values are in the unit shown; a value may also be text with a unit "
            '(`"40 deg"`), converted when the config is read ([Units](../units.md)).', ""]
    out += key_sections(key_rows(cls), "###", "../reference/config.md")
    out += ["## Report sections", "",
            "`[report] sections` chooses among them; left out, the sections shown by "
            "default are drawn.", "", _section_table(cls.sections, defaults), ""]
    family = (*cls.family_sections, *cls.SWEEP_SECTIONS)
    out += ["### For a family of runs", "",
            "A config with a [`[sweep]`](../sweeps.md) table is reported with these "
            "sections instead.", "",
            _section_table(family), ""]
    out += _results(cls)
    out += ["## Shipped configs", ""]
    out += ([table(["config", "title"], [[code(f"configs/{name}"), text(title)]
                                         for name, title in configs]), ""]
            if configs else ["The lecture pack has no config of this kind.", ""])
    out += _figure_note(cls, configs)
    return "\n".join(out)


def kinds_index() -> str:
    configs = shipped_configs()
    out = ["# Scene kinds", "", GENERATED, "",
           "A config's `kind` chooses one of these. Each page lists the kind's keys with "
           "their units, its presets, its report sections and its declared results.", "",
           table(["kind", "what it simulates", "presets", "shipped configs"],
                 [[f"[{code(cls.kind)}]({cls.kind}.md)", text(cls.summary),
                   str(len(cls.presets)), str(len(configs.get(cls.kind, [])))]
                  for cls in KINDS.values()]), "",
           "## Presets", "",
           '`preset = "name"`; keys given in the config override the preset\'s. Each line is '
           "the title a config of the preset alone gets, as `reportgen kinds KIND` prints it.",
           "",
           table(["kind", "preset", "what it shows"],
                 [[code(cls.kind), code(name), text(preset_title(cls, name))]
                  for cls in KINDS.values() for name in cls.presets]), ""]
    return "\n".join(out)


def config_reference() -> str:
    from reportgen.core.integrators import METHODS

    out = ["# Configuration reference", "", GENERATED, "",
           "A scene is one TOML file: `kind`, an optional `title` and `preset`, the kind's "
           "tables (`[params]`, `[initial]`, …), `[run]` for kinds that integrate, "
           "`[report]`, and optionally `[sweep]`. A walk-through is in "
           "[A scene](../scenes.md); units in [Units](../units.md).", ""]
    for name, rows in shared_rows().items():
        header, *keys = rows
        about = header[4].split("— ", 1)[-1]
        out += [f"## {code(header[1])} {{#{name}}}", "",
                text(about[:1].upper() + about[1:]) + " " + SHARED_TABLES.get(name, ""), "",
                _key_table(keys), ""]
    out += ["## `[sweep]` {#sweep}", "",
            "Any kind accepts `[sweep]`: dotted config paths, each with a list of values or "
            "`{ start, stop, num }`, and `store`, `zip`, `spacing`, `block`, `max_points`. "
            "See [A family of runs](../sweeps.md).", ""]
    out += ["## Integrators (`[run] method`) {#integrators}", "",
            '`method = "auto"` (the default) chooses from the scene\'s structure '
            "([Accuracy, cost and stability](../accuracy.md)); or name one:", "",
            table(["method", "what it is", "order", "step"],
                  [[code(name), text(getattr(m, "label", name)), str(getattr(m, "order", "")),
                    "adaptive" if getattr(m, "adaptive", False) else "fixed (`h`)"]
                   for name, m in METHODS.items()]), ""]
    out += ["## Keys of each kind", ""]
    for cls in KINDS.values():
        out += [f"### [{cls.kind}](../kinds/{cls.kind}.md)", "", text(cls.summary), ""]
        out += key_sections(key_rows(cls), "####", "")
    return "\n".join(out)


def pages() -> dict[str, str]:
    """Site path -> Markdown of every page made here."""
    configs = shipped_configs()
    out = {"kinds/index.md": kinds_index(), "reference/config.md": config_reference()}
    for cls in KINDS.values():
        out[f"kinds/{cls.kind}.md"] = kind_page(cls, configs.get(cls.kind, []))
    return out
