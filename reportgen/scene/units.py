"""Units at the edges, SI inside: config values written with a unit.

A numeric config key may be given as text with a unit (``theta = "40 deg"``,
``k = "500 N/m"``, ``I1 = "1.3 kg m^2"``; in an array, ``omega = ["1 rad/s", 2.0]``).
:func:`convert_field` turns such text into the number in the unit the key's field
declares (the brackets ending its description, "initial angle [rad]": see
:func:`reportgen.scene.schema.quantity_of_description`), so the validated config and
the archive's resolved config hold plain numbers in the declared units.  A plain number
keeps meaning the declared unit.

What the bracket may say (:func:`unit_kind`):

* a unit pint reads ("rad", "kg m²", "N/m"): text with a unit of the same dimension is
  converted ("40 deg" -> 0.698 for "[rad]");
* "dimensionless" (or "1"): a pure number (text only with a dimensionless unit, "5 %");
* "config units of …" (:data:`OWN_UNITS`): the kind works in units the config chooses
  (three bodies in AU, years and solar masses; a Hamiltonian's constants): plain numbers
  only, never converted, since no unit system is fixed to convert to;
* "per `key`: …" (:data:`CHOSEN_BY`): another key chooses the unit (normal modes' `units`,
  a central force's power law); the kind converts text itself where that unit is physical
  (:func:`convert_paths`) and the key takes plain numbers otherwise.

A config key holding numbers without such a bracket has no declared unit and takes plain
numbers only (``tests/test_kinds_units.py`` requires every listed key to have one).

Units are read by pint through one shared registry, made on the first value that carries
a unit: validating a config of plain numbers never imports pint.  Any other declared unit
pint cannot read leaves the key taking plain numbers only.
"""

from __future__ import annotations

import copy
import functools
import math
import re
import types
import typing
from typing import Annotated, Any, Literal

from .schema import CHOSEN_BY, OWN_UNITS, key_owner, quantity_of_description

#: a number, then the rest of the text (the unit): "40 deg", "-1.5e3 kg m^2", ".5"
_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*")
#: what a unit may be written with (letters, powers, products, quotients, °, Å, µ)
_UNIT_CHARS = re.compile(r"[\w °Åµμ·⋅*/^().⁰¹²³⁴⁵⁶⁷⁸⁹⁻-]*")
#: longest unit text read (a hostile config cannot make pint work hard)
MAX_UNIT_CHARS = 60
#: declared units meaning "a pure number"
DIMENSIONLESS = ("", "1", "dimensionless")
#: the quantity a declared unit measures, for the error's rule
_WHAT = {"m": "a length", "kg": "a mass", "s": "a time", "rad": "an angle",
         "rad/s": "an angular velocity", "1/s": "a rate", "m/s": "a velocity",
         "m/s^2": "an acceleration", "m/s²": "an acceleration", "kg m^2": "a moment of inertia",
         "kg m²": "a moment of inertia", "kg·m²": "a moment of inertia",
         "N/m": "a spring constant", "J": "an energy", "kg m/s": "a momentum",
         "kg·m/s": "a momentum", "u": "a mass", "N": "a force"}
#: an example of a value with a unit, for the error's rule
_EXAMPLE = {"rad": "40 deg", "rad/s": "10 rpm", "m": "25 cm", "kg": "250 g", "s": "2 min"}


@functools.cache
def registry():
    """The shared pint UnitRegistry (made, and pint imported, on first use)."""
    import pint

    return pint.UnitRegistry()


@functools.cache
def declared_unit(model: type, name: str) -> str | None:
    """The unit the field ``name`` of ``model`` declares ("rad"), "" if none; None if the
    field does not hold numbers (floats, or arrays of them)."""
    field = model.model_fields.get(name)
    if field is None or not _admits(field.annotation, float):
        return None
    return quantity_of_description(field.description or "")[1]


def _admits(annotation: Any, kind: type) -> bool:
    """Whether ``annotation`` takes values of ``kind`` somewhere (in a union, an array)."""
    while typing.get_origin(annotation) is Annotated:
        annotation = typing.get_args(annotation)[0]
    if annotation is kind:
        return True
    origin = typing.get_origin(annotation)
    if origin is Literal:
        return any(isinstance(a, kind) for a in typing.get_args(annotation))
    if origin in (typing.Union, types.UnionType, list, tuple):
        return any(_admits(a, kind) for a in typing.get_args(annotation))
    return False


def _has_text(value: Any, depth: int = 0) -> bool:
    if isinstance(value, str):
        return True
    return depth < 3 and isinstance(value, list) and any(_has_text(v, depth + 1)
                                                        for v in value)


def convert_table(model: type, data: Any) -> Any:
    """The table ``data`` of ``model`` (a pydantic model) with :func:`convert_field`
    applied to each of its keys; a copy only if a value changed.  Every value that cannot
    be converted is one error of a pydantic ValidationError, located at its key."""
    if not isinstance(data, dict) or not any(_has_text(v) for v in data.values()):
        return data
    out, errors = dict(data), []
    for name, value in data.items():
        if not isinstance(name, str) or name not in model.model_fields:
            continue
        try:
            out[name] = convert_field(model, name, value)
        except ValueError as exc:
            errors.append(_error(name, value, str(exc)))
    if errors:
        from pydantic import ValidationError

        raise ValidationError.from_exception_data(model.__name__, errors)
    return out


def convert_items(data: Any, units: dict[tuple[str, str], str]) -> Any:
    """``data`` (a table) with the text quantities of its arrays of tables converted:
    ``units[(array, key)]`` is the unit ``data[array][i][key]`` is stored in (a kind whose
    units depend on a unit-system key says them here).  Errors as :func:`convert_table`'s,
    located at ``array.i.key``."""
    if not isinstance(data, dict):
        return data
    out, errors = dict(data), []
    for (array, key), unit in units.items():
        items = out.get(array)
        if not isinstance(items, list) or not any(
                isinstance(item, dict) and _has_text(item.get(key)) for item in items):
            continue
        out[array] = items = [dict(item) if isinstance(item, dict) else item for item in items]
        for i, item in enumerate(items):
            if isinstance(item, dict) and _has_text(item.get(key)):
                try:
                    item[key] = _convert(item[key], unit, False, 0)
                except ValueError as exc:
                    errors.append(_error((array, i, key), item[key], str(exc)))
    if errors:
        from pydantic import ValidationError

        raise ValidationError.from_exception_data("config", errors)
    return out


def convert_paths(data: Any, units: dict[tuple[str, ...], str]) -> Any:
    """``data`` (a table) with the text quantities at some paths converted: ``units[path]``
    is the unit ``data[path[0]][path[1]]...`` is stored in (a kind whose units another key
    chooses says them here; a value that is an array is converted item by item).  Errors
    as :func:`convert_table`'s, located at the path."""
    if not isinstance(data, dict):
        return data
    out, errors = data, []
    for path, unit in units.items():
        table = out
        for part in path[:-1]:
            table = table.get(part) if isinstance(table, dict) else None
        if not isinstance(table, dict) or not _has_text(table.get(path[-1])):
            continue
        if out is data:
            out = copy.deepcopy(data)
        table = out
        for part in path[:-1]:
            table = table[part]
        try:
            table[path[-1]] = _convert(table[path[-1]], unit, False, 0)
        except ValueError as exc:
            errors.append(_error(path, table[path[-1]], str(exc)))
    if errors:
        from pydantic import ValidationError

        raise ValidationError.from_exception_data("config", errors)
    return out


def is_quantity_text(value: Any) -> bool:
    """Whether ``value`` is text of a number followed by a unit ("5 deg")."""
    found = _NUMBER.fullmatch(value) if isinstance(value, str) else None
    return found is not None and bool(found.group(2))


def convert_at(model: type, path: str, value: Any) -> Any:
    """``value`` given for the dotted config key ``path`` ("initial.theta") of ``model``
    (a swept value, say) as the number in that key's declared unit, as
    :func:`convert_field` converts the key itself; unchanged where the key declares no
    unit (a table of free keys).  ValueError names the rule."""
    owner = key_owner(model, path)
    return value if owner is None else convert_field(*owner, value)


def _error(name: str | tuple, value: Any, message: str):
    from pydantic_core import InitErrorDetails, PydanticCustomError

    loc = name if isinstance(name, tuple) else (name,)
    return InitErrorDetails(type=PydanticCustomError("value_error", "{rule}", {"rule": message}),
                            loc=loc, input=value)


def convert_field(model: type, name: str, value: Any) -> Any:
    """``value`` of the field ``name`` of ``model`` with every text quantity in it (itself,
    or items of an array) as the number in the field's declared unit; anything else
    unchanged, for the field's own validation to judge.  ValueError names the rule."""
    if not _has_text(value):
        return value
    unit = declared_unit(model, name)
    if unit is None:
        return value
    field = model.model_fields[name]
    takes_text = _admits(field.annotation, str)
    return _convert(value, unit, takes_text, 0)


def _convert(value: Any, unit: str, takes_text: bool, depth: int) -> Any:
    if isinstance(value, list) and depth < 3:
        return [_convert(v, unit, takes_text, depth + 1) for v in value]
    if not isinstance(value, str):
        return value
    found = _NUMBER.fullmatch(value)
    if found is None:
        if takes_text or not value.strip() or not _UNIT_CHARS.fullmatch(value):
            return value  # a keyword ("steady") or not a quantity: the field judges it
        plain = _plain_rule(unit)
        raise ValueError(plain or rule(unit) + "; write a number, then its unit")
    try:
        return to_declared(float(found.group(1)), found.group(2), unit)
    except ValueError:
        if takes_text:  # text the field may hold ("2*q"): the field judges it
            return value
        raise


def unit_kind(unit: str) -> str:
    """What a declared unit is: "dimensionless", "own" (the config's own units), "chosen"
    (another key chooses it), "pint" (a unit pint reads) or "unreadable"."""
    if unit in DIMENSIONLESS:
        return "dimensionless"
    if unit.startswith(OWN_UNITS):
        return "own"
    if CHOSEN_BY.fullmatch(unit):
        return "chosen"
    return "pint" if _pint_unit(unit) is not None else "unreadable"


def _plain_rule(unit: str) -> str | None:
    """The rule of a key whose declared unit converts no text ("own", "chosen"), else None."""
    if unit.startswith(OWN_UNITS):
        what = unit[len(OWN_UNITS):].strip()
        return (f"must be a plain number in the config's own units{' ' + what if what else ''}"
                " (this kind converts no unit text)")
    chosen = CHOSEN_BY.fullmatch(unit)
    if chosen is not None:
        key, units = chosen.groups()
        return (f"must be a plain number here: its unit ({units}) is chosen by `{key}`, and "
                "unit text is converted only where that unit is physical")
    return None


def to_declared(number: float, given: str, unit: str) -> float:
    """``number`` in the unit ``given`` as a number in the declared ``unit``.  A declared
    unit may begin with a number ("4.07e-15 s", a kind's time unit τ): the result is then
    in multiples of that quantity."""
    if not math.isfinite(number):
        raise ValueError("must be a finite number")
    if unit in DIMENSIONLESS and not given:
        return number
    plain = _plain_rule(unit)
    if plain is not None:
        raise ValueError(plain)
    if not given:
        raise ValueError(f"must be a valid number, or text with its unit (\"{_example(unit)}\"); "
                         f"a number alone is in {unit}")
    if len(given) > MAX_UNIT_CHARS or not _UNIT_CHARS.fullmatch(given):
        raise ValueError(rule(unit) + f"; {given[:20]!r} is not a unit")
    if "rad" in unit and re.search(r"(?<![A-Za-z])(?:[kMG]?Hz|(?:kilo|mega|giga)?hertz)\b",
                                   given):
        raise ValueError(rule(unit) + f"; {given} is ambiguous for an angle per time "
                         "(1 Hz is 2π rad/s as a frequency, 1 rad/s to pint): give rad/s or rpm")
    target = _pint_unit(unit)
    if target is None:
        raise ValueError(f"must be a plain number in {unit} (this key takes no unit text)")
    try:
        source = _pint_unit_strict(given)
    except Exception:  # pint raises many kinds (UndefinedUnitError, SyntaxError, ...)
        raise ValueError(rule(unit) + f"; {given!r} is not a known unit") from None
    odd = _not_an_angle(source, angle=unit.strip() == "rad") if "rad" in unit else ""
    if odd:
        raise ValueError(rule(unit) + f"; {odd} is not a unit of angle")
    try:
        if isinstance(target, tuple):  # a unit with a factor: multiples of that quantity
            scale, base = target
            out = float(registry().Quantity(number, source).to(base).magnitude) / scale
        else:
            out = float(registry().Quantity(number, source).to(target).magnitude)
    except Exception:  # DimensionalityError, OffsetUnitCalculusError, OverflowError
        raise ValueError(rule(unit) + f"; {given} measures {_dimension(source)}") from None
    if not math.isfinite(out):
        raise ValueError(f"must be a finite number ({number:g} {given} is {out} {unit})")
    return out


#: pint's units of angle (with their SI prefixes: milliradian); every other unit pint
#: calls dimensionless (decibel, neper, byte, percent, grade) is not an angle
_ANGLES = ("radian", "degree", "arcminute", "arcsecond", "turn", "revolutions_per_minute",
           "gradian")


def _not_an_angle(source, angle: bool) -> str:
    """For a declared unit of angle (``angle``: rad) or of an angle per time: the
    dimensionless part of ``source`` (a pint Unit) that is no unit of angle ("decibel",
    "byte", "percent"), or a declared angle given without one; "" when fine.  pint counts
    angles as pure numbers, so "1 dB" would otherwise be 1.26 rad."""
    names = dict(source._units)
    angles = [n for n in names if n.endswith(_ANGLES)]
    dimensionless = [n for n in names if n not in angles and not _dimensions(n)]
    if dimensionless:
        return dimensionless[0]
    if angle and not angles and not source.dimensionality:  # another dimension: said later
        return str(source)
    return ""


def _dimensions(name: str) -> Any:
    """pint's dimensionality of the unit ``name`` (empty for a pure number, and for a unit
    pint cannot take apart, such as a logarithmic one's delta)."""
    try:
        return registry().get_dimensionality(name)
    except Exception:  # pint's UndefinedUnitError and kin
        return {}


def angle_hint(*angles: float, valid=None) -> str:
    """For a kind's range error on angles: "; angles are in rad; write \"40 deg\" for
    degrees" when the numbers were most likely meant as degrees, else "".

    With ``valid`` (the key's rule, a function of one angle in rad): when every one of
    ``angles`` read as degrees would meet it, and one of them does not as given (that
    one is named).  Without: when one of ``angles`` is a full turn or more."""
    finite = [a for a in angles if math.isfinite(a)]
    if len(finite) != len(angles):
        return ""
    if valid is None:
        wrong = [a for a in angles if abs(a) >= 2 * math.pi]
    elif all(valid(math.radians(a)) for a in angles):
        wrong = [a for a in angles if not valid(a)]
    else:
        wrong = []
    return f'; angles are in rad; write "{wrong[0]:g} deg" for degrees' if wrong else ""


def check_turn(key: str, angles, turns: float = 1.0, symbol: str = "θ") -> None:
    """Refuse an angle (or each of a list of angles, in rad) beyond ``turns`` full turns:
    a start angle beyond a full turn is almost surely degrees.  ValueError in the form a
    kind's rule takes, ``key: must satisfy |θ| ≤ 2π (got 40.0); angles are in rad; write
    \"40 deg\" for degrees``."""
    values = list(angles) if isinstance(angles, (list, tuple)) else [angles]
    limit = 2 * math.pi * turns
    if all(abs(a) <= limit for a in values):
        return
    bound = "2π" if turns == 1 else f"{2 * turns:g}π"
    got = values if isinstance(angles, (list, tuple)) else angles
    raise ValueError(f"{key}: must satisfy |{symbol}| ≤ {bound} (got {got})"
                     + angle_hint(*values, valid=lambda a: abs(a) <= limit))


def rule(unit: str) -> str:
    """The rule a key with the declared ``unit`` states: "must be an angle in rad; give
    e.g. \"40 deg\""."""
    if unit in DIMENSIONLESS:
        return "must be a dimensionless number"
    plain = _plain_rule(unit)
    if plain is not None:
        return plain
    scaled = _SCALED.fullmatch(unit)
    if scaled is not None:  # "4.0746e-15 s": a kind's own unit of time, say
        factor, base = float(scaled.group(1)), scaled.group(2)
        what = _WHAT.get(base, f"a quantity in {base}")
        return f"must be {what} (stored in units of {factor:.4g} {base}); give e.g. " \
               f"\"{_example(base)}\""
    what = _WHAT.get(unit, "a quantity")
    return f"must be {what} in {unit}; give e.g. \"{_example(unit)}\""


def _example(unit: str) -> str:
    return _EXAMPLE.get(unit, f"1.5 {unit}" if unit not in DIMENSIONLESS else "0.5")


#: a declared unit that is a multiple of a unit: "4.0746e-15 s"
_SCALED = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s+(.+)")


@functools.cache
def _pint_unit(unit: str):
    """The declared ``unit`` as a pint unit, None if pint cannot read it; a multiple of a
    unit ("4.0746e-15 s") as (the factor, the pint unit)."""
    scaled = _SCALED.fullmatch(unit)
    try:
        if scaled is not None:
            factor = float(scaled.group(1))
            return (factor, _pint_unit_strict(scaled.group(2))) if factor > 0 else None
        return _pint_unit_strict("dimensionless" if unit in DIMENSIONLESS else unit)
    except Exception:
        return None


def _pint_unit_strict(text: str):
    return registry().parse_units(text.replace("·", " ").replace("⋅", " "))


def _dimension(source) -> str:
    dims = str(source.dimensionality)
    return "nothing (a pure number)" if dims == "dimensionless" else re.sub(r"[\[\]]", "", dims)
