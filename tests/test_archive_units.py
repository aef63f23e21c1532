"""Issue 43: every ``units`` an archive writes is one pint reads, from the declarations
themselves: each kind's declared results (and the schemas a config makes: normal modes in
each unit system, a formula system's), as :attr:`Quantity.cf_attrs` writes them.  A unit
that is a multiple of one (τ = 4.0746 fs) becomes the unit and its CF ``scale_factor``,
whose product is the declared unit exactly; a number in the config's own units says so in
``config_units``."""

from __future__ import annotations

import math

import pint
import pytest

from reportgen.kinds import KINDS
from reportgen.kinds.hamiltonian.results import schema_for as formula_schema
from reportgen.kinds.normal_modes.results import MOLECULAR_OMEGA, UNIT_SYSTEMS
from reportgen.kinds.normal_modes.results import schema_for as modes_schema
from reportgen.scene.schema import ResultsSchema, cf_units

REGISTRY = pint.UnitRegistry()


def _schemas() -> dict[str, ResultsSchema]:
    # a kind's static schema where its runs write it; normal modes write the one of their
    # unit system (results_schema), the static one reads archives from before the systems
    out = {name: cls.schema for name, cls in KINDS.items()
           if cls.schema is not None and name != "normal_modes"}
    for system in UNIT_SYSTEMS:
        for source in ("molecule", "chain", "pendula", "matrices"):
            out[f"normal_modes {source} {system}"] = modes_schema(
                source, ("q1", "q2"), system)
    out["hamiltonian formula"] = formula_schema(["x", "y"], ["Lz"])
    return out


SCHEMAS = _schemas()


@pytest.mark.parametrize("name", sorted(SCHEMAS))
def test_every_declared_unit_is_written_as_one_pint_reads(name):
    schema = SCHEMAS[name]
    quantities = [schema.time, *schema.columns, *schema.invariants, *schema.analysis,
                  *schema.open_groups.values()]
    for q in quantities:
        attrs = schema.cf_attrs(q)
        if q.kind == "str":
            assert "units" not in attrs, q.name  # text has none (CF)
            continue
        REGISTRY.parse_units(attrs["units"])  # raises for "various", "time unit", …
        if "scale_factor" in attrs:  # the declared unit is that multiple of the written one
            declared = REGISTRY.parse_expression(q.unit)
            assert declared.to(attrs["units"]).magnitude == pytest.approx(
                attrs["scale_factor"], rel=1e-15), q.name
        if q.unit == "1" and schema.own_units:
            assert attrs["config_units"].startswith("config units"), q.name


def test_the_molecular_time_unit_is_tau_exactly():
    """τ = √(u/(mdyn/Å)) = 1/MOLECULAR_OMEGA s: the archive's scale factor to fs."""
    schema = modes_schema("molecule", ("x",), "molecular")
    units, factor = cf_units(schema.time.unit)
    assert units == "fs" and factor == pytest.approx(1e15 / MOLECULAR_OMEGA, rel=1e-15)
    assert math.isclose(factor, 4.0746, rel_tol=1e-4)


def test_a_formula_systems_time_is_in_config_units():
    schema = formula_schema(["x"], [])
    attrs = schema.cf_attrs(schema.time)
    assert attrs["units"] == "1" and attrs["config_units"] == "config units of time"
