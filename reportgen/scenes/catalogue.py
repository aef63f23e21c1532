"""``reportgen kinds``: every kind with its keys (type, default, meaning), presets and sections."""

from __future__ import annotations

import types
import typing

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from ..config import ReportConfig, RunConfig
from . import KINDS

_SHARED = {"kind", "title", "preset", "run", "report"}


def _type_name(annotation) -> str:
    origin = typing.get_origin(annotation)
    if origin is typing.Annotated:
        return _type_name(typing.get_args(annotation)[0])
    if origin in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(annotation) if a is not type(None)]
        optional = len(args) < len(typing.get_args(annotation))
        return " | ".join(_type_name(a) for a in args) + (" (optional)" if optional else "")
    if origin is not None:
        args = ", ".join(_type_name(a) for a in typing.get_args(annotation))
        return f"{getattr(origin, '__name__', str(origin))}[{args}]"
    return getattr(annotation, "__name__", str(annotation))


def _submodel(annotation) -> type[BaseModel] | None:
    for arg in (annotation, *typing.get_args(annotation)):
        if isinstance(arg, type) and issubclass(arg, BaseModel):
            return arg
    return None


def _table_lines(name: str, model: type[BaseModel], indent: str = "    ") -> list[str]:
    lines = [f"{indent}[{name}]"]
    for key, info in model.model_fields.items():
        sub = _submodel(info.annotation)
        if sub is not None:
            lines.extend(_table_lines(f"{name}.{key}", sub, indent))
            continue
        default = "required" if info.default is PydanticUndefined else f"default {info.default!r}"
        lines.append(f"{indent}  {key:<12} {_type_name(info.annotation):<18} {default:<22} "
                     f"{info.description or ''}".rstrip())
    return lines


def describe_kinds() -> str:
    from ..core.integrators import METHODS

    out = ["Scene kinds (config key `kind`).  Keys shared by every kind: title, preset, "
           "[run], [report].", ""]
    for kind, cls in KINDS.items():
        out.append(f"{kind} — {cls.summary}")
        for key, info in cls.Config.model_fields.items():
            if key in _SHARED:
                continue
            sub = _submodel(info.annotation)
            if sub is not None:
                optional = "" if info.is_required() else "    (optional table)"
                out.extend(_table_lines(key, sub))
                if optional:
                    out[-len(sub.model_fields) - 1] += optional
        defaults = cls.default_section_names or tuple(s.name for s in cls.sections)
        out.append("    sections: " + ", ".join(
            s.name + ("" if s.name in defaults else " (on request)") for s in cls.sections))
        if cls.presets:
            out.append("    presets:  " + ", ".join(cls.presets))
        out.append("")
    out.extend(_table_lines("run", RunConfig, ""))
    out.extend(_table_lines("report", ReportConfig, ""))
    out.append("")
    out.append("Integrators ([run] method):  auto — chosen from the scene's structure")
    for name, method in METHODS.items():
        out.append(f"  {name:<14} {getattr(method, 'label', name)}")
    return "\n".join(out)
