"""One direction of imports: no cycle among reportgen's modules.

Every import of a reportgen module anywhere in a module (top level or inside a
function) and every ``lazy_module("reportgen....")`` is an edge; the graph must be
acyclic, and ``reportgen.core`` must import nothing above it.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "reportgen"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _modules() -> dict[str, Path]:
    return {_module_name(p): p for p in PACKAGE.rglob("*.py")}


def _resolve(name: str, modules: dict[str, Path]) -> str | None:
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


def _edges(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    targets: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets.update(a.name for a in node.names if a.name.startswith("reportgen"))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package
                for _ in range(node.level - 1):
                    base = base.rpartition(".")[0]
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module or ""
            if not base.startswith("reportgen"):
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                targets.add(sub if sub in modules else base)
        elif (isinstance(node, ast.Call) and getattr(node.func, "id", None) == "lazy_module"
              and node.args and isinstance(node.args[0], ast.Constant)):
            targets.add(node.args[0].value)
    resolved = {_resolve(t, modules) for t in targets}
    return {t for t in resolved if t and t != name}


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    return {name: _edges(name, path, modules) for name, path in modules.items()}


def test_no_import_cycle():
    graph = _graph()
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                cycle = visit(nxt)
                if cycle:
                    return cycle
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            cycle = visit(node)
            assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_core_imports_nothing_above_it():
    graph = _graph()
    for name, targets in graph.items():
        if name.startswith("reportgen.core"):
            above = {t for t in targets if not t.startswith("reportgen.core")
                     and t not in ("reportgen",)}
            assert not above, f"{name} imports {sorted(above)} from above core"


def test_the_graph_sees_imports():
    """The checker itself: known edges are found (so a broken parser cannot pass)."""
    graph = _graph()
    assert "reportgen.archive.store" in graph["reportgen.rendering.report"]
    assert "reportgen.scene.base" in graph["reportgen.kinds"]
    assert "reportgen.core.integrators" in graph["reportgen.scene.integration"]


@pytest.mark.parametrize(("args", "absent"), [
    (["--help"], ("numba", "scipy", "matplotlib", "weasyprint", "h5py", "reportgen.core")),
    (["kinds"], ("numba", "scipy", "matplotlib", "weasyprint", "h5py")),
    (["validate", str(PACKAGE.parent / "configs")],
     ("numba", "scipy.linalg", "scipy.integrate", "scipy.special", "scipy.optimize",
      "matplotlib", "weasyprint", "distributed")),
])
def test_light_commands_import_only_what_they_use(args, absent):
    """--help, kinds and validate stay fast: the heavy libraries load only where used
    (validate may import the bare ``scipy`` package, whose submodules load on use)."""
    code = ("import sys\nfrom reportgen.commands.cli import main\ntry:\n    main(sys.argv[1:])\n"
            "except SystemExit:\n    pass\n"
            "print('MODULES: ' + ' '.join(sorted(m for m in sys.modules if '.' not in m or "
            "m.startswith(('reportgen.core', 'scipy.')))))")
    proc = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    last = proc.stdout.strip().splitlines()[-1]
    assert last.startswith("MODULES: ")
    loaded = set(last.split()[1:])
    assert "reportgen" in loaded  # the listing is read
    assert not loaded & set(absent), sorted(loaded & set(absent))
