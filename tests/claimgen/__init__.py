"""Config generators for the claims test (``tests/test_claims.py``), one module per kind.

Each module ``tests/claimgen/<kind>.py`` exposes

- ``configs()``: a hypothesis strategy of config dicts of that kind (TOML-serialisable,
  no title: a scene nobody shipped), spread over the kind's case space -- both sides of
  every threshold a claim-carrying sentence is chosen by;
- ``EXAMPLES``: how many of them one run of the test draws (96 over the twelve kinds, to
  keep the suite's time; ``REPORTGEN_CLAIMS_SCALE=N`` draws N times as many: the issue's
  run of 200 and more is ``REPORTGEN_CLAIMS_SCALE=3 pytest tests/test_claims_*.py``).

Each kind's claims test is ``tests/test_claims_<kind>.py`` (one file each, so that the
test workers share them out): ``test_claims_hold = claims_test("<kind>")``.

:func:`contradictions_of` runs one config (simulate without the study, then the report's
text without saving a figure) and returns the claims its report makes that its archive
contradicts: what the test asserts empty, and what a kind's own tests may call directly.
"""

from __future__ import annotations

import importlib
import os
import pkgutil
import shutil
import tempfile
from pathlib import Path


def kinds() -> list[str]:
    """The kinds with a generator module here."""
    return sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_"))


def generator(kind: str):
    return importlib.import_module(f"claimgen.{kind}")


def run_config(config: dict, folder: Path, name: str = "scene"):
    """Simulate ``config`` (a dict) into ``folder/<name>/run.h5`` and return the archive
    (:class:`reportgen.archive.store.ArchiveData`)."""
    from reportgen.archive.store import read_archive
    from reportgen.kinds import load_scene
    from reportgen.pipeline.stages import simulate_scene
    from reportgen.scene.config import read_config, to_toml

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.toml"
    path.write_text(to_toml(config), encoding="utf-8")
    scene = load_scene(read_config(path))
    archive = simulate_scene(scene, folder / name)
    return read_archive(archive)


def contradictions_of(config: dict, folder: Path, name: str = "scene") -> tuple[list[str], str]:
    """(contradictions, report text) of ``config``: every claim of its report that its
    archive contradicts (empty: all true)."""
    from reportgen.rendering.report import report_text
    from reportgen.scene.claims import contradictions

    data = run_config(config, folder, name)
    text = report_text(data)
    return contradictions(data, text), text


def claims_test(kind: str):
    """The claims test of ``kind``: hypothesis draws ``EXAMPLES`` (times
    ``REPORTGEN_CLAIMS_SCALE``) configs from its generator; every claim each report makes
    must hold for its archive."""
    from hypothesis import HealthCheck, given, settings

    module = generator(kind)
    scale = float(os.environ.get("REPORTGEN_CLAIMS_SCALE", "1"))

    @settings(max_examples=max(1, round(module.EXAMPLES * scale)), deadline=None,
              database=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(config=module.configs())
    def test_claims_hold(config):
        folder = Path(tempfile.mkdtemp(prefix=f"claims-{kind}-"))
        try:
            found, _ = contradictions_of(config, folder)
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        assert not found, f"{config}\n" + "\n".join(found)

    test_claims_hold.__doc__ = f"Every claim of a generated {kind} scene's report holds."
    return test_claims_hold
