"""The cases many test modules share, defined once.

Each is a constant (for ``pytest.mark.parametrize`` lists and module-level tables, imported as
``from conftest import FLYING``: pytest puts tests/ on the path, as for ``orders``) and a
fixture of the same name in lower case (for a test's arguments). Cases are frozen, so sharing
them cannot couple tests. Files are read by absolute path: a test passes from any working
directory.
"""

from pathlib import Path

import pytest

from webfem import Case, load_case

#: The repository root and its case files.
ROOT = Path(__file__).resolve().parents[1]
CASE_DIR = ROOT / "cases"

#: The paper's rig at 20 m/s with every effect webfem models (= cases/base.toml): mixed
#: lubrication, the web partly on its asperities.
BASE = Case()
#: The base case at 40 m/s: the web flies (a fluid film everywhere), every model answers in
#: about a second.
FLYING = BASE.updated({"roller.speed": 40.0})
#: The base case with Hashimoto's model exactly (model.physics = "paper").
PAPER = BASE.updated({"model.physics": "paper"})
#: An undriven roller carried by the web (cases/idler.toml).
IDLER = load_case(CASE_DIR / "idler.toml")
#: The base case on a grooved roller (cases/base_grooved.toml).
GROOVED = load_case(CASE_DIR / "base_grooved.toml")
#: A PET film on an idler (cases/pet_idler.toml), smooth and grooved.
PET_IDLER = load_case(CASE_DIR / "pet_idler.toml")
PET_IDLER_GROOVED = load_case(CASE_DIR / "pet_idler_grooved.toml")


@pytest.fixture
def base() -> Case:
    """:data:`BASE`."""
    return BASE


@pytest.fixture
def flying() -> Case:
    """:data:`FLYING`."""
    return FLYING


@pytest.fixture
def idler() -> Case:
    """:data:`IDLER`."""
    return IDLER


@pytest.fixture
def grooved() -> Case:
    """:data:`GROOVED`."""
    return GROOVED


def inspect_before_save(monkeypatch, module, inspect, name: str = "save_figure") -> None:
    """Have ``module``'s saving function ``name`` call ``inspect(fig, renderer)`` on the
    drawn figure before it saves (and closes) it: a chart test measures its layout there."""
    real = getattr(module, name)

    def keep(fig, path):
        fig.canvas.draw()
        inspect(fig, fig.canvas.get_renderer())
        return real(fig, path)

    monkeypatch.setattr(module, name, keep)


class FakeResult:
    """A result the loss scan reads, its mu (and any other summary value) given: its case,
    and its summary by key."""

    def __init__(self, case, mu, **values):
        self.case = case
        self.summary = {"mu": mu, "model": "fake", "model_used": None, **values}

    def __getitem__(self, key):
        return self.summary[key]

    def slim(self):
        return self
