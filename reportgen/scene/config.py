"""Scene configuration: TOML text -> a frozen, validated object.

Every problem found is reported in one pass as one line naming the file, the
key, the rule and the value received.  Kind-specific tables (``[params]``,
``[initial]``, …) are pydantic models declared by each scene module; the
tables every kind shares (``[run]``, ``[report]``) live here.
"""

from __future__ import annotations

import copy
import difflib
import hashlib
import json
import math
import re
import tomllib
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    model_validator,
)

from ..errors import ConfigError  # noqa: F401 - part of this module's interface
from ..support.layout import printable, scene_name
from .units import convert_table


class Strict(BaseModel):
    """Base of every config table: unknown keys, wrong types, NaN and inf are errors."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)

    @model_validator(mode="before")
    @classmethod
    def _units(cls, data: Any) -> Any:
        """Text with a unit ("40 deg") as the number in the field's declared unit."""
        return convert_table(cls, data)


def _finite(x: float) -> float:
    if not math.isfinite(x):
        raise ValueError("must be a finite number")
    return x


Positive = Annotated[float, Field(gt=0), AfterValidator(_finite)]
NonNegative = Annotated[float, Field(ge=0), AfterValidator(_finite)]
Real = Annotated[float, AfterValidator(_finite)]


#: the integrators' step budget per run (reportgen.core.integrators.driver's max_steps)
FIXED_STEP_BUDGET = 10_000_000


class RunConfig(Strict):
    """``[run]``: how the scene is integrated."""

    t_end: Positive = Field(description="end time of the integration [s]")
    samples: int = Field(2001, ge=2, le=2_000_000, description="stored output points, uniform in t")
    method: str = Field("auto", description='"auto" or a named integrator (`reportgen kinds`)')
    # Tight defaults: a compiled DOP853 step costs ~100 ns, so 1e-12 is nearly free and
    # keeps stored trajectories within ~1e-9 of exact solutions over tens of periods.
    rtol: float = Field(1e-12, gt=0, lt=1,
                        description="relative tolerance of adaptive methods [dimensionless]")
    atol: float = Field(1e-14, gt=0, lt=1,
                        description="absolute tolerance of adaptive methods [dimensionless]")
    h: Positive | None = Field(None, description="step size of fixed-step methods [s]")
    study: bool = Field(True, description="run the error-against-run-time study")
    study_budget: Annotated[float, Field(gt=0, allow_inf_nan=True)] = Field(
        1.0, description="wall-clock time the study's timed runs may take together [s] (inf: "
                         "no budget; scipy DOP853's baseline at rtol 1e-10 is always measured)")

    @model_validator(mode="after")
    def _steps_within_budget(self):
        """A fixed step that would take more steps than the integrators' budget to reach
        ``t_end`` is a config error, said before anything runs (not a failed run)."""
        if self.h is not None and not self.t_end / self.h <= FIXED_STEP_BUDGET:
            raise ValueError(f"run.h: h = {self.h:.3g} needs {self.t_end / self.h:.3g} steps "
                             f"to reach run.t_end = {self.t_end:g}; at most "
                             f"{FIXED_STEP_BUDGET:.0e} fixed steps are taken (raise h)")
        return self


class OwnUnitsRunConfig(RunConfig):
    """``[run]``: how the scene is integrated, in the time unit of the config's own units.

    For a kind that works in units the config chooses (three bodies in years, a
    Hamiltonian's scaled time): ``t_end`` and ``h`` are plain numbers in that unit, never
    converted from a unit text (``"2 min"`` would be seconds, which this kind does not
    use)."""

    t_end: Positive = Field(description="end time of the integration [config units of time]")
    h: Positive | None = Field(None, description="step size of fixed-step methods "
                                                 "[config units of time]")


class ReportConfig(Strict):
    """``[report]``: what the report shows."""

    sections: list[str] | None = Field(None, description="sections to show (default: the kind's)")
    formats: list[Literal["html", "pdf"]] = Field(["html", "pdf"], description="report formats")
    figure_formats: list[Literal["svg", "pdf", "png"]] = Field(
        ["svg"], description="figure files written next to the report (SVG always: the HTML "
                             "inlines it; PDF/PNG are standalone exports)")
    png: bool = Field(False, description='also save figures as PNG (same as adding "png" to '
                                         'figure_formats)')


@dataclass(frozen=True)
class SourceConfig:
    """A config as read from disk, before kind-specific validation."""

    path: Path | None
    text: str
    data: dict[str, Any]

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode("utf-8")).hexdigest()

    @property
    def label(self) -> str:
        return str(self.path) if self.path is not None else "<archive config>"

    @property
    def name(self) -> str:
        """Scene name: the file stem (output folder name)."""
        return self.path.stem if self.path is not None else "scene"


#: a config larger than this is refused unread (the archive keeps the text, the report shows it)
MAX_CONFIG_BYTES = 1_000_000


def read_config(path: Path) -> SourceConfig:
    """Read and parse a TOML file; syntax and encoding problems, a file too large and a
    file name that cannot name a scene folder (:func:`reportgen.support.layout.scene_name`) are
    ConfigErrors."""
    path = Path(path)
    scene_name(path)
    label = printable(str(path))
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MAX_CONFIG_BYTES + 1)
    except OSError as exc:
        raise ConfigError([f"{label}: cannot read file: {exc.strerror}"]) from None
    if len(raw) > MAX_CONFIG_BYTES:
        raise ConfigError([f"{label}: larger than {MAX_CONFIG_BYTES // 1000} kB: not a scene "
                           "config"])
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError([f"{label}: not UTF-8 text (byte {exc.start})"]) from None
    return parse_config_text(text, path)


#: deepest nesting of tables and arrays a config may have (the deepest kind needs ~4)
MAX_CONFIG_NESTING = 32


def parse_config_text(text: str, path: Path | None = None) -> SourceConfig:
    """Parse TOML text; text over :data:`MAX_CONFIG_BYTES`, invalid TOML and nesting deeper
    than :data:`MAX_CONFIG_NESTING` are ConfigErrors.

    Nesting is looked for twice: in the text before it is parsed (:func:`_deepest_in_text`:
    a key of 30,000 dotted parts, 60 kB, cost the parser 3.4 GiB, quadratic in the parts;
    ``x = [[[[...]]]]`` exhausts its recursion), and in the parsed tables and arrays."""
    label = printable(str(path)) if path is not None else "<archive config>"
    if len(text) > MAX_CONFIG_BYTES or len(text.encode("utf-8")) > MAX_CONFIG_BYTES:
        raise ConfigError([f"{label}: larger than {MAX_CONFIG_BYTES // 1000} kB: not a scene "
                           "config"])
    deep = _deepest_in_text(text)
    if deep is not None:
        raise ConfigError([f"{label}: line {deep.line}: config nesting too deep: "
                           f"{deep.what}, more than {MAX_CONFIG_NESTING}"])
    too_deep = ConfigError([f"{label}: config nesting too deep (tables and arrays nested "
                            f"more than {MAX_CONFIG_NESTING} levels)"])
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError([f"{label}: invalid TOML: {exc}"]) from None
    except RecursionError:
        raise too_deep from None
    if _nesting(data) > MAX_CONFIG_NESTING:
        raise too_deep
    return SourceConfig(path=path, text=text, data=data)


#: what can nest in TOML text: strings and comments (whose text never nests), brackets,
#: dots and the words between them (white space, ``=`` and ``,`` are skipped by the search)
_TOML_TOKENS = re.compile(r'''
      (?P<text>"""(?:[^"\\]|\\[\s\S]|"(?!""))*"{3,5}   # multi-line basic string
             | \'\'\'[\s\S]*?\'{3,5}                   # multi-line literal string
             | "(?:[^"\\\n]|\\.)*"                      # basic string (a quoted key, too)
             | '[^'\n]*')                               # literal string
    | (?P<comment>\#[^\n]*)
    | (?P<open>[\[{])
    | (?P<close>[\]}])
    | (?P<dot>\.)
    | (?P<word>[A-Za-z0-9_+:-]+)
''', re.VERBOSE)


@dataclass(frozen=True)
class _Deep:
    line: int
    what: str


def _deepest_in_text(text: str) -> _Deep | None:
    """The first place where ``text`` nests deeper than :data:`MAX_CONFIG_NESTING`, read
    from the text alone (linear in its length, before the parser sees it): a dotted key
    of more parts (in a key, a table header or an inline table: ``a.b."c"``, each part a
    table), or more arrays and inline tables one inside the other.  Dots in numbers and
    dates make at most two parts; strings and comments are skipped whole.  None when
    nothing is that deep."""
    if text.count(".") < MAX_CONFIG_NESTING and (
            text.count("[") + text.count("{") <= MAX_CONFIG_NESTING):
        return None  # too few dots and brackets to nest that deep: the common case
    parts, after_dot, depth = 0, False, 0
    longest = deepest = (0, 0)  # (parts or depth, where it started or reached)
    start = 0
    for match in _TOML_TOKENS.finditer(text):
        kind = match.lastgroup
        if kind in ("word", "text"):  # a part of a key (or a value: one part)
            if after_dot:
                parts += 1
            else:
                parts, start = 1, match.start()
            after_dot = False
            if parts > longest[0]:
                longest = (parts, start)
            continue
        if kind == "dot" and parts and not after_dot:
            after_dot = True
            continue
        parts, after_dot = 0, False
        if kind == "open":
            depth += 1
            if depth > deepest[0]:
                deepest = (depth, match.start())
        elif kind == "close":
            depth = max(depth - 1, 0)
    found = []
    if longest[0] > MAX_CONFIG_NESTING:
        found.append((longest[1], f"a key of {longest[0]} dotted parts"))
    if deepest[0] > MAX_CONFIG_NESTING:
        found.append((deepest[1], f"arrays and inline tables nested {deepest[0]} deep"))
    if not found:
        return None
    where, what = min(found)
    return _Deep(text.count("\n", 0, where) + 1, what)


def _nesting(value) -> int:
    """How deeply tables and arrays nest in ``value`` (walked without recursion)."""
    deepest, stack = 0, [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, dict | list):
            deepest = max(deepest, depth + 1)
            if deepest > MAX_CONFIG_NESTING:
                return deepest
            stack.extend((v, depth + 1) for v in (item.values() if isinstance(item, dict)
                                                  else item))
    return deepest


def deep_merge(base: dict, override: dict) -> dict:
    """Tables merge key by key; any other value in ``override`` replaces ``base``'s."""
    out = copy.deepcopy(base)
    for key, value in override.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def _short(value: Any, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _unwrap(annotation: Any) -> Any:
    while typing.get_origin(annotation) is Annotated:
        annotation = typing.get_args(annotation)[0]
    return annotation


def _alternatives(annotation: Any) -> list:
    """The members of a union other than None (``[]`` if not a union)."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [_unwrap(a) for a in typing.get_args(annotation) if a is not type(None)]
    return []


def _is_model(annotation: Any) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _member_for_tag(members: list, tag: Any) -> Any:
    """The union member a pydantic error location names by ``tag``: a discriminator value
    (``"cone"``), a model name, or a schema label (``"list[...]"``, ``"literal['apex']"``)."""
    for member in members:
        if _is_model(member) and (tag == member.__name__ or any(
                typing.get_origin(_unwrap(f.annotation)) is Literal
                and tag in typing.get_args(_unwrap(f.annotation))
                for f in member.model_fields.values())):
            return member
    if isinstance(tag, str):
        for member in members:
            origin = typing.get_origin(member)
            name = "literal" if origin is Literal else getattr(origin or member, "__name__", "")
            if name and (tag == name or tag.startswith(name.lower() + "[")):
                return member
    return None


def _schema_label(item: Any) -> bool:
    """Whether a location item is pydantic's name for a schema, not a config key."""
    return isinstance(item, str) and ("[" in item or item.startswith("function-"))


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def config_key(loc: tuple, model: type[BaseModel] | None = None) -> str:
    """A pydantic error location as the dotted config key it points to: ``shape.radius``,
    ``atoms.1.position`` (array items by zero-based index), ``impulse.at.2``; a key that
    is not a bare TOML key is quoted as in TOML (``"é"``, ``""``).

    With ``model`` (the validated model) the location is followed through the model's
    fields, so the tags pydantic adds for the member of a union that failed (``cone``,
    ``list[function-after[...]]``) are dropped; without it only schema labels are dropped.
    """
    return ".".join(_follow(loc, model)[0])


def _follow(loc: tuple, model: type[BaseModel] | None) -> tuple[list[str], Any]:
    """:func:`config_key`'s walk: the key's parts and the annotation ``loc`` ends at
    (None where the model does not say)."""
    parts, annotation = [], model
    for item in loc:
        annotation = _unwrap(annotation)
        members = _alternatives(annotation)
        while len(members) == 1:  # X | None: pydantic adds no tag
            annotation = members[0]
            members = _alternatives(annotation)
        if members:  # a union: ``item`` names the member that failed
            annotation = _member_for_tag(members, item)
            continue
        if annotation is None and _schema_label(item):
            continue
        origin = typing.get_origin(annotation)
        text = str(item)
        parts.append(text if _BARE_KEY.fullmatch(text) else json.dumps(text, ensure_ascii=False))
        if isinstance(item, int):
            args = typing.get_args(annotation)
            annotation = args[0] if origin in (list, tuple, set, frozenset) and args else None
        elif _is_model(annotation):
            field = annotation.model_fields.get(str(item))
            annotation = field.annotation if field is not None else None
        elif origin is dict:
            annotation = typing.get_args(annotation)[1]
        else:
            annotation = None
    return parts, annotation


def _known_keys(loc: tuple, model: type[BaseModel] | None) -> list[str]:
    """The keys the table at ``loc`` accepts (``[]`` if it is not a model's table)."""
    annotation = _unwrap(_follow(loc, model)[1]) if model is not None else None
    return list(annotation.model_fields) if _is_model(annotation) else []


def _meant_by_words(name: str, loc: tuple, model: type[BaseModel] | None,
                    keys: list[str]) -> str | None:
    """The key among ``keys`` whose description has a word close to ``name``: a misspelt
    word for a key named by a symbol ("lenght" for ``l``, "length of the pendulum")."""
    annotation = _unwrap(_follow(loc, model)[1]) if model is not None else None
    if not _is_model(annotation):
        return None
    words: dict[str, str] = {}
    for key in keys:
        field = annotation.model_fields.get(key)
        for word in re.findall(r"[a-z]{4,}", (field.description or "").lower() if field else ""):
            words.setdefault(word, key)
    close = difflib.get_close_matches(name.lower(), list(words), n=1, cutoff=0.75)
    return words[close[0]] if close else None


#: "initial.theta / initial.theta_dot: ..." — a scene's cross-key rule naming its own keys
_NAMED_KEYS = re.compile(r"[A-Za-z_][\w.\[\]]*((?: / |, )[A-Za-z_][\w.\[\]]*)*: ")


def _rule(err: dict) -> str:
    """pydantic's message for one error as a rule (``must be greater than 0``)."""
    kind = err["type"]
    if kind == "extra_forbidden":
        return "unknown key"
    if kind == "missing":
        return "required key is missing"
    if kind in ("model_type", "dict_type", "model_attributes_type"):
        return "must be a table"
    if kind in ("list_type", "tuple_type"):
        return "must be an array"
    msg = err["msg"]
    for prefix in ("Value error, ", "Assertion failed, "):
        if msg.startswith(prefix):
            msg = msg[len(prefix):]
    if msg.startswith("Input should be "):
        msg = "must be " + msg[len("Input should be "):]
    return msg


def did_you_mean(word: Any, choices) -> str:
    """``"; did you mean 'x'?"`` for the choice closest to ``word``, or "" if none is close."""
    close = (difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
             if isinstance(word, str) else [])
    return f"; did you mean '{close[0]}'?" if close else ""


def _did_you_mean(errors: list[dict], model: type[BaseModel] | None
                  ) -> tuple[dict[tuple, str], set[tuple]]:
    """For each unknown key close to a key of its table, ``"; did you mean 'x'?"`` (a
    missing required key of the same table preferred), and the missing keys so explained
    (their own "required key is missing" would say the same thing twice)."""
    missing: dict[tuple, list[str]] = {}
    for err in errors:
        if err["type"] == "missing" and err["loc"] and isinstance(err["loc"][-1], str):
            missing.setdefault(tuple(err["loc"][:-1]), []).append(err["loc"][-1])
    hints, meant = {}, set()
    for err in errors:
        loc = tuple(err["loc"])
        if err["type"] != "extra_forbidden" or not loc or not isinstance(loc[-1], str):
            continue
        table, name = loc[:-1], loc[-1]
        close = (difflib.get_close_matches(name, missing.get(table, []), n=1, cutoff=0.6)
                 or difflib.get_close_matches(name, _known_keys(table, model), n=1,
                                              cutoff=0.6))
        if not close:  # a word of a key's description: missing keys first
            by_words = (_meant_by_words(name, table, model, missing.get(table, []))
                        or _meant_by_words(name, table, model, _known_keys(table, model)))
            close = [by_words] if by_words else []
        if close:
            hints[loc] = f"; did you mean '{close[0]}'?"
            if close[0] in missing.get(table, []):
                missing[table].remove(close[0])  # one misspelling explains one missing key
                meant.add((*table, close[0]))
    return hints, meant


def format_validation_error(label: str, exc: ValidationError,
                            model: type[BaseModel] | None = None) -> list[str]:
    """One line per problem: ``file: key 'a.b': rule (got value)``.

    ``model`` is the model that was validated (default: the one :class:`Strict` records on
    the error); it lets locations inside unions name the config key.  A value that no
    member of a union accepts is one problem: its rules are joined with "or".
    """
    problems: dict[str, tuple[str, list[str], str]] = {}  # by key: (where, rules, got)
    errors = exc.errors(include_url=False)
    hints, meant = _did_you_mean(errors, model)
    for err in errors:
        if err["type"] == "missing" and tuple(err["loc"]) in meant:
            continue  # said once, as the misspelled key's "did you mean"
        key = config_key(tuple(err["loc"]), model)
        rule = _rule(err) + hints.get(tuple(err["loc"]), "")
        got = "" if err["type"] == "missing" else f" (got {_short(err.get('input'))})"
        ctx = err.get("ctx") or {}
        if err["type"] == "union_tag_invalid":
            tag_key = str(ctx.get("discriminator", "type")).strip("'\"")
            key = f"{key}.{tag_key}" if key else tag_key
            rule = f"must be one of {ctx.get('expected_tags', '')}"
            got = f" (got {_short(ctx.get('tag'))})"
        elif err["type"] == "union_tag_not_found":
            tag_key = str(ctx.get("discriminator", "type")).strip("'\"")
            key = f"{key}.{tag_key}" if key else tag_key
            rule, got = "required key is missing", ""
        elif err["type"] in ("value_error", "assertion_error"):
            if isinstance(err.get("input"), dict):  # the whole table: the rule says what
                got = ""
            named = _NAMED_KEYS.match(rule)
            if named:  # the scene's message names its keys ("a.b / c.d: rule"): as any key
                key = re.sub(r"\[(\d+)\]", r".\1", rule[:named.end() - 2])  # atoms.0
                rule = rule[named.end():]
        where = f"key '{key}'" if key else ""
        _, rules, _ = problems.setdefault(where or rule, (where, [], got))
        if rule not in rules:
            rules.append(rule)
    lines = []
    for where, rules, got in problems.values():
        if len(rules) > 1 and all(r.startswith("must be ") for r in rules):
            rule = "must be " + " or ".join(r[len("must be "):] for r in rules)
        else:
            rule = "; or ".join(rules)
        lines.append(f"{label}: {where + ': ' if where else ''}{rule}{got}")
    return lines


def to_toml(data: dict[str, Any], limit: int = MAX_CONFIG_BYTES) -> str:
    """A config dict as TOML text (tables last), for configs made in code (presets, audit
    cases, the API's dicts); numpy numbers and arrays are written as plain numbers.

    Text over ``limit`` bytes (a config file's largest) is a ValueError, before any text
    is made when the dict's keys and values alone are more (a list of 5 million values
    made 25 MB of TOML, then refused)."""
    least = _least_toml_bytes(data, limit)
    if least > limit:
        raise ValueError(f"its TOML would be larger than {limit // 1000} kB (at least "
                         f"{least} bytes for its keys and values): not a scene config")

    def value(v) -> str:
        if hasattr(v, "dtype") and hasattr(v, "tolist"):  # a numpy number or array (a
            v = v.tolist()  # notebook's np.float64(0.5), np.int64(401)): as plain Python
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return repr(int(v))
        if isinstance(v, float):
            return repr(float(v)) if math.isfinite(v) else (
                "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf"))
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(x) for x in v) + "]"
        raise TypeError(f"cannot write {type(v).__name__} as TOML")

    def table(prefix: str, mapping: dict) -> list[str]:
        lines = [f"{k} = {value(v)}" for k, v in mapping.items()
                 if not isinstance(v, dict) and not _is_table_array(v)]
        for k, v in mapping.items():
            if isinstance(v, dict):
                lines += ["", f"[{prefix}{k}]"] + table(f"{prefix}{k}.", v)
            elif _is_table_array(v):
                for item in v:
                    lines += ["", f"[[{prefix}{k}]]"] + table(f"{prefix}{k}.", item)
        return lines

    text = "\n".join(table("", data)).strip() + "\n"
    size = len(text.encode("utf-8"))
    if size > limit:
        raise ValueError(f"its TOML is {size} bytes, larger than {limit // 1000} kB: not a "
                         "scene config")
    return text


def _least_toml_bytes(data: Any, limit: int) -> int:
    """The fewest bytes ``data`` can take as TOML (each key and text as written, a byte a
    number), counted without recursion and no further than past ``limit``."""
    total, stack = 0, [data]
    while stack and total <= limit:
        item = stack.pop()
        if isinstance(item, dict):
            total += 4 * len(item)  # "k = " at the least, before the keys are looked at
            if total <= limit:
                total += sum(len(str(k)) - 1 for k in item)
                stack.extend(item.values())
        elif isinstance(item, (list, tuple)):
            total += 2 + len(item)  # brackets, a separator each
            if total <= limit:
                stack.extend(item)
        elif isinstance(item, str):
            total += len(item) + 2
        elif hasattr(item, "dtype") and hasattr(item, "size"):  # a numpy array: its numbers
            total += 2 * int(item.size)
        else:
            total += 1
    return total


def _is_table_array(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)
