"""Stage keys from the import graph: reportgen.support.codestamp.module_files / code_hash."""

from __future__ import annotations

import ast
import os
import shutil
import textwrap
from pathlib import Path

import pytest

from reportgen.support import codestamp
from reportgen.support.codestamp import PACKAGE, code_hash, files_hash, module_files

#: a package shaped like reportgen after the kinds restructuring
SOURCES = {
    "__init__.py": """
        '''The package; it imports plots, which a simulation must not get through it.'''
        from . import plots
        """,
    "lazy.py": """
        import importlib

        def lazy_module(name):
            return importlib.import_module(name)
        """,
    "plots.py": "import matplotlib\n",
    "core/__init__.py": "from . import heavy\n",
    "core/heavy.py": "import numpy\n",
    "core/x.py": "X = 1\n",
    "core/y.py": "def f():\n    return 2\n",
    "core/typing_only.py": "class T: ...\n",
    "core/sub/__init__.py": "from . import deep\n",
    "core/sub/deep.py": "DEEP = 3\n",
    "kinds/__init__.py": """
        import importlib
        import pkgutil

        def discover():
            for info in pkgutil.iter_modules(__path__):
                importlib.import_module(f"{__name__}.{info.name}")
        """,
    "kinds/shared.py": "def helper():\n    return 4\n",
    "kinds/a/__init__.py": "from . import report, simulation\n",
    "kinds/a/config.py": "N = 5\n",
    "kinds/a/simulation.py": '''
        """The physics.  A docstring is no import:

            from pkg.core import heavy
        import pkg.plots
        """

        from __future__ import annotations

        from typing import TYPE_CHECKING

        import numpy as np

        from pkg.core import sub
        from pkg.lazy import lazy_module

        from ..shared import helper
        from . import config

        # import pkg.plots
        x = lazy_module("pkg.core.x")
        gone = lazy_module("pkg.core.gone")

        if TYPE_CHECKING:
            from pkg.core import typing_only

            from .report import render


        def run() -> float:
            from pkg.core.y import f
            import pkg.nowhere.at_all
            from pkg.nothing import thing
            from .missing import what
            return f() + helper() + config.N + np.pi + x.X + sub.deep.DEEP
        ''',
    "kinds/a/report.py": """
        from pkg.plots import matplotlib

        from ..shared import helper
        from . import config

        def render():
            return helper() + config.N
        """,
}

SIMULATION = {
    "__init__.py", "lazy.py", "core/__init__.py", "core/x.py", "core/y.py",
    "core/sub/__init__.py", "core/sub/deep.py", "kinds/__init__.py", "kinds/shared.py",
    "kinds/a/__init__.py", "kinds/a/config.py", "kinds/a/simulation.py",
}


def write_package(folder: Path, sources: dict[str, str] = SOURCES) -> Path:
    root = folder / "pkg"
    for name, text in sources.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip())
    return root


@pytest.fixture
def pkg(tmp_path: Path) -> Path:
    return write_package(tmp_path)


def closure(root: Path, *modules: str) -> set[str]:
    return {path.relative_to(root).as_posix() for path in module_files(modules, root, "pkg")}


def key(root: Path, *modules: str) -> str:
    return code_hash(modules, root, "pkg")


def edit(path: Path, text: str) -> None:
    """Append ``text`` to ``path``, surely seen as a new version of the file."""
    stat = path.stat()
    path.write_text(path.read_text() + textwrap.dedent(text))
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 1_000_000_000))


def test_closure_of_a_simulation(pkg):
    files = module_files(["pkg.kinds.a.simulation"], pkg, "pkg")
    assert files == sorted(files)
    assert {path.relative_to(pkg).as_posix() for path in files} == SIMULATION
    # a package's __init__ run on the way is hashed, its imports are not followed: not
    # the kind's report (kinds/a/__init__), the plots (pkg/__init__), core.heavy
    # (core/__init__); TYPE_CHECKING-only imports never run


def test_report_edit_changes_the_report_key_only(pkg):
    simulation, report = key(pkg, "pkg.kinds.a.simulation"), key(pkg, "pkg.kinds.a.report")
    assert len(simulation) == 16 and int(simulation, 16) >= 0
    assert "kinds/a/report.py" not in closure(pkg, "pkg.kinds.a.simulation")
    assert "plots.py" in closure(pkg, "pkg.kinds.a.report")
    edit(pkg / "kinds/a/report.py", "CAPTION = 'another caption'\n")
    assert key(pkg, "pkg.kinds.a.simulation") == simulation
    assert key(pkg, "pkg.kinds.a.report") != report


def test_shared_edit_changes_both_keys(pkg):
    simulation, report = key(pkg, "pkg.kinds.a.simulation"), key(pkg, "pkg.kinds.a.report")
    edit(pkg / "kinds/shared.py", "# a comment is an edit too\n")
    assert key(pkg, "pkg.kinds.a.simulation") != simulation
    assert key(pkg, "pkg.kinds.a.report") != report


def test_edits_that_add_an_import_are_seen(pkg):
    assert "core/heavy.py" not in closure(pkg, "pkg.kinds.a.simulation")
    edit(pkg / "kinds/a/config.py", "from pkg.core import heavy\n")
    assert "core/heavy.py" in closure(pkg, "pkg.kinds.a.simulation")


def test_same_key_in_every_checkout(pkg, tmp_path):
    other = tmp_path / "elsewhere"
    shutil.copytree(pkg, other / "pkg")
    assert key(other / "pkg", "pkg.kinds.a.simulation") == key(pkg, "pkg.kinds.a.simulation")
    files = module_files(["pkg.kinds.a.simulation"], pkg, "pkg")
    assert key(pkg, "pkg.kinds.a.simulation") == files_hash(files, pkg)


def test_type_checking_imports_do_not_count_but_their_else_does(tmp_path):
    root = write_package(tmp_path, {
        "__init__.py": "",
        "t1.py": "",
        "t2.py": "",
        "t3.py": "",
        "main.py": """
            import typing
            from typing import TYPE_CHECKING

            if TYPE_CHECKING:
                from . import t1
            else:
                from . import t2
            if typing.TYPE_CHECKING:
                import pkg.t3
            """,
    })
    assert closure(root, "pkg.main") == {"__init__.py", "main.py", "t2.py"}


def test_missing_imports_are_ignored_but_not_missing_roots(pkg):
    # the simulation imports pkg.nowhere.at_all, pkg.nothing, .missing, pkg.core.gone
    assert closure(pkg, "pkg.kinds.a.simulation") == SIMULATION
    for roots in (["pkg.kinds.a.simulation", "pkg.kinds.nope"], ["numpy"], ["pkg.core.x.X"]):
        with pytest.raises(ModuleNotFoundError):
            module_files(roots, pkg, "pkg")
    assert module_files("pkg.kinds.a.simulation", pkg, "pkg") == module_files(
        ["pkg.kinds.a.simulation"], pkg, "pkg")


def test_explicit_package_imports_are_followed(pkg):
    assert closure(pkg, "pkg.core") == {"__init__.py", "core/__init__.py", "core/heavy.py"}
    # the kinds' package discovers them dynamically: not one kind in its closure
    assert closure(pkg, "pkg.kinds") == {"__init__.py", "kinds/__init__.py"}
    # a kind's package composes its simulation and report
    assert {"kinds/a/report.py", "kinds/a/simulation.py", "plots.py"} <= closure(
        pkg, "pkg.kinds.a")
    # the root package itself
    assert closure(pkg, "pkg") == {"__init__.py", "plots.py"}


def test_from_package_import_attribute_follows_the_package(tmp_path):
    root = write_package(tmp_path, {
        "__init__.py": "",
        "core/__init__.py": "from .impl import solve\n",
        "core/impl.py": "def solve(): ...\n",
        "user.py": "from pkg.core import solve\n",
        "other.py": "from .core import impl\n",
    })
    assert closure(root, "pkg.user") == {"__init__.py", "user.py", "core/__init__.py",
                                        "core/impl.py"}
    assert closure(root, "pkg.other") == {"__init__.py", "other.py", "core/__init__.py",
                                         "core/impl.py"}


def test_relative_imports_from_a_package_init(tmp_path):
    root = write_package(tmp_path, {
        "__init__.py": "",
        "a/__init__.py": "from . import b\nfrom .. import top\nfrom ... import beyond\n",
        "a/b.py": "",
        "top.py": "",
    })
    assert closure(root, "pkg.a") == {"__init__.py", "a/__init__.py", "a/b.py", "top.py"}


def test_dynamic_imports(tmp_path):
    root = write_package(tmp_path, {
        "__init__.py": "",
        "x.py": "",
        "y.py": "",
        "z.py": "",
        "w.py": "",
        "v.py": "",
        "discovered.py": "",
        "lazy.py": "",
        "user.py": """
            import importlib
            from importlib import import_module

            from . import lazy

            X = lazy.lazy_module("pkg.x")
            Y = importlib.import_module("pkg.y")
            Z = import_module(".z", __package__)
            W = import_module(".w", "pkg")
            V = lazy.lazy_module(name="pkg.v")
            NOT_A_LITERAL = import_module("pkg." + "discovered")


            def load(name):
                return import_module(f"pkg.{name}")
            """,
        # PEP 562 lazy exports: every value of a literal table can be imported
        "exports/__init__.py": """
            import importlib

            _EXPORTS = {"solve": ".policy", "Method": ".base"}


            def __getattr__(name):
                return getattr(importlib.import_module(_EXPORTS[name], __name__), name)
            """,
        "exports/policy.py": "",
        "exports/base.py": "",
    })
    assert closure(root, "pkg.user") == {"__init__.py", "user.py", "lazy.py", "x.py", "y.py",
                                        "z.py", "w.py", "v.py"}
    assert closure(root, "pkg.exports") == {"__init__.py", "exports/__init__.py",
                                           "exports/policy.py", "exports/base.py"}


#: (source, whether the scanner reads it; else the file is parsed whole)
TRICKY = [
    ("import a; import b\n", True),
    ("x = 1; import pkg.x\n", False),
    ("try: import pkg.x\nexcept ImportError: pass\n", False),
    ("from pkg import (  # a comment (with parentheses\n    x,  # and more)\n    y,\n)\n", True),
    ("from pkg \\\n    import x\n", False),
    ("import pkg.x as \\\n    y\n", True),
    ('s = """\nimport pkg.x\n"""\nt = \'\'\'\nfrom pkg import y\n\'\'\'\n', True),
    ("s = 'import pkg.x'  # import pkg.y\nu = \"\"\nimport pkg.z\n", True),
    ('def f():\n    """Doc.\n\n    import pkg.x\n    """\n    from . import y\n', True),
    ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.x\n", True),
    ("import typing\nif typing.TYPE_CHECKING:\n    import pkg.x\nelse:\n    import pkg.y\nz = 1\n",
     True),
    ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n" + "    import pkg.x\n" * 40
     + "else:\n    import pkg.y\n", True),
    ("from typing import TYPE_CHECKING\ndef f():\n    if TYPE_CHECKING:\n        import pkg.x\n",
     False),
    ("from typing import TYPE_CHECKING\nif not TYPE_CHECKING:\n    import pkg.x\n", False),
    ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.x\n\n\n"
     + "def f():\n    pass\n" * 40, True),
    ("m = lazy_module('pkg.x')\nn = import_module('.y', __package__)\n", True),
    ("m = lazy_module(r'pkg.x')\n", False),
    ("m = lazy_module('pkg' '.z')\n", False),
    ("m = import_module(NAME)\nn = import_module(f'pkg.{NAME}')\n", True),
    ("m = import_module(TABLE[k])\n", False),
    ("m = import_module(name='pkg.x')\n", False),
    ("def lazy_module(name):\n    return importlib.import_module(name, __name__)\n", True),
    ("reimport = 1\nimporter = 2\nfrom_ = 3\n", True),
    ("import pkg.a\r\nfrom pkg import (\r\n    b,\r\n)\r\n", True),
]


@pytest.mark.parametrize(("source", "sure"), TRICKY)
def test_scanner_reads_like_the_parser(source, sure):
    """The regex scanner gives the parser's answer, or gives up (None)."""
    scanned = codestamp._scanned_imports(source.replace("\r\n", "\n"), "pkg.mod", False)
    parsed = codestamp._ast_imports(ast.parse(source), "pkg.mod", False)
    assert scanned == (parsed if sure else None)


def test_files_the_scanner_gives_up_on_are_parsed(tmp_path):
    root = write_package(tmp_path, {
        "__init__.py": "",
        "x.py": "",
        "y.py": "",
        "z.py": "",
        "main.py": """
            try: import pkg.x
            except ImportError: pass
            from pkg \\
                import y
            Z = lazy_module(r"pkg.z")
            """,
    })
    assert closure(root, "pkg.main") == {"__init__.py", "main.py", "x.py", "y.py", "z.py"}


def real_modules() -> list[tuple[str, Path, bool]]:
    modules = []
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = ["reportgen", *path.relative_to(PACKAGE).with_suffix("").parts]
        is_package = parts[-1] == "__init__"
        modules.append((".".join(parts[:-1] if is_package else parts), path, is_package))
    return modules


def test_scanner_reads_every_module_of_the_package_like_the_parser():
    unsure = []
    for module, path, is_package in real_modules():
        text = path.read_text()
        scanned = codestamp._scanned_imports(text, module, is_package)
        if scanned is None:
            unsure.append(module)
        else:
            assert scanned == codestamp._ast_imports(ast.parse(text), module, is_package), module
    assert len(unsure) <= len(real_modules()) // 10, unsure   # the fast path is the rule


def test_the_real_package():
    cli = module_files(["reportgen.commands.cli"])
    assert PACKAGE / "commands" / "cli.py" in cli and PACKAGE / "__init__.py" in cli
    core = PACKAGE / "core"
    integrators = module_files(["reportgen.core.integrators"])
    print("\n".join(str(path.relative_to(PACKAGE)) for path in integrators))
    assert core / "integrators" / "__init__.py" in integrators
    assert core / "integrators" / "policy.py" in integrators   # PEP 562 exports
    outside = [path for path in integrators if not path.is_relative_to(core)]
    assert outside == [PACKAGE / "__init__.py"]
    # core never reaches out of core (but for the package's __init__)
    for module, _, _ in real_modules():
        if module.startswith("reportgen.core"):
            files = module_files([module])
            assert all(path.is_relative_to(core) or path == PACKAGE / "__init__.py"
                       for path in files), module
