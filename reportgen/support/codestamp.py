"""Hashes of reportgen's own code, part of the stage keys.

The package is installed editable (``make run``), so after a ``git pull`` the same
version number may run different code.  A stage's cached output must then not be
reused: the simulate key holds the hash of the code a kind's simulation imports, the
figures key and the report stamp that of the code its report imports
(:meth:`reportgen.scene.base.Scene.simulation_code`, ``report_code``), each found by
:func:`module_files` from the import graph: no hand-kept list of files.  Standard library
only.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import os
import re
from collections.abc import Iterable
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent

def _hash(files: Iterable[Path], root: Path) -> str:
    """Hash of the files' names (relative to their ``root`` folder: the same in every
    checkout) and contents."""
    h = hashlib.sha256()
    for path in sorted(set(files)):
        h.update(path.relative_to(root).as_posix().encode() + b"\0")
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


# --- stage keys from the import graph -----------------------------------------------------
#
# A stage's key holds the code it can run: the modules its entry module imports, found by
# reading the sources (nothing is imported).  Each file's import list is parsed once per
# process and version of the file (:func:`_file_imports`).  ``ast.parse`` of the whole
# package takes ~200 ms, so a file is first read by a regex scanner (strings and comments
# skipped, the import statements then parsed alone); a file the scanner cannot read
# with certainty (an ``import`` that does not start its line, a non-literal
# ``lazy_module``/``import_module`` argument, ``TYPE_CHECKING`` used otherwise than in a
# module-level ``if``) is parsed whole.  Both readings give the same answer
# (tests/test_codestamp.py checks it on every file of the package).

#: calls whose string-literal first argument names a module imported (now or on first use)
_DYNAMIC = frozenset({"lazy_module", "import_module"})

_SCAN = re.compile(r'''
    (?=[#"'ilT])(?:
      (?P<long>"""[^"\\]*(?:(?:\\.|"(?!""))[^"\\]*)*"""
              |\'\'\'[^'\\]*(?:(?:\\.|'(?!''))[^'\\]*)*\'\'\')
      |(?P<skip>\#[^\n]*
              |"[^"\\\n]*(?:\\.[^"\\\n]*)*"
              |'[^'\\\n]*(?:\\.[^'\\\n]*)*')
      |(?P<imp>import\b)
      |(?P<call>(?:lazy_module|import_module)\s*\()
      |(?P<tc>TYPE_CHECKING\b))''', re.S | re.X)
#: a call with literal arguments: ``lazy_module("a.b")``, ``import_module(".b", "a")``,
#: ``import_module(".b", __name__)``
_LITERAL_CALL = re.compile(r'''(?:lazy_module|import_module)\s*\(\s*(["'])([\w.]*)\1\s*
    (?:,\s*(?:(["'])([\w.]*)\3|(__name__|__package__))\s*)?,?\s*\)''', re.X)
#: a first argument :func:`_ast_imports` ignores: an f-string, or a name (or an expression
#: starting with one: attribute, call, operation) but a subscript ``table[...]`` or a
#: keyword ``name=...``
_IGNORED_ARGUMENT = re.compile(r"""\s*(?:(?:[fF][rR]?|[rR][fF])["']
                                   |[A-Za-z_]\w*(?![\w"'])(?!\s*\[)(?!\s*=[^=]))""", re.X)
_STATEMENT = re.compile(r"(?:import|from)\b")
_TYPE_CHECKING_IF = re.compile(r"if[ \t]+(?:typing\.)?TYPE_CHECKING[ \t]*:")

#: one import of a file: ("mod", "a.b.c", "") imports module a.b.c; ("from", "a.b", "c")
#: is ``from a.b import c`` (c a module or an attribute of a.b)
_Import = tuple[str, str, str]


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING"
            or isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _anchor(level: int, base: str) -> str | None:
    """The package ``level`` dots name relative to ``base`` (``importlib``'s rule)."""
    bits = base.rsplit(".", level - 1) if base else []
    return bits[0] if len(bits) == level else None


def _ast_imports(tree: ast.AST, module: str, is_package: bool) -> set[_Import]:
    """The imports of ``tree`` (module ``module``), but those under ``if TYPE_CHECKING:``.

    ``from a import b``: ("from", "a", "b"); ``import a.b`` and a call
    ``lazy_module("a.b")`` / ``import_module("a.b")``: ("mod", "a.b", "").  A call's
    argument counts when it is a string literal (relative ones resolved as importlib does,
    against a literal ``package`` argument, ``__name__`` or ``__package__``) or an item of
    a module-level dict of string literals (``import_module(_EXPORTS[name], __name__)``:
    PEP 562 lazy exports, every value counts).  Any other argument is ignored: kinds are
    discovered by ``import_module(f"{__name__}.{info.name}")``, and a shared module must
    not pull in every kind.
    """
    package = module if is_package else module.rpartition(".")[0]
    tables: dict[str, list[str]] = {}
    for node in tree.body if isinstance(tree, ast.Module) else ():
        if (isinstance(node, ast.Assign | ast.AnnAssign) and isinstance(node.value, ast.Dict)
                and all(isinstance(v, ast.Constant) and isinstance(v.value, str)
                        for v in node.value.values)):
            for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
                if isinstance(target, ast.Name):
                    tables[target.id] = [v.value for v in node.value.values]
    found: set[_Import] = set()
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.extend(node.orelse)
            continue
        if isinstance(node, ast.Import):
            found.update(("mod", alias.name, "") for alias in node.names)
            continue
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = _anchor(node.level, package)
                base = anchor and (f"{anchor}.{base}" if base else anchor)
            if base:
                found.update(("from", base, alias.name) for alias in node.names)
            continue
        if isinstance(node, ast.Call):
            func = node.func
            name = (func.id if isinstance(func, ast.Name)
                    else func.attr if isinstance(func, ast.Attribute) else None)
            if name in _DYNAMIC:
                found.update(("mod", target, "") for target in _call_targets(
                    node, name, tables, module, package))
        stack.extend(ast.iter_child_nodes(node))
    return found


def _call_targets(call: ast.Call, func: str, tables: dict[str, list[str]], module: str,
                  package: str) -> list[str]:
    args = {k.arg: k.value for k in call.keywords if k.arg}
    first = call.args[0] if call.args else args.get("name")
    second = call.args[1] if len(call.args) > 1 else args.get("package")
    if isinstance(first, ast.Constant) and isinstance(first.value, str):
        names = [first.value]
    elif (isinstance(first, ast.Subscript) and isinstance(first.value, ast.Name)
          and first.value.id in tables):
        names = tables[first.value.id]
    else:
        return []
    anchor = None
    if func == "import_module":
        if isinstance(second, ast.Constant) and isinstance(second.value, str):
            anchor = second.value
        elif isinstance(second, ast.Name) and second.id in ("__name__", "__package__"):
            anchor = module if second.id == "__name__" else package
    return [resolved for name in names if (resolved := _absolute(name, anchor))]


def _absolute(name: str, anchor: str | None) -> str | None:
    level = len(name) - len(name.lstrip("."))
    if not level:
        return name or None
    base = _anchor(level, anchor) if anchor else None
    rest = name[level:]
    return base and (f"{base}.{rest}" if rest else base)


def _scanned_imports(text: str, module: str, is_package: bool) -> set[_Import] | None:
    """:func:`_ast_imports` of ``text`` without parsing it all, or None if unsure."""
    statements: dict[int, int] = {}          # import statement: start -> end
    calls: list[re.Match[str]] = []
    checks: list[int] = []                   # TYPE_CHECKING tokens
    long_strings: list[tuple[int, int]] = []
    for match in _SCAN.finditer(text):
        kind = match.lastgroup
        if kind == "long":
            long_strings.append(match.span())
            continue
        if kind == "skip":
            continue
        at = match.start()
        if at and (text[at - 1].isalnum() or text[at - 1] == "_"):
            continue                         # inside a longer name
        line = text.rfind("\n", 0, at) + 1
        if kind == "imp":
            if line >= 2 and text[line - 2] == "\\":
                return None                  # a continuation line
            start = line + len(text[line:at]) - len(text[line:at].lstrip(" \t"))
            if start in statements:
                continue
            if not _STATEMENT.match(text, start) or _inside(start, long_strings):
                return None                  # ``x = 1; import y``, ``try: import y``...
            end = _statement_end(text, start)
            if end is None:
                return None
            statements[start] = end
        elif kind == "call":
            if text[line:at].rstrip().endswith("def"):
                continue
            calls.append(match)
        else:
            checks.append(at)
    # module-level ``if TYPE_CHECKING:`` blocks: parsed alone (their ``else`` counts)
    found: set[_Import] = set()
    blocks: list[tuple[int, int]] = []
    for at in checks:
        if any(start <= at < end for start, end in statements.items()) or _inside(at, blocks):
            continue
        line = text.rfind("\n", 0, at) + 1
        if not _TYPE_CHECKING_IF.match(text, line) or at > line + 10:
            return None
        block = _block(text, line)
        if block is None:
            return None
        node, end = block
        blocks.append((line, end))
        found |= _ast_imports(node, module, is_package)
    source = "\n".join(text[start:end] for start, end in statements.items()
                       if not _inside(start, blocks))
    try:
        found |= _ast_imports(ast.parse(source), module, is_package)
    except SyntaxError:
        return None
    for match in calls:
        if _inside(match.start(), blocks):
            continue
        literal = _LITERAL_CALL.match(text, match.start())
        if literal is None:
            if _IGNORED_ARGUMENT.match(text, match.end()):
                continue
            return None                      # let the parser decide
        _, name, _, package_literal, dunder = literal.groups()
        anchor = None
        if match.group().startswith("import_module"):
            anchor = (package_literal if package_literal is not None
                      else module if dunder == "__name__"
                      else (module if is_package else module.rpartition(".")[0])
                      if dunder == "__package__" else None)
        target = _absolute(name, anchor)
        if target:
            found.add(("mod", target, ""))
    return found


def _inside(at: int, spans: Iterable[tuple[int, int]]) -> bool:
    return any(start <= at < end for start, end in spans)


def _statement_end(text: str, start: int) -> int | None:
    """End of the import statement at ``start``: its line, and the next ones while a
    parenthesis is open or a line ends in a backslash (an import holds no strings, so a
    ``#`` starts a comment)."""
    depth, at = 0, start
    while at <= len(text):
        end = text.find("\n", at)
        end = len(text) if end < 0 else end
        code = text[at:end].partition("#")[0]
        depth += code.count("(") - code.count(")")
        if depth <= 0 and not code.rstrip().endswith("\\"):
            return end
        at = end + 1
    return None


def _block(text: str, line: int) -> tuple[ast.If, int] | None:
    """The module-level ``if`` statement starting at offset ``line``, and its end: parsed
    from there on, more lines at a time, until a statement follows it."""
    lines = 16
    while True:
        end = line
        for _ in range(lines):
            end = text.find("\n", end) + 1 or len(text)
            if end == len(text):
                break
        try:
            body = ast.parse(text[line:end]).body
        except SyntaxError:
            body = []
        if len(body) >= 2 or (end == len(text) and body):
            node = body[0]
            if not isinstance(node, ast.If):
                return None
            last = line
            for _ in range(node.end_lineno or 1):
                last = text.find("\n", last) + 1 or len(text)
            return node, last
        if end == len(text):
            return None
        lines *= 4


@functools.cache
def _file_imports(path: Path, mtime_ns: int, size: int, module: str, is_package: bool
                  ) -> frozenset[_Import]:
    """The imports of the file (module ``module``), once per version of the file."""
    data = path.read_bytes()
    try:
        text = data.decode()
        found = _scanned_imports(text.replace("\r\n", "\n") if "\r" in text else text,
                                 module, is_package)
    except UnicodeDecodeError:
        found = None
    if found is None:
        try:
            found = _ast_imports(ast.parse(data, str(path)), module, is_package)
        except (SyntaxError, ValueError):
            found = set()                    # hashed all the same: an edit changes the key
    return frozenset(found)


class _Package:
    """Where the modules of ``package`` (a folder ``root``) are: each folder listed once
    per walk."""

    def __init__(self, root: Path, package: str):
        self.root, self.package = root, package
        self._found: dict[str, tuple[Path, bool] | None] = {}
        self._listed: dict[tuple[str, ...], frozenset[str]] = {}

    def _names(self, parts: tuple[str, ...]) -> frozenset[str]:
        names = self._listed.get(parts)
        if names is None:
            try:
                names = frozenset(os.listdir(os.path.join(self.root, *parts)))
            except OSError:
                names = frozenset()
            self._listed[parts] = names
        return names

    def find(self, name: str) -> tuple[Path, bool] | None:
        """(file, is a package) of module ``name``, None if not in the package or missing."""
        if name in self._found:
            return self._found[name]
        found = None
        if name == self.package:
            if "__init__.py" in self._names(()):
                found = (self.root / "__init__.py", True)
        elif name.startswith(self.package + "."):
            parts = tuple(name[len(self.package) + 1:].split("."))
            if all(part.isidentifier() for part in parts):
                if "__init__.py" in self._names(parts):
                    found = (self.root.joinpath(*parts, "__init__.py"), True)
                elif parts[-1] + ".py" in self._names(parts[:-1]):
                    found = (self.root.joinpath(*parts[:-1], parts[-1] + ".py"), False)
        self._found[name] = found
        return found


def module_files(roots: Iterable[str], package_dir: Path = PACKAGE, package: str = "reportgen"
                 ) -> list[Path]:
    """Source files of the modules ``roots`` (dotted names inside ``package``, whose folder
    is ``package_dir``) and of every module of ``package`` they import, transitively.

    Static analysis, nothing is imported: ``import a.b``, ``from a import b`` (``a.b``
    if it is a module, else ``a``), relative imports, imports inside functions, and
    string-literal arguments of ``lazy_module(...)`` / ``importlib.import_module(...)``
    (see :func:`_ast_imports`).  Imports under ``if TYPE_CHECKING:`` never run and do not
    count; modules outside ``package`` and imported modules that do not exist are ignored
    (a root that does not exist raises ModuleNotFoundError: a misspelt root would otherwise
    give a key that never changes).  ``roots`` may also be one name.

    Importing ``a.b.c`` runs the ``__init__.py`` of ``a`` and ``a.b`` first: their files
    are part of the result, but their own imports are not followed.  A kind's package
    ``__init__`` composes its simulation and its report; following it from the simulation
    (``from . import config``) would make every caption part of the physics key.  Code
    an ``__init__`` runs on import is therefore only counted when that ``__init__`` is
    imported itself (``import a.b``, ``from a import b`` with ``b`` a package, or
    ``from a.b import name`` with ``name`` not a module): then it is followed.
    """
    root = Path(package_dir)
    modules = _Package(root, package)
    files: set[Path] = set()
    followed: set[str] = set()
    todo: list[tuple[str, Path, bool]] = []

    def use(name: str) -> None:
        found = modules.find(name)
        if found is None:
            return
        files.add(found[0])
        parent = name
        while "." in parent:                 # packages run on the way, not followed
            parent = parent.rpartition(".")[0]
            init = modules.find(parent)
            if init is not None and init[1]:
                files.add(init[0])
        if name not in followed:
            followed.add(name)
            todo.append((name, *found))

    for name in [roots] if isinstance(roots, str) else roots:
        if modules.find(name) is None:
            raise ModuleNotFoundError(f"no module {name} in {package} ({root})", name=name)
        use(name)
    while todo:
        name, path, is_package = todo.pop()
        stat = os.stat(path)
        for kind, base, attr in _file_imports(path, stat.st_mtime_ns, stat.st_size, name,
                                               is_package):
            if kind == "from" and attr != "*" and modules.find(f"{base}.{attr}") is not None:
                use(f"{base}.{attr}")
            else:
                use(base)
    return sorted(files)


def code_hash(roots: Iterable[str], package_dir: Path = PACKAGE, package: str = "reportgen"
              ) -> str:
    """16 hex digits of sha256 over the :func:`module_files` of ``roots``: their paths
    relative to ``package_dir`` (the same in every checkout) and their bytes."""
    return _hash(module_files(roots, package_dir, package), Path(package_dir))


def files_hash(files: Iterable[Path], root: Path) -> str:
    """16 hex digits of sha256 over ``files`` (e.g. templates): their paths relative to
    ``root`` and their bytes."""
    return _hash(files, root)
