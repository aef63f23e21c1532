"""`reportgen kinds` lists every key each kind's Config model accepts, and nothing else.

The expected keys are collected here from the pydantic models themselves (independently of
the catalogue's own walk), so a key added to a kind cannot be left out of the listing.
"""

from __future__ import annotations

import typing

import pytest
from pydantic import BaseModel
from pydantic.fields import FieldInfo

from reportgen.kinds import KINDS
from reportgen.scene.catalogue import describe_kinds
from reportgen.scene.config import ReportConfig, RunConfig

SHARED = (RunConfig, ReportConfig)  # described once, after the kinds


def models_in(annotation) -> list[type[BaseModel]]:
    """Every model reachable through an annotation's arguments (X | None, list[X],
    Annotated[A | B, ...])."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in typing.get_args(annotation) for m in models_in(arg)]


def model_keys(model: type[BaseModel], prefix: str = "") -> list[tuple[str, FieldInfo]]:
    """(dotted key, field) for every key of a model, its tables and arrays of tables."""
    keys = []
    for name, info in model.model_fields.items():
        keys.append((prefix + name, info))
        for sub in models_in(info.annotation):
            keys += model_keys(sub, f"{prefix}{name}.")
    return keys


def listed_keys(lines: list[str]) -> dict[str, list[str]]:
    """Dotted key -> the lines listing it.  ``[a.b]`` / ``[[a.b]]`` lines open a table; the
    lines indented under a table hold its keys; other lines hold top-level keys."""
    keys: dict[str, list[str]] = {}
    table, header_indent = None, 0
    for line in lines:
        if not line.strip():
            continue
        indent = len(line) - len(line.lstrip())
        token = line.split()[0]
        if token.startswith("["):
            table, header_indent = token.strip("[]"), indent
            keys.setdefault(table, []).append(line)
        elif token.endswith(":"):  # "sections: ..."
            continue
        elif table is not None and indent > header_indent:
            keys.setdefault(f"{table}.{token}", []).append(line)
        else:
            table = None
            keys.setdefault(token, []).append(line)
    return keys


def blocks() -> tuple[dict[str, list[str]], list[str]]:
    """The listing cut into one block of lines per kind, and the shared tables' block."""
    text = describe_kinds()
    per_kind, current = {}, None
    lines = text.splitlines()
    for i, line in enumerate(lines):
        head = line.split(" — ")[0]
        if not line.startswith(" ") and head in KINDS:
            current = per_kind[head] = []
        elif not line.strip():
            current = None
        elif current is not None:
            current.append(line)
        elif line.startswith("[run]"):
            shared = []
            for rest in lines[i:]:
                if not rest.strip():
                    break
                shared.append(rest)
    return per_kind, shared


PER_KIND, SHARED_BLOCK = blocks()


def shared_tables(cls) -> set[str]:
    return {name for name, info in cls.Config.model_fields.items()
            if models_in(info.annotation) and set(models_in(info.annotation)) <= set(SHARED)}


@pytest.mark.parametrize("kind", list(KINDS))
def test_every_key_of_the_config_model_is_listed_under_its_kind(kind):
    cls = KINDS[kind]
    assert kind in PER_KIND, f"{kind} has no block in `reportgen kinds`"
    listed = listed_keys(PER_KIND[kind])
    shared_listed = listed_keys(SHARED_BLOCK)
    shared = shared_tables(cls)
    missing = []
    for key, _ in model_keys(cls.Config):
        top, _, rest = key.partition(".")
        where = shared_listed if top in shared and rest else listed
        if key not in where:
            missing.append(key)
    assert not missing, f"{kind}: keys missing from `reportgen kinds`: {missing}"


@pytest.mark.parametrize("kind", list(KINDS))
def test_nothing_listed_that_the_model_does_not_accept(kind):
    accepted = {key for key, _ in model_keys(KINDS[kind].Config)}
    invented = set(listed_keys(PER_KIND[kind])) - accepted
    assert not invented, f"{kind}: listed but not accepted: {invented}"


def shows_status(line: str, info: FieldInfo) -> bool:
    if info.is_required():
        return "required" in line
    return "optional" in line or "default " in line


@pytest.mark.parametrize("kind", list(KINDS))
def test_each_key_shows_required_or_default_and_its_meaning(kind):
    cls = KINDS[kind]
    listed, shared_listed = listed_keys(PER_KIND[kind]), listed_keys(SHARED_BLOCK)
    shared = shared_tables(cls)
    for key, info in model_keys(cls.Config):
        top, _, rest = key.partition(".")
        lines = (shared_listed if top in shared and rest else listed)[key]
        assert any(shows_status(line, info) for line in lines), (kind, key, lines)
        if info.description:
            assert any(info.description in line for line in lines), (kind, key, lines)


def test_normal_modes_lists_matrices_and_arrays_of_tables():
    block = PER_KIND["normal_modes"]
    listed = listed_keys(block)
    for key in ("M", "A", "atoms.position", "bonds.k", "angles.atoms", "chain.n", "evolve.t_end"):
        assert key in listed, key
    top_level = [line.split()[0] for line in block if line.startswith("    ")
                 and not line.startswith("     ")]
    assert "M" in top_level and "A" in top_level
    for table in ("atoms", "bonds", "angles"):
        assert any(line.split()[0] == f"[[{table}]]" for line in block), table
    (matrix,) = listed["M"]
    assert "list[list[float]]" in matrix and "optional" in matrix


def test_union_of_tables_lists_every_form():
    listed = listed_keys(PER_KIND["inertia"])
    headers = [line.strip().split("  ")[0] for line in PER_KIND["inertia"]]
    for form in ("cone", "box", "cylinder", "ellipsoid", "octahedron", "points"):
        assert f'[shape] type = "{form}"' in headers, form
    assert {"shape.type", "shape.radius", "shape.a", "shape.masses"} <= set(listed)


def test_types_rules_and_defaults_are_shown():
    (line,) = listed_keys(PER_KIND["pendulum"])["params.l"]
    assert line.split()[:4] == ["l", "float", ">", "0"] and "required" in line
    (line,) = listed_keys(SHARED_BLOCK)["run.samples"]
    assert "int ≥ 2, ≤ 2000000" in line and "default 2001" in line
    (line,) = listed_keys(SHARED_BLOCK)["report.formats"]
    assert 'list["html" | "pdf"]' in line and 'default ["html", "pdf"]' in line
    (line,) = listed_keys(PER_KIND["pendulum"])["run"]
    assert "required table" in line
    (line,) = listed_keys(PER_KIND["normal_modes"])["run"]
    assert "optional table" in line


def test_cli_kinds_prints_the_listing(cli):
    code, out, err = cli("kinds")
    assert code == 0 and err == ""
    assert out.rstrip("\n") == describe_kinds()
