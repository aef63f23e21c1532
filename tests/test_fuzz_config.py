"""Property-based bad input: random and malformed configs never produce a traceback.

Every generated config either validates or raises ConfigError whose lines each
name the file; the CLI turns that into exit status 2.
"""

from __future__ import annotations

import json
import math

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from reportgen.config import ConfigError, parse_config_text
from reportgen.scenes import KINDS, load_scene

KEYS = ["kind", "title", "preset", "params", "initial", "run", "report", "boundary", "g", "l",
        "m", "theta", "theta_dot", "t_end", "samples", "method", "rtol", "atol", "h", "study",
        "sections", "formats", "omega", "q", "p", "../../etc/passwd", "x" * 80, "é", ""]

numbers = st.one_of(
    st.integers(min_value=-10**30, max_value=10**30),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-308, 5e-324, 1e308, -1e308, math.pi]),
)
scalars = st.one_of(numbers, st.booleans(), st.text(max_size=30),
                    st.sampled_from(list(KINDS) + ["auto", "dop853", "html", "pdf"]))
values = st.recursive(
    scalars,
    lambda inner: st.one_of(st.lists(inner, max_size=4),
                            st.dictionaries(st.sampled_from(KEYS), inner, max_size=5)),
    max_leaves=12,
)


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a JSON string is a valid TOML basic string
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {toml_value(x)}" for k, x in v.items()) + "}"


def toml_document(doc: dict) -> str:
    return "\n".join(f"{json.dumps(k)} = {toml_value(v)}" for k, v in doc.items()) + "\n"


def near_valid(kind: str):
    """Mostly-valid documents of a kind with one or more tables perturbed."""
    base = {"kind": kind, "preset": st.sampled_from(list(KINDS[kind].presets) or [None])}
    return st.fixed_dictionaries(
        {"kind": st.just(kind)},
        optional={"preset": base["preset"], "title": st.text(max_size=40),
                  "params": st.dictionaries(st.sampled_from(KEYS), values, max_size=4),
                  "initial": st.dictionaries(st.sampled_from(KEYS), values, max_size=4),
                  "run": st.dictionaries(st.sampled_from(KEYS), values, max_size=5),
                  "report": st.dictionaries(st.sampled_from(KEYS), values, max_size=3),
                  "extra": values},
    ).map(lambda d: {k: v for k, v in d.items() if v is not None})


documents = st.one_of(
    st.dictionaries(st.sampled_from(KEYS), values, max_size=7),
    st.sampled_from(list(KINDS)).flatmap(near_valid),
)


def _validate(text: str) -> None:
    try:
        load_scene(parse_config_text(text))
    except ConfigError as exc:
        assert exc.problems and all(isinstance(p, str) and p for p in exc.problems)
        assert all("\n" not in p or "invalid TOML" in p for p in exc.problems)


@settings(max_examples=800, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(documents)
def test_generated_configs_never_crash(doc):
    _validate(toml_document(doc))


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=200))
def test_random_text_never_crashes(text):
    _validate(text)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(list(KINDS)).flatmap(near_valid))
def test_cli_validate_exit_code(tmp_path_factory, doc):
    from reportgen.cli import main

    folder = tmp_path_factory.mktemp("fuzz")
    path = folder / "scene.toml"
    path.write_text(toml_document(doc))
    assert main(["validate", str(path)]) in (0, 2)
