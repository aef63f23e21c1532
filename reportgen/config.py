"""Scene configuration: TOML text -> a frozen, validated object.

Every problem found is reported in one pass as one line naming the file, the
key, the rule and the value received.  Kind-specific tables (``[params]``,
``[initial]``, …) are pydantic models declared by each scene module; the
tables every kind shares (``[run]``, ``[report]``) live here.
"""

from __future__ import annotations

import copy
import hashlib
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, ValidationError

FORMATS = ("html", "pdf")


class ConfigError(Exception):
    """One or more problems in a scene configuration (exit status 2)."""

    def __init__(self, problems: list[str]):
        self.problems = problems
        super().__init__("\n".join(problems))


class Strict(BaseModel):
    """Base of every config table: unknown keys, wrong types, NaN and inf are errors."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)


def _finite(x: float) -> float:
    if not math.isfinite(x):
        raise ValueError("must be a finite number")
    return x


Positive = Annotated[float, Field(gt=0), AfterValidator(_finite)]
NonNegative = Annotated[float, Field(ge=0), AfterValidator(_finite)]
Real = Annotated[float, AfterValidator(_finite)]


class RunConfig(Strict):
    """``[run]``: how the scene is integrated."""

    t_end: Positive = Field(description="end time of the integration [s]")
    samples: int = Field(2001, ge=2, le=2_000_000, description="stored output points, uniform in t")
    method: str = Field("auto", description='"auto" or a named integrator (`reportgen kinds`)')
    # Tight defaults: a compiled DOP853 step costs ~100 ns, so 1e-12 is nearly free and
    # keeps stored trajectories within ~1e-9 of exact solutions over tens of periods.
    rtol: float = Field(1e-12, gt=0, lt=1, description="relative tolerance of adaptive methods")
    atol: float = Field(1e-14, gt=0, lt=1, description="absolute tolerance of adaptive methods")
    h: Positive | None = Field(None, description="step size of fixed-step methods [s]")
    study: bool = Field(True, description="run the error-against-run-time study")


class ReportConfig(Strict):
    """``[report]``: what the report shows."""

    sections: list[str] | None = Field(None, description="sections to show (default: the kind's)")
    formats: list[Literal["html", "pdf"]] = Field(["html", "pdf"], description="report formats")
    png: bool = Field(False, description="also save figures as PNG")


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


def read_config(path: Path) -> SourceConfig:
    """Read and parse a TOML file; syntax and encoding problems are ConfigErrors."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise ConfigError([f"{path}: cannot read file: {exc.strerror}"]) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError([f"{path}: not UTF-8 text (byte {exc.start})"]) from None
    return parse_config_text(text, path)


def parse_config_text(text: str, path: Path | None = None) -> SourceConfig:
    label = str(path) if path is not None else "<archive config>"
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError([f"{label}: invalid TOML: {exc}"]) from None
    return SourceConfig(path=path, text=text, data=data)


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


def format_validation_error(label: str, exc: ValidationError) -> list[str]:
    """One line per problem: ``file: key 'a.b': rule (got value)``."""
    lines = []
    for err in exc.errors(include_url=False):
        loc = ".".join(str(p) for p in err["loc"] if not str(p).startswith("function-"))
        msg = err["msg"]
        if msg.startswith("Value error, "):
            msg = msg[len("Value error, ") :]
        if err["type"] == "extra_forbidden":
            msg = "unknown key"
        elif err["type"] == "missing":
            lines.append(f"{label}: key '{loc}': required key is missing")
            continue
        where = f"key '{loc}'" if loc else "config"
        got = "" if err["type"] == "missing" else f" (got {_short(err.get('input'))})"
        lines.append(f"{label}: {where}: {msg}{got}")
    return lines


def to_toml(data: dict[str, Any]) -> str:
    """A config dict as TOML text (tables last), for configs made in code (presets, audit cases)."""

    def value(v) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            return repr(v) if not (isinstance(v, float) and not math.isfinite(v)) else (
                "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf"))
        if isinstance(v, str):
            import json

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

    return "\n".join(table("", data)).strip() + "\n"


def _is_table_array(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)
