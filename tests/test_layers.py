"""The package's import layers (docs/architecture.md, "Layers"): no module imports a higher layer.

Every ``import windflutter...`` and ``from windflutter... import`` in ``src/windflutter`` is read
with :mod:`ast` -- module-level, inside functions, under ``if TYPE_CHECKING:`` and relative ones
alike -- and checked against :data:`LAYERS`. The check is static (nothing is imported), takes a
few tenths of a second and is an independent reading of the source: it shares no code with the
package.

An upward import that is known and not fixed yet is listed in :data:`ALLOWED` with the reason;
each entry is a debt to remove deliberately -- the test fails when an entry is no longer needed,
so the list can only shrink.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "windflutter"

#: Top-level modules and sub-packages of windflutter, lowest layer first. A module may import
#: its own layer and the layers below. ``windflutter`` is the package ``__init__`` (``__version__``
#: and the BLAS policy).
LAYERS: tuple[tuple[str, ...], ...] = (
    ("errors",),
    ("units", "linalg_tools", "files", "schema", "threads", "fastlib", "heap", "aero_types", "version"),
    ("results", "backends", "exporters", "parallel"),
    ("config",),
    ("structure",),
    ("rotor",),
    ("model",),
    ("mesh",),
    ("aero",),
    ("solve",),
    ("steady",),
    ("system",),
    ("section", "overspeed", "frozen"),
    ("methods",),
    ("simulate", "sensitivity"),
    ("post",),
    ("analysers", "operating"),
    ("workflow",),
    ("api",),
    ("cli", "__main__", "windflutter"),
)

#: Known upward imports: (importing module, imported module) -> why it is still there. Remove an
#: entry together with the import it excuses.
ALLOWED: dict[tuple[str, str], str] = {
}


def _unit(module: str) -> str:
    """Layer unit of a dotted module name: ``windflutter.mesh.turbine`` -> ``mesh``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def _module_name(path: Path, src: Path = SRC) -> str:
    rel = path.relative_to(src.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


@functools.lru_cache(maxsize=None)
def _parse(text: str) -> ast.Module:
    """The syntax tree of a source text, parsed once (four checks read every module; the trees are
    only read, never changed)."""
    return ast.parse(text)


def _statements(body):
    """Every statement in ``body`` and in the statement blocks nested in it (function and class
    bodies, if/else, try/except/finally, with, loops, match cases): where imports can stand.
    Expressions are not visited (they are most of the tree and hold no imports)."""
    for node in body:
        yield node
        for name in ("body", "orelse", "finalbody", "handlers", "cases"):
            block = getattr(node, name, None)
            if isinstance(block, list):
                yield from _statements(block)


def _imports(path: Path, src: Path = SRC) -> list[tuple[str, int]]:
    """Every windflutter module imported by the file at ``path`` of the package at ``src``:
    ``[(module, line)]``.

    ``from windflutter.x import y`` counts as an import of ``windflutter.x.y`` when ``y`` is a
    sub-module file, else of ``windflutter.x``.
    """
    name = _module_name(path, src)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: list[tuple[str, int]] = []
    for node in _statements(_parse(path.read_text(encoding="utf-8")).body):
        if isinstance(node, ast.Import):
            found += [(a.name, node.lineno) for a in node.names if a.name.split(".")[0] == "windflutter"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "windflutter":
                continue
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                where = src.parent.joinpath(*sub.split("."))
                is_module = where.with_suffix(".py").exists() or (where / "__init__.py").exists()
                found.append((sub if is_module else target, node.lineno))
    return found


def _layer_of() -> dict[str, int]:
    return {unit: i for i, units in enumerate(LAYERS) for unit in units}


@functools.lru_cache(maxsize=1)
def _graph() -> dict[str, list[tuple[str, int]]]:
    return {_module_name(p): _imports(p) for p in sorted(SRC.rglob("*.py"))}


def upward_imports() -> dict[tuple[str, str], list[int]]:
    """Every import of a higher layer: ``{(importer, imported): [lines]}``."""
    layer = _layer_of()
    out: dict[tuple[str, str], list[int]] = {}
    for importer, targets in _graph().items():
        for target, line in targets:
            if layer[_unit(target)] > layer[_unit(importer)]:
                out.setdefault((importer, target), []).append(line)
    return {k: sorted(set(v)) for k, v in out.items()}


def test_every_module_has_a_layer():
    """A new top-level module or sub-package must be placed in LAYERS deliberately."""
    layer = _layer_of()
    units = {_unit(m) for m in _graph()} | {_unit(t) for ts in _graph().values() for t, _ in ts}
    missing = sorted(u for u in units if u not in layer)
    assert not missing, f"place these in tests/test_layers.py LAYERS (and docs/architecture.md): {missing}"
    stale = sorted(u for u in layer if u not in units)
    assert not stale, f"LAYERS names modules that do not exist: {stale}"


def test_no_upward_imports():
    found = upward_imports()
    new = {k: v for k, v in found.items() if k not in ALLOWED}
    lines = [f"{a} (line {', '.join(map(str, v))}) imports {b}" for (a, b), v in sorted(new.items())]
    assert not new, "upward imports (see docs/architecture.md, Layers):\n  " + "\n  ".join(lines)


def test_allow_list_only_shrinks():
    """An ALLOWED entry whose import is gone must be deleted (the list is a debt, not a licence)."""
    found = upward_imports()
    stale = sorted(k for k in ALLOWED if k not in found)
    assert not stale, f"remove these fixed entries from ALLOWED: {stale}"


def test_the_checker_sees_every_kind_of_import(tmp_path):
    """The parser finds module-level, function-level, TYPE_CHECKING and relative imports (a
    check that cannot see an import cannot fail on it)."""
    pkg = tmp_path / "windflutter"
    (pkg / "mesh").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "workflow.py").write_text("")
    (pkg / "mesh" / "__init__.py").write_text("")
    (pkg / "system").mkdir()
    (pkg / "system" / "__init__.py").write_text("")  # a sub-package named in a from-import
    (pkg / "mesh" / "a.py").write_text(
        "from typing import TYPE_CHECKING\n"
        "import windflutter.errors\n"
        "if TYPE_CHECKING:\n    from windflutter.post import store\n"
        "def f():\n    from .. import workflow\n    from ..stability.turbine import X\n"
        "    import numpy\n"
        "class C:\n    try:\n        import windflutter.cli\n    except ImportError:\n"
        "        from windflutter import system\n")
    got = sorted(_imports(pkg / "mesh" / "a.py", pkg))
    assert got == [("windflutter.cli", 11), ("windflutter.errors", 2), ("windflutter.post", 4),
                   ("windflutter.stability.turbine", 7), ("windflutter.system", 13), ("windflutter.workflow", 6)]


@pytest.mark.parametrize("importer, target, upward", [
    ("windflutter.post.store", "windflutter.workflow", True),
    ("windflutter.mesh.turbine", "windflutter.structure.fem", False),
    ("windflutter.mesh.turbine", "windflutter.mesh.parts", False),
    ("windflutter.results", "windflutter.units", False),
    ("windflutter.units", "windflutter.results", True),
])
def test_layer_order_examples(importer, target, upward):
    layer = _layer_of()
    assert (layer[_unit(target)] > layer[_unit(importer)]) is upward


def module_cycles(graph: dict[str, list[tuple[str, int]]]) -> list[list[str]]:
    """The strongly connected components of more than one module of the import graph (Tarjan):
    groups of modules that import each other, directly or round a circle, at module level or inside
    functions alike.  A package ``__init__`` that re-exports its sub-modules is left out of the graph
    (its sub-modules' imports of the package are how Python resolves them, not a design circle)."""
    nodes = [m for m in graph]
    inits = {m for m in graph if (SRC.parent / Path(*m.split("."))).is_dir()}
    edges = {m: sorted({t for t, _ in graph[m] if t in graph and t not in inits and t != m}) for m in nodes
             if m not in inits}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, []):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in edges:
        if v not in index:
            visit(v)
    return out


def test_no_import_circles():
    """No two modules of the package import each other, round any circle (issue 29: a circle inside
    a layer, e.g. rotor/rotating.py <-> rotor/spin.py, was hidden by imports inside functions)."""
    assert module_cycles(_graph()) == []


def test_the_circle_check_can_fail():
    graph = {"windflutter.rotor.a": [("windflutter.rotor.b", 3)], "windflutter.rotor.b": [("windflutter.rotor.a", 9)],
             "windflutter.rotor.c": [("windflutter.rotor.a", 1)]}
    assert module_cycles(graph) == [["windflutter.rotor.a", "windflutter.rotor.b"]]


def private_imports(src: Path = SRC) -> list[str]:
    """``from windflutter.x import _name`` in another module than ``windflutter.x`` (a private name
    borrowed across modules: make it public in its module instead)."""
    out = []
    for path in sorted(src.rglob("*.py")):
        for node in _statements(_parse(path.read_text(encoding="utf-8")).body):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("windflutter") or \
                    isinstance(node, ast.ImportFrom) and node.level:
                for alias in node.names:
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        out.append(f"{_module_name(path, src)} (line {node.lineno}) imports {alias.name}")
    return out


def test_no_private_names_across_modules():
    assert private_imports() == []


def test_the_private_name_check_can_fail(tmp_path):
    pkg = tmp_path / "windflutter"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("def f():\n    from windflutter.b import _g\n")
    assert private_imports(pkg) == ["windflutter.a (line 2) imports _g"]


# ------------------------------------------------------------------ function-local imports
#: modules whose import loads a heavy library (matplotlib): imported inside the function that draws,
#: from anywhere
HEAVY_MODULES = frozenset({
    "windflutter.post.plots", "windflutter.post.report", "windflutter.post.campbell_plots",
    "windflutter.post.vg_plots", "windflutter.post.simulate_plot",
})
_CLI_START_UP = "CLI start-up: a sub-command imports what it runs after its arguments are parsed"
_LATE_BINDING = ("entries into real work, looked up when called (tests/cli's HeavyWork guard patches them "
                 "in their module, which only a late import sees)")
#: function-local imports of the package's own modules that stay: importing file (relative to
#: src/windflutter; a folder ends in '/') -> (the modules it may import locally, why).  Every other
#: import of our own modules is at module level (issue 29); cli/ is exempt as a whole.
LOCAL_IMPORTS: dict[str, tuple[frozenset[str], str]] = {
    "cli/": (frozenset({"*"}), _CLI_START_UP),
    "__init__.py": (frozenset({"windflutter.api"}), "the package facade: `import windflutter` stays light, the "
                    "API is loaded on first use"),
    "api.py": (frozenset({"windflutter.model", "windflutter.mesh.analysis", "windflutter.workflow"}), _LATE_BINDING),
    "system/operational.py": (frozenset({"windflutter.mesh.turbine"}), f"build_model: {_LATE_BINDING}"),
    "analysers.py": (frozenset({"windflutter.frozen.turbine"}), "the seed's methods (frozen.turbine), a fenced "
                     "plug-in loaded only when a pk or thesis case runs"),
    "methods.py": (frozenset({"windflutter.frozen.turbine"}), "the seed's methods, a fenced plug-in "
                   "loaded only when a pk or thesis case is built"),
    "mesh/shell_beam.py": (frozenset({"windflutter.mesh.turbine"}), f"build_model: {_LATE_BINDING}"),
    "simulate/blade.py": (frozenset({"windflutter.mesh.turbine"}), f"build_model: {_LATE_BINDING}"),
    "simulate/turbine_run.py": (frozenset({"windflutter.mesh.turbine"}), f"build_model: {_LATE_BINDING}"),
}


def local_imports(src: Path = SRC) -> dict[str, set[str]]:
    """Per file (relative to ``src``) the package modules it imports inside a function."""
    return {k: set(v) for k, v in _local_imports(src).items()}


@functools.lru_cache(maxsize=8)
def _local_imports(src: Path) -> dict[str, set[str]]:
    out: dict[str, set[str]] = {}
    for path in sorted(src.rglob("*.py")):
        rel = path.relative_to(src).as_posix()
        name = _module_name(path, src)
        for fn in ast.walk(_parse(path.read_text(encoding="utf-8"))):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if isinstance(node, ast.ImportFrom):
                    base = _resolve(name, path, node.module, node.level) if node.level else (node.module or "")
                    mods = [_submodule(src, base, a.name) for a in node.names]
                elif isinstance(node, ast.Import):
                    mods = [a.name for a in node.names]
                else:
                    continue
                out.setdefault(rel, set()).update(m for m in mods if m == "windflutter" or m.startswith("windflutter."))
    return {k: v for k, v in out.items() if v}


def _submodule(src: Path, base: str, name: str) -> str:
    """``base.name`` when that is a module or package of ``src``'s package, else ``base``."""
    rel = Path(*f"{base}.{name}".split(".")[1:])
    return f"{base}.{name}" if (src / rel).with_suffix(".py").is_file() or (src / rel).is_dir() else base


def _resolve(name: str, path: Path, module: str | None, level: int) -> str:
    parts = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    parts = parts[: len(parts) - (level - 1)]
    return ".".join(parts + ([module] if module else []))


def _allowed(rel: str) -> tuple[frozenset[str], str] | None:
    if rel in LOCAL_IMPORTS:
        return LOCAL_IMPORTS[rel]
    return next((v for k, v in LOCAL_IMPORTS.items() if k.endswith("/") and rel.startswith(k)), None)


def unlisted_local_imports(src: Path = SRC) -> dict[str, list[str]]:
    bad = {}
    for rel, mods in local_imports(src).items():
        allowed = _allowed(rel)
        names = allowed[0] if allowed else frozenset()
        extra = sorted(m for m in mods - HEAVY_MODULES if "*" not in names and m not in names)
        if extra:
            bad[rel] = extra
    return bad


def test_local_imports_of_our_modules_only_where_listed():
    """Our own modules are imported at module level, except a drawing module (matplotlib), the CLI's
    start-up and the listed cases (issue 29)."""
    bad = unlisted_local_imports()
    assert not bad, f"import these at module level (or list them with a reason in LOCAL_IMPORTS): {bad}"


def test_local_import_list_only_shrinks():
    """A listed module no longer imported locally must leave LOCAL_IMPORTS (the list is a debt)."""
    found = local_imports()
    stale = []
    for key, (names, _) in LOCAL_IMPORTS.items():
        files = [r for r in found if (r.startswith(key) if key.endswith("/") else r == key)]
        if not files:
            stale.append(key)
        elif "*" not in names:
            used = set().union(*(found[r] for r in files))
            stale += [f"{key}: {m}" for m in sorted(names - used)]
    assert not stale, f"remove these entries from LOCAL_IMPORTS: {stale}"


def test_the_local_import_check_can_fail(tmp_path):
    pkg = tmp_path / "windflutter"
    (pkg / "post").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    for f in ("post/__init__.py", "post/plots.py", "post/store.py", "units.py"):
        (pkg / f).write_text("")
    (pkg / "post" / "x.py").write_text("import numpy\nfrom windflutter import errors\n"
                                       "def f():\n    from .store import a\n    from windflutter.post import plots\n"
                                       "    import scipy\n    from windflutter import units\n")
    assert unlisted_local_imports(pkg) == {"post/x.py": ["windflutter.post.store", "windflutter.units"]}


# ------------------------------------------------------------------ the seed's methods, fenced
#: the only modules that may import the seed's frozen-azimuth methods (windflutter.frozen): the
#: methods registry that builds a pk / thesis case, the analyser adapter that runs one, and the
#: commands of the Goland wing and the thesis's simple model (issue 29: the core never imports them)
FENCE_GATES = ("windflutter.methods", "windflutter.analysers", "windflutter.cli.")


def fence_breaches(graph=None) -> list[str]:
    """Modules outside ``windflutter.frozen`` and :data:`FENCE_GATES` that import it."""
    graph = _graph() if graph is None else graph
    return sorted(f"{m} (line {line}) imports {t}" for m, ts in graph.items() for t, line in ts
                  if (t == "windflutter.frozen" or t.startswith("windflutter.frozen."))
                  and not m.startswith("windflutter.frozen") and not m.startswith(FENCE_GATES))


def test_the_core_does_not_import_the_seed_methods():
    assert fence_breaches() == []


def test_the_fence_check_can_fail():
    graph = {"windflutter.overspeed": [("windflutter.frozen.search", 4)],
             "windflutter.methods": [("windflutter.frozen.turbine", 9)],
             "windflutter.frozen.turbine": [("windflutter.frozen.search", 3)]}
    assert fence_breaches(graph) == ["windflutter.overspeed (line 4) imports windflutter.frozen.search"]
