"""The Python API: run scenes, open their archives, look at them in a notebook.

Three functions, exported lazily by :mod:`reportgen` (``import reportgen`` stays cheap):

* :func:`run` - run a scene from a TOML file, a folder of them, or a dict with the keys of
  a config; returns the :class:`~reportgen.pipeline.stages.Outcome` (a list for a folder).
* :func:`open` - an archive (``run.h5`` or its scene folder) as a :class:`Run`, read
  through the validating reader, with :meth:`Run.to_xarray`, :meth:`Run.to_datatree` and
  :attr:`Run.results` (each result with its unit).
* :func:`kinds` - the scene kinds with their presets and keys, as ``reportgen kinds``
  lists them.

>>> import reportgen
>>> scene = {"kind": "pendulum", "title": "Small swing",
...          "params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 0.2},
...          "run": {"t_end": 2.0, "samples": 201}}
>>> outcome = reportgen.run(scene, out=str(tmp), formats=("html",))
>>> outcome.name, outcome.status
('small_swing', 'ok')
>>> r = reportgen.open(outcome.folder)
>>> r.kind, r.title, r.status
('pendulum', 'Small swing', 'ok')
>>> r.behaviour.split(":")[0]
'libration'
>>> ds = r.to_xarray()
>>> ds.theta.attrs["units"], ds.theta.attrs["long_name"]
('rad', 'angle from the downward vertical')
>>> float(ds.theta.sel(t=0.0))
0.2
>>> r.results["period"].unit, r.results["period"].symbol
('s', 'T')
>>> tree = r.to_datatree()
>>> tree["runs/main"]["y"].dims, str(tree["checks"]["quantity"].dtype)[:2]
(('t', 'component'), '<U')
>>> reportgen.run({"kind": "pendulum"}, out=str(tmp), name="bad")
Traceback (most recent call last):
    ...
reportgen.errors.ConfigError: ...
"""

from __future__ import annotations

import contextlib
import html
import json
import re
import unicodedata
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from .errors import ConfigError

__all__ = ["Run", "kinds", "open", "run", "verify"]

#: how many of the report's figures :meth:`Run._repr_html_` shows inline
REPR_FIGURES = 3


# ---------------------------------------------------------------------- run
def _slug(text: str) -> str:
    """``"Hénon–Heiles (θ0 = 0.2)"`` -> ``"henon_heiles_0_0_2"``: a scene name (accents
    dropped, letters without an ASCII form too)."""
    plain = "".join(unicodedata.normalize("NFKD", c).encode("ascii", "ignore").decode("ascii")
                    or " " for c in text)
    return re.sub(r"[^a-z0-9]+", "_", plain.lower()).strip("_")


def _write_source(config: Mapping, out: Path, name: str | None,
                  before_writing: Callable[[], None] = lambda: None) -> Path:
    """The dict ``config`` as ``out/<name>/<name>.toml`` (inside ``out``, never outside),
    validated first: a rejected dict writes nothing.

    Without ``name``, the scene is named by the dict's title, else by its kind; an untitled
    dict whose folder holds a run of other physics is refused (naming that run and
    ``name=``) rather than replacing it.  A title names one scene: a titled dict with
    edited physics replaces its earlier run, as an edited config file does."""
    from .kinds import load_scene
    from .scene.config import MAX_CONFIG_NESTING, parse_config_text, to_toml
    from .support.fsutil import atomic_write, links_out
    from .support.layout import printable, scene_name_problem

    title = str(config.get("title") or "")
    stem = name or _slug(title) or _slug(str(config.get("kind", "")))
    if not stem:
        raise ConfigError(["the config dict has no title or kind to name the scene by "
                           "(pass name=...)"])
    problem = scene_name_problem(stem)
    if problem is not None:  # a name leading out of ``out``: nothing written
        raise ConfigError([f"scene name {printable(repr(stem))} {problem}"])
    folder = out / stem
    path = folder / f"{stem}.toml"
    try:
        text = to_toml(dict(config))
    except (TypeError, ValueError) as exc:
        raise ConfigError([f"config dict {stem!r}: {exc}"]) from None
    except RecursionError:  # nested thousands deep (a shallower one fails as text, below)
        deep = _nesting(config, MAX_CONFIG_NESTING) or "?"
        raise ConfigError([f"config dict {stem!r}: key {printable(deep)!r} nested more than "
                           f"{MAX_CONFIG_NESTING} tables or lists deep, as a config file may "
                           f"not be"]) from None
    scene = load_scene(parse_config_text(text, path))  # ConfigError: nothing written
    before_writing()  # the output folder's lock, from here to the end of the run
    escaping = links_out(folder, out)
    if escaping:
        raise ConfigError([f"{printable(str(escaping[0]))} is a symbolic link leading outside "
                           f"{printable(str(out))}: not followed (remove the link)"])
    if name is None and not title:
        other = _other_physics(folder / "run.h5", scene.physics_key())
        if other is not None:
            raise ConfigError([
                f"{printable(str(folder))} holds another {scene.kind} run ({other}) with other "
                f"physics than this untitled dict: pass name=... (or a title) to run it beside "
                f"that one, or name={stem!r} to replace it"])
    if not path.is_file() or path.read_bytes() != text.encode("utf-8"):
        folder.mkdir(parents=True, exist_ok=True)
        atomic_write(path, text.encode("utf-8"))
    return path


def _nesting(config: Mapping, limit: int) -> str | None:
    """The dotted key of the first value of ``config`` nested more than ``limit`` tables
    or lists deep, else None; without recursion."""
    stack = [(config, "", 0)]
    while stack:
        value, key, depth = stack.pop()
        if depth > limit:
            return key[:80]
        if isinstance(value, Mapping):
            stack.extend((v, f"{key}.{k}" if key else str(k), depth + 1)
                         for k, v in value.items())
        elif isinstance(value, list | tuple):
            stack.extend((v, f"{key}[]", depth + 1) for v in value
                         if isinstance(v, Mapping | list | tuple))
    return None


def _other_physics(archive: Path, key: str) -> str | None:
    """The title of the run in ``archive`` if its physics key is not ``key`` (None when
    the same, or no readable archive is there: nothing of another scene to lose)."""
    from .archive.store import stored_identity

    identity = stored_identity(archive) if archive.exists() else None
    if identity is None or identity.physics_key in ("", key):
        return None
    import h5py

    try:
        with h5py.File(archive, "r") as f:
            title = f.attrs.get("title", "")
        title = title.decode("utf-8") if isinstance(title, bytes) else str(title)
    except (OSError, ValueError):
        title = ""
    return f"'{title}'" if title else "untitled"


@contextlib.contextmanager
def _callers_matplotlib():
    """Draw in the report's style and leave the caller's matplotlib as it was: every
    rcParam (the style is set for the run, issue 43) and pyplot's backend, which the
    style's import sets to Agg (a notebook's inline backend would stop showing figures)."""
    import sys

    import matplotlib

    saved = dict(matplotlib.rcParams)
    backend = saved.pop("backend")
    try:
        from .rendering.plots.style import RC

        matplotlib.rcParams.update(RC)  # again on every run: an earlier one restored
        yield
    finally:
        dict.update(matplotlib.rcParams, saved)  # as they were, unvalidated, no switching
        if dict.__getitem__(matplotlib.rcParams, "backend") != backend:
            pyplot = sys.modules.get("matplotlib.pyplot")
            if pyplot is not None:
                pyplot.switch_backend(backend)
            else:
                dict.__setitem__(matplotlib.rcParams, "backend", backend)


def run(source: str | Path | Mapping, out: str | Path = "output", *, force: bool = False,
        formats: tuple[str, ...] | None = None, name: str | None = None,
        time_limit: float | None = 600.0):
    """Run scenes as ``reportgen run`` does, each stage only when its inputs changed.

    ``source``: a TOML config, a folder (every ``*.toml`` below it) or a dict with the
    keys of a config, validated, then written as TOML to ``out/<name>/<name>.toml``
    (``name``: the argument, else the dict's title as a slug, else its kind; an untitled
    dict is refused rather than replace a run of other physics there).  Returns the scene's
    :class:`~reportgen.pipeline.stages.Outcome` (a list of them for a folder); a bad
    config raises :class:`~reportgen.errors.ConfigError` before anything runs, a failed
    simulation comes back as the outcome's ``status`` and ``message``.  ``formats``
    (("html",), say) overrides the config's ``[report] formats``.  ``time_limit``: seconds
    each scene may take, its validation included, as ``reportgen run --time-limit`` (None:
    none; enforced from the main thread): a scene over it comes back failed, its earlier
    archive kept.  While it runs, numpy's BLAS uses one thread (the caller's count is given
    back after): see :mod:`reportgen.support.threads`.
    """
    import threading

    from .pipeline.stages import (
        Outcome,
        _alarm,
        _time_limit_message,
        _TimeLimit,
        run_scene,
        validate_all,
    )
    from .support.layout import collect_configs
    from .support.threads import one_blas_thread

    if time_limit is not None and not (isinstance(time_limit, int | float)
                                       and 0 < time_limit < float("inf")):
        raise ConfigError([f"time_limit must be a positive number of seconds or None "
                           f"(got {time_limit!r})"])
    if threading.current_thread() is not threading.main_thread():
        time_limit = None  # the alarm that stops a scene is the main thread's

    if formats is not None:
        if isinstance(formats, str | bytes) or not all(f in ("html", "pdf") for f in formats):
            raise ConfigError([f"formats must be a list of 'html' and 'pdf', e.g. ['html'] "
                               f"(got {formats!r})"])
    from .errors import UsageError
    from .support.fsutil import output_folder, output_lock

    out = Path(out)
    outcomes = []
    with contextlib.ExitStack() as held:
        def lock() -> None:
            """The output folder's lock, as `reportgen run` takes it, held to the end."""
            try:
                held.enter_context(output_lock(output_folder(out)))
            except UsageError as exc:
                raise ConfigError([str(exc)]) from None

        if isinstance(source, Mapping):
            paths = [_write_source(source, out, name, before_writing=lock)]
        else:
            try:
                paths = collect_configs([source])
            except UsageError as exc:
                raise ConfigError([str(exc)]) from None
            validate_all(paths, time_limit)
            lock()
        held.enter_context(one_blas_thread())  # as the command has (support/threads.py)
        with _callers_matplotlib():
            for path in paths:
                try:
                    with _alarm(time_limit):
                        outcome = run_scene(str(path), str(out), force,
                                            tuple(formats) if formats else None)
                except _TimeLimit:
                    outcome = Outcome(name=Path(path).stem, status="failed",
                                      message=_time_limit_message(time_limit))
                if outcome.config_error:
                    raise ConfigError([outcome.message])
                outcomes.append(outcome)
    single = isinstance(source, Mapping) or Path(source).is_file()
    return outcomes[0] if single else outcomes


# ---------------------------------------------------------------------- verify
def verify(path: str | Path):
    """Re-simulate an archive (``run.h5``, or each one below a folder) from its own stored
    config with the installed reportgen and compare every stored number, as
    ``reportgen verify`` does; nothing is written beside the archive.  Returns a
    :class:`~reportgen.pipeline.verify.Verification` (a list of them for a folder): its
    ``verdict`` ("identical", "different", "unreadable"), ``differences`` (path, largest
    absolute and relative difference, the rtol that would pass), ``code_changed`` and the
    ``libraries`` whose versions differ."""
    from .pipeline.verify import archives_in, verify_archive

    path = Path(path)
    if not path.is_dir():
        return verify_archive(path)
    return [verify_archive(archive) for archive in archives_in([path])]


# ---------------------------------------------------------------------- open
#: the largest figure file the notebook view inlines
MAX_INLINE_SVG_BYTES = 8 * 2**20


def _inlinable_svg(path: Path) -> str | None:
    """The SVG drawing of the figure file ``path`` as the sanitizer writes it
    (:func:`~reportgen.support.svgsafe.clean_svg`: an output folder is untrusted), read
    only if a regular file, not a link or a FIFO, of at most :data:`MAX_INLINE_SVG_BYTES`
    (:func:`~reportgen.support.fsutil.read_back`); else None."""
    from .support.fsutil import read_back
    from .support.svgsafe import SvgRefused, clean_svg

    try:
        return clean_svg(read_back(path, MAX_INLINE_SVG_BYTES)).svg
    except (OSError, SvgRefused):
        return None


def _ident(name: str, taken: set[str]) -> str:
    """``name`` as a Python identifier (``initial.theta`` -> ``initial_theta``), unique in
    ``taken`` (which it joins)."""
    out = re.sub(r"\W", "_", name) or "_"
    if out[0].isdigit():
        out = "_" + out
    base, n = out, 1
    while out in taken:
        n += 1
        out = f"{base}_{n}"
    taken.add(out)
    return out


def _plain(value):
    """An attribute value as Python (str, not bytes; lists, not string arrays)."""
    import numpy as np

    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()] if value.dtype.kind in "OSU" else value
    if isinstance(value, np.generic):
        return value.item()
    return value


def _group_attrs(path: Path, group: str) -> dict[str, dict[str, Any]]:
    """The attributes of every variable of ``group`` in the archive (validated already)."""
    import xarray as xr

    try:
        with xr.open_dataset(path, group=group, engine="h5netcdf", phony_dims="access",
                             decode_cf=False) as raw:
            return {k: {a: _plain(v) for a, v in raw[k].attrs.items()} for k in raw.variables}
    except (OSError, ValueError, KeyError):
        return {}


def _tables_as_groups(tree, h5: Path):
    """``tree`` (an archive of format ≤ 2 opened whole) with its compound tables (``/checks``,
    ``/study/error_vs_runtime``) as groups of named, typed columns, as format 3 stores them."""
    import h5py
    import numpy as np
    import xarray as xr

    from .archive.h5io import read_table

    rows = {"checks": "check", "study/error_vs_runtime": "row"}  # format 3's dimensions
    with h5py.File(h5, "r") as f:
        tables = {path: read_table(f[path]) for path in rows
                  if isinstance(f.get(path), h5py.Dataset) and f[path].dtype.names}
    nodes = {node.path: node.to_dataset(inherit=False) for node in tree.subtree}
    for path, records in tables.items():
        parent, _, name = f"/{path}".rpartition("/")
        holder = nodes[parent or "/"]
        attrs = {}
        if name in holder.variables:
            old_dim, attrs = holder[name].dims[0], dict(holder[name].attrs)
            holder = holder.drop_vars(name)
            if not any(old_dim in v.dims for v in holder.data_vars.values()):
                holder = holder.drop_vars([old_dim], errors="ignore")
        nodes[parent or "/"] = holder
        dim = rows[path]
        columns = {c: (dim, records[c].astype(str) if records[c].dtype == object
                       else records[c]) for c in records.dtype.names}
        nodes[f"/{path}"] = xr.Dataset(columns, coords={dim: np.arange(len(records))},
                                       attrs={k: v for k, v in attrs.items()
                                              if k not in ("units", "symbol")})
    return xr.DataTree.from_dict(nodes)


def _cf(attrs: dict[str, Any]) -> dict[str, Any]:
    return {k: attrs[k] for k in ("units", "long_name", "symbol", "config_units")
            if k in attrs}


def _decoded(values, attrs: dict[str, Any]):
    """(``values`` in their ``units``, their CF attributes): a value stored as a multiple
    of its unit (CF ``scale_factor``: a time in τ = 4.0746 fs, units "fs") scaled, as
    xarray decodes it."""
    import numpy as np

    factor = attrs.get("scale_factor")
    values = np.asarray(values)
    return (values * float(factor) if factor is not None else values), _cf(attrs)


class Run:
    """A scene's archive read through the validating reader (a bad file raises
    :class:`~reportgen.archive.h5io.ArchiveError`).

    ``config`` (the resolved config, a dict), ``kind``, ``title``, ``status``,
    ``message``, ``behaviour`` (the ``/analysis`` verdict, or None), ``results`` (the
    scalar analysis results with their units, :attr:`results`), ``checks`` (dicts:
    quantity, value, reference, abs_error, rel_error, unit, source) and ``h5`` (the
    archive's path).
    """

    def __init__(self, path: str | Path):
        from .archive.store import read_archive

        path = Path(path)
        self.h5 = path / "run.h5" if path.is_dir() else path
        self.data = read_archive(self.h5)
        d = self.data
        self.config: dict[str, Any] = json.loads(json.dumps(d.config))
        self.kind, self.title, self.status, self.message = d.kind, d.title, d.status, d.message
        behaviour = d.analysis.get("behaviour") if d.sweep is None else None
        self.behaviour: str | None = str(behaviour) if behaviour else None
        self.checks: list[dict[str, Any]] = [
            {"quantity": c.quantity, "value": c.value, "reference": c.reference,
             "abs_error": c.abs_error, "rel_error": c.rel_error, "unit": c.unit,
             "source": c.source} for c in d.checks]

    def __repr__(self) -> str:
        return f"<reportgen.Run {self.kind} {self.title!r} {self.status} ({self.h5})>"

    # ------------------------------------------------------------- results
    @property
    def results(self):
        """The scalar results of ``/analysis`` (and its subgroups, as "group/name"), each a
        :class:`~reportgen.quantities.Result` with ``value``, ``unit`` (pint reads it),
        ``description``, ``symbol`` and ``config_units`` from the kind's declaration:
        ``float(run.results["period"])``, ``run.results["period"].value`` or
        ``run.results.period.quantity`` (a pint Quantity); ``values_only()`` gives the
        bare numbers."""
        cached = self.__dict__.get("_results")
        if cached is None:
            from .quantities import archive_results

            cached = self.__dict__["_results"] = archive_results(self.data)
        return cached

    # ------------------------------------------------------------- xarray
    def to_datatree(self):
        """The whole archive as one :class:`xarray.DataTree`, every group a node, loaded
        into memory (the file is closed again): what
        ``xr.open_datatree(run.h5, engine="h5netcdf")`` gives for an archive of format 3,
        where every variable has named dimensions, each number a ``units`` pint reads
        (``ds.pint.quantify()``) and the checks and study tables are groups of typed columns.
        An archive of an earlier format opens the same way: its tables (compound datasets)
        become such groups and its unnamed dimensions are named as h5netcdf names them."""
        import warnings

        import xarray as xr

        old = self.data.format_version < 3
        with warnings.catch_warnings():
            if old:  # format ≤ 2: h5netcdf names its unnamed dimensions, and says so
                warnings.simplefilter("ignore")
            with xr.open_datatree(self.h5, engine="h5netcdf",
                                  **({"phony_dims": "access"} if old else {})) as tree:
                tree = tree.load().copy()
        if old:
            tree = _tables_as_groups(tree, self.h5)
        return tree

    def to_xarray(self, group: str | None = None):
        """The archive, or one group of it, as an :class:`xarray.Dataset` with
        ``units`` and ``long_name`` on every variable.

        Without ``group``: a sweep is one dataset on ``member``, the swept values as
        coordinates (``initial.theta`` -> ``initial_theta``) and per member its scalar
        results and ``status``; otherwise the main run on the coordinate ``t``, one
        variable per state column (named by the column), the invariants and reference
        solutions; a kind that integrates nothing (normal modes, rotations, inertia)
        gives its ``/analysis`` group.  A sweep's point sets (a surface of section's
        crossings, a varying number per member) join it on their own dimension
        ``<set>_point``, with ``<set>_member`` naming each point's member.  ``group``
        names any group of the archive instead: ``"analysis"``, ``"runs/loops"``,
        ``"sweep/points/crossings"`` (a sweep's point sets, each point with its
        ``member``), ``"study"``."""
        if group is not None:
            return self._group_xarray(group)
        if self.data.sweep is not None:
            return self._sweep_xarray()
        if "main" not in self.data.runs:
            if self.data.runs:
                raise ValueError(f"{self.h5}: the archive holds no main run; ask for one of "
                                 + ", ".join(f"group='runs/{r}'" for r in self.data.runs))
            return self._group_xarray("analysis")
        import numpy as np
        import xarray as xr

        run = self.data.runs["main"]
        attrs = _group_attrs(self.h5, "runs/main")
        y = attrs.get("y", {})
        n = len(run.t)
        per_column = {key: list(y.get(f"column_{key}") or [""] * len(run.columns))
                      for key in ("units", "long_names", "symbols")}
        factors = list(y.get("column_scale_factors", [1.0] * len(run.columns)))
        taken = {"t"}
        variables = {}
        table = np.asarray(run.y).reshape(n, -1)
        for i, column in enumerate(run.columns):
            cf = {"units": str(per_column["units"][i]),
                  "long_name": str(per_column["long_names"][i]) or column,
                  "symbol": str(per_column["symbols"][i])}
            if "config_units" in y and cf["units"] == "1":  # one attr for all of y's "1"
                cf["config_units"] = y["config_units"]
            variables[_ident(column, taken)] = ("t", table[:, i] * float(factors[i]), cf)
        for q, values in run.invariants.items():
            if np.ndim(values) == 1 and len(values) == n:
                linked = q if q in attrs else f"invariant_{q}"
                variables[_ident(q, taken)] = ("t", *_decoded(values, attrs.get(linked, {})))
        for c, values in run.reference.items():
            if np.ndim(values) == 1 and len(values) == n:
                variables[_ident(f"reference_{c}", taken)] = (
                    "t", *_decoded(values, attrs.get(f"reference_{c}", {})))
        times, t_attrs = _decoded(np.asarray(run.t), attrs.get("t", {}))
        t_attrs = t_attrs or {"units": "s", "long_name": "time"}
        return xr.Dataset(variables, coords={"t": ("t", times, t_attrs)},
                          attrs=self._dataset_attrs())

    def _group_xarray(self, group: str, stamp: bool = True):
        import h5py
        import xarray as xr

        group = group.strip("/")
        with h5py.File(self.h5, "r") as f:
            if not isinstance(f.get(group or "/"), h5py.Group):
                groups: list[str] = []
                f.visititems(lambda n, o: groups.append(n) if isinstance(o, h5py.Group)
                             else None)
                raise ValueError(f"{self.h5}: no group {group!r} (groups: "
                                 f"{', '.join(sorted(groups))})")
        with xr.open_dataset(self.h5, group=group or "/", engine="h5netcdf") as ds:
            out = ds.load()
        if stamp:
            out.attrs.update(self._dataset_attrs())
        return out

    def _dataset_attrs(self) -> dict[str, Any]:
        out = {"kind": self.kind, "title": self.title, "status": self.status,
               "message": self.message, "archive": str(self.h5)}
        if self.behaviour:
            out["behaviour"] = self.behaviour
        return out

    def _sweep_xarray(self):
        import numpy as np
        import xarray as xr

        sweep = self.data.sweep
        values_attrs = _group_attrs(self.h5, "sweep/values")
        analysis_attrs = _group_attrs(self.h5, "sweep/analysis")
        taken = {"member", "status", "message"}
        coords: dict[str, Any] = {"member": ("member", np.arange(sweep.size),
                                             {"long_name": "member of the sweep", "units": "1"})}
        for key, values in sweep.values.items():
            cf = _cf(values_attrs.get(key, {}))
            cf.setdefault("long_name", f"swept value of {key}")
            cf["config_key"] = key
            coords[_ident(key, taken)] = ("member", np.asarray(values, dtype=float), cf)
        variables: dict[str, Any] = {
            "status": ("member", np.asarray([str(s) for s in sweep.status], dtype=str),
                       {"long_name": "the member's run status", "units": ""}),
            "message": ("member", np.asarray([str(s) for s in sweep.message], dtype=str),
                        {"long_name": "why the member is not ok", "units": ""})}
        for key, values in sweep.analysis.items():
            variables[_ident(key, taken)] = ("member", np.asarray(values, dtype=float),
                                             _cf(analysis_attrs.get(key, {})))
        for key, values in sweep.labels.items():
            variables[_ident(key, taken)] = ("member", np.asarray([str(v) for v in values],
                                                                  dtype=str), {})
        ds = xr.Dataset(variables, coords=coords, attrs=self._dataset_attrs())
        for name in sweep.points:  # crossings and the like: a varying number per member
            points = self._group_xarray(f"sweep/points/{name}", stamp=False)
            names = set(points.variables) | set(points.dims)
            points = points.rename({v: f"{name}_{v}" for v in names})
            ds.attrs.update({f"{name}_{k}": v for k, v in points.attrs.items()})
            ds = ds.merge(points.drop_attrs(deep=False), combine_attrs="override")
        return ds

    # ------------------------------------------------------------- notebook
    def headline(self) -> list[tuple[str, str]]:
        """The kind's headline facts (label, value) as the report shows them."""
        from .rendering.report import kind_of_archive

        return [(str(a), str(b)) for a, b in kind_of_archive(self.data).headline(self.data)]

    def figures(self) -> list[Path]:
        """The report's SVG figures beside the archive (``figures/*.svg``), if drawn."""
        return sorted((self.h5.parent / "figures").glob("*.svg"))

    def signature_figures(self) -> list[Path]:
        """The kind's signature figures this scene drew (its report's ``gallery_figures``,
        in that order: the gallery card's thumbnail first), else the report's first figure;
        from the figures' validated manifest, so [] when none was drawn."""
        from .kinds import KINDS
        from .scene.gallery import signature_figures
        from .support.layout import drawn_svg_figures

        folder = self.h5.parent
        drawn = drawn_svg_figures(folder)
        picked = signature_figures([str(fig.get("id", "")) for fig in drawn],
                                   tuple(getattr(KINDS.get(self.kind), "gallery_figures", ())))
        return [folder / drawn[i]["files"]["svg"] for i in picked]

    def _repr_html_(self) -> str:
        from .support.layout import visible_controls

        def e(text) -> str:  # what the archive says, escaped, its controls shown
            return html.escape(visible_controls(str(text)))

        parts = [f"<h3>{e(self.title or self.kind)}</h3>",
                 f"<p><b>{e(self.kind)}</b> &middot; status <b>{e(self.status)}</b>"
                 + (f" &middot; {e(self.message)}" if self.message else "")
                 + (f" &middot; {e(self.behaviour)}" if self.behaviour else "") + "</p>"]
        try:
            facts = self.headline()
        except Exception as exc:  # a notebook view shows what it can
            facts = [("headline", f"unavailable ({type(exc).__name__}: {exc})")]
        if facts:
            parts.append("<table>" + "".join(f"<tr><th style='text-align:left'>{e(a)}</th>"
                                             f"<td>{e(b)}</td></tr>" for a, b in facts)
                         + "</table>")
        for svg in self.signature_figures()[:REPR_FIGURES]:
            text = _inlinable_svg(svg)
            if text is not None:
                parts.append(f"<div style='max-width:40em' title='{e(svg.name)}'>"
                             f"{text}</div>")
        from .scene.typeset import typeset_html

        return typeset_html("\n".join(parts))  # as the report's pages are typeset


def open(path: str | Path) -> Run:  # noqa: A001 - reportgen.open, like io.open
    """The archive ``path`` (``run.h5``, or the scene folder holding it) as a :class:`Run`."""
    return Run(path)


# ---------------------------------------------------------------------- kinds
def kinds() -> list[dict[str, Any]]:
    """Every scene kind: ``name``, ``summary``, ``presets`` (names) and ``keys``, one dict
    per key as ``reportgen kinds`` lists them (``key`` dotted, ``type``, ``default``,
    ``description``, ``units`` when the description ends in one).

    >>> pendulum = [k for k in kinds() if k["name"] == "pendulum"][0]
    >>> [(k["key"], k["units"]) for k in pendulum["keys"] if k["key"].startswith("initial.")]
    [('initial.theta', 'rad'), ('initial.theta_dot', 'rad/s')]
    """
    from .kinds import KINDS
    from .scene.catalogue import _SHARED_KEYS, _field_rows
    from .scene.schema import split_unit

    out = []
    for cls in KINDS.values():
        fields = cls.Config.model_fields
        overrides = {key: {"meaning": fields[key].description or text}
                     for key, text in _SHARED_KEYS.items() if key in fields}
        keys, table = [], ""
        for indent, key, kind, default, meaning in _field_rows("", fields, 4, overrides):
            if not (kind or default):  # a table header: [params], [[bodies]]
                table = key.strip("[]") if indent == 4 else table
                continue
            description, unit = split_unit(meaning)  # the unit the value converter reads
            keys.append({"key": f"{table}.{key}" if indent > 4 and table else key,
                         "type": kind, "default": default, "description": description,
                         "units": unit})
        out.append({"name": cls.kind, "summary": cls.summary,
                    "presets": list(cls.presets), "keys": keys})
    return out
