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
    {"errors", "units", "progress", "sections", "case", "sweepspec", "files", "bundled",
     "physics"},
    {"fem"},
    {"result", "describe"},
    {"models"},
    {"api"},
    {"sweeps", "traction", "calibrate", "effects", "idler", "studies", "groove_sizing"},
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
