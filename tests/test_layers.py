"""Layers one way (issue 10): no module of webfem imports a module of a higher layer.

The layers, bottom to top, as docs/architecture.md states them. A module's imports are read
from its source (``ast``), including imports inside functions.
"""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "webfem"

#: Bottom (0) to top. A module may import its own layer and those below.
LAYERS = [
    {"errors", "validated", "units", "progress", "sections", "keys", "case", "sweepspec",
     "files", "bundled", "cores", "line_speed",
     "physics"},
    {"fem"},
    {"summary", "result", "describe"},
    {"models"},
    {"api"},
    {"sweeps", "traction", "loss_scan", "calibrate", "effects", "idler", "studies",
     "groove_sizing"},
    {"io"},
    {"cli", "__main__"},
]


def layer_of(module: str) -> int:
    """The layer of ``webfem.a.b`` by its first part (``webfem`` itself: the public face)."""
    head = module.split(".")[1] if "." in module else "__init__"
    for i, names in enumerate(LAYERS):
        if head in names:
            return i
    raise KeyError(module)


def imports_of(path: Path) -> set[str]:
    """The webfem modules a file imports (absolute names)."""
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    package = parts[:-1] if parts[-1] != "__init__" else parts[:-1]
    if parts[-1] == "__init__":
        package = parts[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
                if node.module is None:   # from . import x, y
                    out |= {f"{name}.{a.name}" for a in node.names}
                    continue
            else:
                name = node.module or ""
            if name.startswith("webfem"):
                out.add(name)
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.startswith("webfem")}
    return out


MODULES = sorted(p for p in PACKAGE.rglob("*.py") if p.name != "__init__.py"
                 or p.parent != PACKAGE)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_import_from_a_higher_layer(path):
    me = ".".join(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    mine = layer_of(me)
    face = {"webfem", "webfem.__version__"}      # the package's face: loaded before anything
    upward = sorted(m for m in imports_of(path) if m not in face and layer_of(m) > mine)
    assert not upward, f"{me} (layer {mine}) imports {upward}"


def test_the_layer_table_covers_every_module():
    heads = {p.relative_to(PACKAGE).parts[0].removesuffix(".py") for p in MODULES}
    known = set().union(*LAYERS)
    assert heads <= known, heads - known


# -- private names and cycles (issue 21, item 5) ---------------------------------------------

def module_name(path: Path) -> str:
    """``webfem.a.b`` for ``webfem/a/b.py``, ``webfem.a`` for ``webfem/a/__init__.py``."""
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


ALL_MODULES = {module_name(p): p for p in PACKAGE.rglob("*.py")}


def imported_names(path: Path):
    """Every ``(module, name, bound as)`` a file imports from webfem, at any depth (inside
    functions and ``if TYPE_CHECKING:`` too): ``from .x import y as z`` gives
    ``("webfem.x", "y", "z")``, ``import webfem.x`` gives ``("webfem.x", None, None)``."""
    me = module_name(path)
    package = me.split(".") if path.name == "__init__.py" else me.split(".")[:-1]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source.split(".")[0] == "webfem":
                for alias in node.names:
                    yield source, alias.name, alias.asname or alias.name
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "webfem":
                    yield alias.name, None, alias.asname


def module_edges(path: Path) -> set[str]:
    """The webfem modules (files) a file's imports load by name: ``from . import x`` is
    module ``x`` when it is one, else the package's ``__init__``."""
    out = set()
    for source, name, _ in imported_names(path):
        if name is not None and f"{source}.{name}" in ALL_MODULES:
            out.add(f"{source}.{name}")
        elif source in ALL_MODULES:
            out.add(source)
    return out - {module_name(path)}


def private(name: str) -> bool:
    """``_name`` is private; ``__version__`` and the like are not."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_names_used(path: Path) -> list[str]:
    """The private names of other webfem modules a file uses: imported (``from .x import
    _y``) or reached through a module it imported (``from . import x`` then ``x._y``)."""
    used, modules = set(), {}
    for source, name, bound in imported_names(path):
        if name is None:
            if bound:   # import webfem.x as m
                modules[bound] = source
        elif private(name):
            used.add(f"{source}.{name}")
        elif f"{source}.{name}" in ALL_MODULES:
            modules[bound] = f"{source}.{name}"
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in modules and private(node.attr)):
            used.add(f"{modules[node.value.id]}.{node.attr}")
    return sorted(used)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_private_name_imported_across_modules(path):
    """A name with a leading underscore is its module's own: another module that needs it
    needs a public, documented name."""
    used = private_names_used(path)
    assert not used, f"{module_name(path)} uses private names of other modules: {used}"


def import_cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            scc = []
            while True:
                w = stack.pop()
                on.discard(w)
                scc.append(w)
                if w == v:
                    break
            if len(scc) > 1:
                out.append(sorted(scc))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_import_cycles_are_found():
    """The cycle finder itself: a -> b -> a is one, a -> b -> c is none."""
    assert import_cycles({"a": {"b"}, "b": {"a"}, "c": {"a"}}) == [["a", "b"]]
    assert import_cycles({"a": {"b"}, "b": {"c"}}) == []


def test_no_import_cycles():
    """No two modules import each other, directly or round a loop, counting every import
    (lazy ones inside functions and ``TYPE_CHECKING`` ones too: a cycle hidden in a
    function is still two modules that cannot be understood apart). The package's face
    (``webfem/__init__.py``) is left out: it imports the api to re-export it, and a
    module importing ``webfem.__version__`` from it is no design cycle."""
    graph = {m: module_edges(p) - {"webfem"} for m, p in ALL_MODULES.items()
             if m != "webfem"}
    cycles = import_cycles(graph)
    assert not cycles, "import cycles: " + "; ".join(" <-> ".join(c) for c in cycles)
