"""``reportgen kinds``: every kind with every key it accepts, its presets and sections.

The listing is read off each kind's ``Config`` model, so a key added to a model is listed
without editing this module.  Per kind: the top-level keys, then its tables (``[name]``),
then its arrays of tables (``[[name]]``), each key with its type and rule, its default (or
``required``) and its meaning.  ``[run]`` and ``[report]``, which every kind shares, are
described once at the end.
"""

from __future__ import annotations

import difflib
import json
import re
import types
import typing

from pydantic import BaseModel
from pydantic.fields import FieldInfo

from ..errors import UsageError
from ..kinds import KINDS
from .config import ReportConfig, RunConfig

#: tables described once, at the end, rather than under every kind
_SHARED_TABLES = {RunConfig: "run", ReportConfig: "report"}

#: meanings of the keys every kind declares in ``SceneConfig`` without a description
_SHARED_KEYS = {
    "kind": "selects this kind",
    "title": "report title (default: the kind and the file name)",
    "preset": "start from a named set of keys, which explicit keys override",
}

#: pydantic's bound constraints (``annotated_types.Gt`` ...) by attribute
_BOUNDS = (("gt", ">"), ("ge", "≥"), ("lt", "<"), ("le", "≤"))

#: a row of the listing: (indent, key, type and rule, default, meaning); a header row
#: (a table) has its text in ``key`` and the rest in ``meaning``
Row = tuple[int, str, str, str, str]


# ------------------------------------------------------------------------ types
def _unwrap(annotation) -> tuple[typing.Any, list]:
    """``Annotated[X, m1, m2]`` -> (X, [m1, m2]); other annotations unchanged."""
    metadata: list = []
    while typing.get_origin(annotation) is typing.Annotated:
        annotation, *extra = typing.get_args(annotation)
        metadata = [*extra, *metadata]
    return annotation, metadata


def _alternatives(annotation) -> list:
    """The members of a union, None dropped; ``[annotation]`` if it is not a union."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [a for a in typing.get_args(annotation) if a is not type(None)]
    return [annotation]


def _rules(metadata: list) -> str:
    """Bounds (``> 0``, ``≤ 2000000``) and length limits found in pydantic metadata."""
    parts, shortest, longest = [], None, None
    for item in metadata:
        for m in item.metadata if isinstance(item, FieldInfo) else [item]:
            parts += [f"{sign} {getattr(m, attr)}" for attr, sign in _BOUNDS
                      if getattr(m, attr, None) is not None]
            shortest = getattr(m, "min_length", None) or shortest
            longest = getattr(m, "max_length", None) or longest
    if shortest is not None and shortest == longest:
        parts.append(f"length {shortest}")
    else:
        parts += [f"length ≥ {shortest}"] if shortest is not None else []
        parts += [f"length ≤ {longest}"] if longest is not None else []
    return ", ".join(parts)


def _type_name(annotation, metadata: list = ()) -> str:
    """``float > 0``, ``list[float]``, ``"kepler" | "power"``, ``list[float] | "apex"``."""
    annotation, inner = _unwrap(annotation)
    rules = _rules([*metadata, *inner])
    members = _alternatives(annotation)
    if len(members) > 1:
        name = " | ".join(_type_name(m) for m in members)
    elif members[0] is not annotation:  # X | None: "optional" is in the default column
        name = _type_name(members[0])
    elif typing.get_origin(annotation) is typing.Literal:
        name = " | ".join(f'"{a}"' if isinstance(a, str) else repr(a)
                          for a in typing.get_args(annotation))
    elif typing.get_origin(annotation) is not None:
        origin = typing.get_origin(annotation)
        args = ", ".join(_type_name(a) for a in typing.get_args(annotation))
        name = f"{getattr(origin, '__name__', str(origin))}[{args}]"
    else:
        name = getattr(annotation, "__name__", str(annotation))
    return f"{name} {rules}" if rules else name


def _free_table(annotation) -> str | None:
    """``"name = number"`` for a table of free keys (``dict[str, float]``), ``"name =
    text"`` for ``dict[str, str]``; None for any other annotation."""
    annotation = _unwrap(annotation)[0]
    if typing.get_origin(annotation) is not dict:
        return None
    value = _unwrap(typing.get_args(annotation)[1])[0]
    return "name = " + {float: "number", int: "whole number", str: "text"}.get(
        value, _type_name(value))


def _is_model(annotation) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _table_models(annotation) -> tuple[list[type[BaseModel]], bool]:
    """The models a key holds as a table (one, or each member of a union of models) and
    whether it is an array of tables; ([], False) for a plain key."""
    members = _alternatives(_unwrap(annotation)[0])
    members = [_unwrap(m)[0] for m in members]
    if len(members) > 1:
        return (members, False) if all(_is_model(m) for m in members) else ([], False)
    (member,) = members
    if typing.get_origin(member) is list:
        items, _ = _table_models(typing.get_args(member)[0])
        return items, bool(items)
    if _alternatives(member) != [member]:  # (A | B) | None
        return _table_models(member)
    return ([member], False) if _is_model(member) else ([], False)


# ----------------------------------------------------------------------- fields
def _toml(value) -> str:
    """A default as it would be written in the config."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def _default(info: FieldInfo) -> str:
    if info.is_required():
        return "required"
    value = info.get_default(call_default_factory=True)
    return "optional" if value is None else f"default {_toml(value)}"


def _doc_line(model: type[BaseModel]) -> str:
    """First line of a table model's docstring, without its ``[name]``: prefix."""
    lines = (model.__doc__ or "").strip().splitlines()
    return re.sub(r"^``\[+[\w.]+\]+``:\s*", "", lines[0]) if lines else ""


def _discriminator(models: list[type[BaseModel]]) -> str | None:
    """The key whose literal value tells the members of a union of tables apart."""
    common = set.intersection(*(set(m.model_fields) for m in models))
    for key in sorted(common):
        if all(typing.get_origin(m.model_fields[key].annotation) is typing.Literal
               for m in models):
            return key
    return None


def _table_rows(path: str, models: list[type[BaseModel]], array: bool, indent: int,
                status: str, meaning: str) -> list[Row]:
    """A table or array of tables and its keys.  A union of tables (``[shape]`` with
    ``type = "cone"`` or ``"box"`` ...) lists the keys every form has, then each form's."""
    header = f"[[{path}]]" if array else f"[{path}]"
    what = " ".join(w for w in (status, "array of tables" if array else "table") if w)
    tag = _discriminator(models) if len(models) > 1 else None
    if len(models) > 1:
        meaning = "; ".join(m for m in (f"`{tag}` chooses the form" if tag else
                                        "one of the forms below", meaning) if m)
    rows: list[Row] = [(indent, header, "", "", what + (f" — {meaning}" if meaning else ""))]
    common = [k for k in models[0].model_fields
              if all(k in m.model_fields for m in models)]
    common.sort(key=lambda k: k != tag)  # the tag first
    overrides = {}
    if tag is not None:  # one row for the tag, naming every value
        values = tuple(v for m in models for v in typing.get_args(m.model_fields[tag].annotation))
        overrides[tag] = {"type": _type_name(typing.Literal[values]),
                          "meaning": "the form of this table"}
    rows += _field_rows(path, {k: models[0].model_fields[k] for k in common}, indent, overrides)
    if len(models) > 1:
        for model in models:
            label = (f'{tag} = "{typing.get_args(model.model_fields[tag].annotation)[0]}"'
                     if tag else model.__name__)
            rows.append((indent, f"{header} {label}", "", "", _doc_line(model)))
            rows += _field_rows(path, {k: f for k, f in model.model_fields.items()
                                       if k not in common}, indent)
    return rows


def _field_rows(path: str, fields: dict[str, FieldInfo], indent: int,
                overrides: dict[str, dict[str, str]] | None = None) -> list[Row]:
    """Rows for the keys of one table (``path``; "" for the top level): plain keys, then
    the shared tables, the tables and the arrays of tables (the order TOML needs).
    ``overrides`` replaces the type or meaning shown for a key."""
    key_indent = indent + 2 if path else indent
    plain, shared, tables, arrays = [], [], [], []
    for key, info in fields.items():
        models, array = _table_models(info.annotation)
        sub = f"{path}.{key}" if path else key
        status = "required" if info.is_required() else "optional"
        free = _free_table(info.annotation)
        if free is not None:  # [params] of free names: a table, not a dict-valued key
            meaning = info.description or ""
            tables.append((indent, f"[{sub}]", "", "", f"{status} table of free keys: {free}"
                           + (f" — {meaning}" if meaning else "")))
        elif len(models) == 1 and models[0] in _SHARED_TABLES:
            shared.append((key_indent, f"[{sub}]", "", "", f"{status} table — keys under "
                           f"[{_SHARED_TABLES[models[0]]}] at the end"))
        elif models:
            meaning = info.description or (_doc_line(models[0]) if len(models) == 1 else "")
            (arrays if array else tables).extend(
                _table_rows(sub, models, array, indent, status, meaning))
        else:
            shown = (overrides or {}).get(key, {})
            plain.append((key_indent, key,
                          shown.get("type") or _type_name(info.annotation, info.metadata),
                          _default(info), shown.get("meaning") or info.description or ""))
    return plain + shared + tables + arrays


def _format(rows: list[Row]) -> list[str]:
    """Rows as aligned columns; a cell wider than its column's cap pushes only its row."""
    keys = [r for r in rows if r[2] or r[3]]
    wkey = min(max((r[0] + len(r[1]) for r in keys), default=0), 18)
    wtype = min(max((len(r[2]) for r in keys), default=0), 24)
    wdef = min(max((len(r[3]) for r in keys), default=0), 16)
    lines = []
    for indent, key, kind, default, meaning in rows:
        if not (kind or default):  # a table header
            lines.append(f"{' ' * indent}{key}  {meaning}".rstrip())
        else:
            lines.append(f"{' ' * indent}{key:<{wkey - indent}}  {kind:<{wtype}}  "
                         f"{default:<{wdef}}  {meaning}".rstrip())
    return lines


# ---------------------------------------------------------------------- listing
def key_rows(cls) -> list[Row]:
    """One kind's keys, tables and arrays of tables (each a :data:`Row`), in the order
    ``reportgen kinds KIND`` lists them; the documentation's kind pages are made from the
    same rows."""
    fields = cls.Config.model_fields
    overrides = {key: {"meaning": fields[key].description or text}
                 for key, text in _SHARED_KEYS.items() if key in fields}
    overrides["kind"]["type"] = f'"{cls.kind}"'
    overrides["preset"]["meaning"] += f" ({', '.join(cls.presets) or 'this kind has none'})"
    return _field_rows("", fields, 4, overrides)


def shared_rows() -> dict[str, list[Row]]:
    """``[run]`` and ``[report]``, which every kind shares: table name -> its rows."""
    return {name: _table_rows(name, [model], False, 0, "", _doc_line(model))
            for model, name in _SHARED_TABLES.items()}


def _kind_lines(cls) -> list[str]:
    """One kind: its keys, tables and arrays of tables, then its sections."""
    lines = [f"{cls.kind} — {cls.summary}"]
    lines += _format(key_rows(cls))
    defaults = cls.default_section_names or tuple(s.name for s in cls.sections)
    lines.append("    sections: " + ", ".join(
        s.name + ("" if s.name in defaults else " (on request)") for s in cls.sections))
    return lines


def _shared_lines() -> list[str]:
    """``[run]`` and ``[report]``, which every kind shares."""
    return [line for rows in shared_rows().values() for line in _format(rows)]


def kind_class(name: str):
    """The kind called ``name``; a UsageError naming the kinds (and the closest) if none is."""
    if name in KINDS:
        return KINDS[name]
    close = difflib.get_close_matches(name, list(KINDS), n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    raise UsageError(f"kinds: no kind {name!r}; {hint}(kinds: {', '.join(KINDS)})")


def describe_kind(name: str) -> str:
    """One kind: its keys, tables, sections and presets (each in words), then the shared
    ``[run]`` and ``[report]`` tables."""
    cls = kind_class(name)
    out = _kind_lines(cls)
    out.append("    presets: " + ("none" if not cls.presets else
                                  "(`reportgen kinds " + cls.kind + " --presets` shows their keys)"))
    out += [f"      {preset:<18} {preset_title(cls, preset)}" for preset in cls.presets]
    return "\n".join([*out, "", *_shared_lines()])


def preset_title(cls, preset: str) -> str:
    """A preset in words: the title the kind gives a config that is the preset alone (as
    ``reportgen kinds KIND`` prints it, and the documentation's kind pages)."""
    from .config import ConfigError, SourceConfig

    try:
        scene = cls.from_source(SourceConfig(None, "", {"kind": cls.kind, "preset": preset}))
    except ConfigError:  # a preset that needs more keys than it holds
        return "(needs more keys than the preset gives)"
    return scene.title


def preset_settings(cls, preset: str) -> list[tuple[str, str]]:
    """(dotted key, TOML value) for every key the preset sets, as ``reportgen kinds KIND
    --presets`` prints them."""
    return _flat(cls.presets[preset])


def _flat(data: dict, prefix: str = "") -> list[tuple[str, str]]:
    """(dotted key, TOML value) for every key of a nested table."""
    rows = []
    for key, value in data.items():
        if isinstance(value, dict):
            rows += _flat(value, f"{prefix}{key}.")
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for i, item in enumerate(value):
                rows += _flat(item, f"{prefix}{key}.{i}.")
        else:
            rows.append((prefix + key, _toml(value)))
    return rows


def describe_presets(name: str | None = None) -> str:
    """Every preset of one kind (``name``) or of all kinds: a line in words, then the keys
    it sets, as they would be written in the config."""
    classes = [kind_class(name)] if name is not None else list(KINDS.values())
    out = []
    for cls in classes:
        if not cls.presets:
            if name is not None:
                out.append(f"{cls.kind}: no presets")
            continue
        out.append(f"{cls.kind} — preset = \"name\" starts from these keys; keys given "
                   "in the config override them")
        for preset, data in cls.presets.items():
            out.append(f"  {preset} — {preset_title(cls, preset)}")
            out += [f"      {key} = {value}" for key, value in _flat(data)]
        out.append("")
    return "\n".join(out).rstrip("\n")


def describe_kinds() -> str:
    from ..core.integrators import METHODS

    out = ["Scene kinds (config key `kind`).  Under each kind: its top-level keys, then its "
           "tables [name] and arrays of tables [[name]] (one per item), each key with its type "
           "and rule, default and meaning.  [run] and [report] are described at the end.", ""]
    for cls in KINDS.values():
        out += _kind_lines(cls) + [""]
    out += _shared_lines()
    out.append("")
    out.append("Integrators ([run] method):  auto — chosen from the scene's structure")
    for name, method in METHODS.items():
        out.append(f"  {name:<14} {getattr(method, 'label', name)}")
    return "\n".join(out)
