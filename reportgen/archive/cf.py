"""What xarray, pint and CF readers see of an archive: the attributes and coordinates
:mod:`reportgen.archive.store` writes beside the numbers (format 3).

* every dataset's CF attributes from the kind's declared results (:func:`declared`,
  :meth:`~reportgen.scene.schema.ResultsSchema.cf_attrs`), text without ``units``;
* the columns of the checks and study tables (:data:`CHECK_COLUMNS`,
  :func:`study_columns`), a number of several units saying where they are
  (:data:`UNITS_COLUMN`, :data:`UNITS_NOTE`);
* the coordinates of ``/analysis``: each group holds those of the dimensions its arrays
  use (:func:`analysis_dimensions`).
"""

from __future__ import annotations

from typing import Any

import h5py
import numpy as np

from ..scene.results import RunRecord
from ..scene.schema import Quantity, ResultsSchema
from .h5io import DIMENSION_ATTR, dataset

#: the attribute of a column whose rows each have their own unit: the column holding it
UNITS_COLUMN = "units_column"
#: the attribute of a number of no one unit (``units`` absent): what its units are
UNITS_NOTE = "units_note"
#: the columns of ``/checks``: their CF attributes (value, reference, scale and abs_error
#: in each row's ``unit``, which :data:`UNITS_COLUMN` names)
CHECK_COLUMNS: dict[str, dict[str, str]] = {
    "quantity": {"long_name": "the checked quantity"},
    "value": {"long_name": "the value computed", UNITS_COLUMN: "unit"},
    "reference": {"long_name": "its exact or independent reference", UNITS_COLUMN: "unit"},
    "scale": {"long_name": "what the error is relative to (NaN: |reference|)",
              UNITS_COLUMN: "unit"},
    "abs_error": {"long_name": "|value - reference|", UNITS_COLUMN: "unit"},
    "rel_error": {"long_name": "abs_error / scale", "units": "1"},
    "unit": {"long_name": "the unit of value, reference, scale and abs_error in this row "
                          "(empty: a pure number or the config's own units)"},
    "source": {"long_name": "where the reference comes from"},
}


def study_columns(schema: ResultsSchema, main: RunRecord | None):
    """The CF attributes of each column of the study table (``describe`` of
    :func:`~reportgen.archive.h5io.column_table`): its meaning from the study's declaration,
    times in s, the step in the runs' time unit, errors in the state's unit when its
    components share one."""
    from ..core.study import RECORD_FIELDS  # simulate time only: the report never writes
    from ..scene.schema import split_unit

    state = {declared(schema.column, c).unit for c in (main.columns if main else ())}
    time = schema.cf_attrs(schema.time)
    units: dict[str, dict[str, Any]] = {
        "tolerance": {"units": "1"}, "nfev": {"units": "1"}, "repeats": {"units": "1"},
        "wall_time_s": {"units": "s"}, "compile_time_s": {"units": "s"},
        "h": {k: v for k, v in time.items() if k not in ("long_name", "symbol")}}
    if len(state) == 1:
        error = schema.cf_attrs(Quantity("error", "", state.pop(), ""))
        units["error_final"] = units["error_max"] = {
            k: v for k, v in error.items() if k not in ("long_name", "symbol")}
    else:  # the largest over components of several units: a number without one unit
        units["error_final"] = units["error_max"] = {UNITS_NOTE: (
            "those of the state's components (column_units of /runs/main/y), which differ: "
            "the largest difference over them")}

    def describe(column: str) -> dict[str, Any]:
        return {"long_name": split_unit(RECORD_FIELDS.get(column, column))[0],
                **units.get(column, {})}

    return describe


def analysis_dimensions(g: h5py.Group, schema: ResultsSchema, main: h5py.Group | None) -> None:
    """Every array below ``/analysis`` on named dimensions: the declared ``dims`` of its
    quantity, ``<result>_<axis>`` for an array the schema leaves unnamed.  Each group
    holds the coordinates of the dimensions its own arrays use (format 3; netCDF lets a
    subgroup see its parent's, but xarray opening one group alone would not): ``t`` carries
    the main run's times with their units, a dimension the schema numbers
    (:attr:`~reportgen.scene.schema.ResultsSchema.numbered`: modes) counts 1 … n as the
    report does, any other is an index 0 … n − 1.  A group holding a 1-D result named
    as its dimension (a pendulum's mode numbers k) has that result as the coordinate.
    A dimension's name means one length throughout ``/analysis`` (``<dim>_<n>`` for a
    second length), so a tree of the groups aligns."""
    arrays: list[tuple[h5py.Dataset, h5py.Group, tuple[str, ...]]] = []
    dims_of: dict[str, tuple[str, ...]] = {}

    def visit(name: str, obj) -> None:
        if isinstance(obj, h5py.Dataset) and obj.ndim > 0:
            q = declared(schema.result, name)
            dims = q.dims if len(q.dims) == obj.ndim else ()
            if not dims:
                stem = name.replace("/", "_")
                dims = tuple(f"{stem}_{i}" if obj.ndim > 1 else f"{stem}_index"
                             for i in range(obj.ndim))
            # a matrix on (xyz, xyz): xarray wants distinct names, (xyz, xyz_2)
            dims = tuple(d if d not in dims[:i] else f"{d}_{dims[:i].count(d) + 1}"
                         for i, d in enumerate(dims))
            dims_of[obj.name] = dims
            arrays.append((obj, obj.parent, dims))

    g.visititems(visit)
    users: dict[tuple[str, int], dict[str, h5py.Group]] = {}
    for ds, group, dims in arrays:
        for dim, n in zip(dims, ds.shape, strict=True):
            users.setdefault((dim, n), {})[group.name] = group

    def own_coordinate(group: h5py.Group, name: str, dim: str, n: int) -> bool:
        item = group.get(name)
        return (isinstance(item, h5py.Dataset) and item.shape == (n,)
                and item.dtype.kind in "iuf" and dims_of.get(item.name) == (dim,))

    names: dict[tuple[str, int], str] = {}
    for (dim, n), groups in users.items():
        candidates = [dim, f"{dim}_{n}", *(f"{dim}_{n}_{k}" for k in range(2, 100))]
        names[(dim, n)] = next(
            c for c in candidates if c not in names.values() and all(
                c not in grp or own_coordinate(grp, c, dim, n) for grp in groups.values()))
    scales: dict[tuple[str, str], h5py.Dataset] = {}  # (group, name) -> its scale
    for ds, group, dims in arrays:
        for axis, (dim, n) in enumerate(zip(dims, ds.shape, strict=True)):
            name = names[(dim, n)]
            scale = scales.get((group.name, name))
            if scale is None:
                scale = _dimension_scale(group, name, dim, n, schema, main)
                scales[(group.name, name)] = scale
            if scale != ds:  # a coordinate is its own dimension's scale, not attached
                ds.dims[axis].attach_scale(scale)


def _dimension_scale(group: h5py.Group, name: str, dim: str, n: int, schema: ResultsSchema,
                     main: h5py.Group | None) -> h5py.Dataset:
    """The coordinate of the dimension ``dim`` (``n`` long, stored as ``name``) in
    ``group``: a result of that name there, else the main run's times, the numbers 1 … n
    or an index (marked :data:`DIMENSION_ATTR`: no result)."""
    if name in group:  # a result that is its own dimension's coordinate
        scale = group[name]
        scale.make_scale(name)
        return scale
    times = main is not None and dim == "t" and len(main["t"]) == n
    if times:
        scale = dataset(group, name, main["t"][()])
        scale.attrs.update({k: v for k, v in main["t"].attrs.items()
                            if k in ("units", "long_name", "symbol", "scale_factor",
                                     "config_units")})
    elif dim in schema.numbered:
        scale = described(dataset(group, name, np.arange(1, n + 1, dtype=np.int64)),
                          schema.numbered[dim], "1")
    else:
        scale = described(dataset(group, name, np.arange(n, dtype=np.int64)),
                          f"index along {dim}", "1")
    scale.attrs[DIMENSION_ATTR] = np.bool_(True)
    scale.make_scale(name)
    return scale


def described(ds: h5py.Dataset, long_name: str, units: str | None = None, symbol: str = ""):
    """Give ``ds`` its CF attributes: ``long_name``, ``symbol`` and, for numbers, ``units``
    (None: text, which has none)."""
    ds.attrs.update({"long_name": long_name, "symbol": symbol})
    if units is not None:
        ds.attrs["units"] = units
    return ds


def declared(lookup, name: str) -> Quantity:
    """The declared quantity ``name`` by ``lookup``, or an undeclared stand-in."""
    try:
        return lookup(name)
    except KeyError:
        return Quantity(name, "", "", name.replace("_", " ").replace("/", ": "))
