"""Expected convergence orders and their tolerances: the one place they are pinned.

The tests measure an observed order p = log2(e_h / e_{h/2}) from successive refinements and
compare it with the entry here (``assert p == ORDER.approx()``). A change of element, mesh
grading or refinement that moves an order is then one edit here, seen by every test that
relies on it. ``measured`` records what the order was when it was pinned.

Importable from the test modules as ``from orders import ...`` (pytest puts tests/ on the
path).
"""

from dataclasses import dataclass

import pytest

__all__ = ["Order", "GAP_1D", "GAP_2D", "GAP_GROOVED", "GAP_STUDY", "REYNOLDS_2D", "BEAM_HERMITE"]


@dataclass(frozen=True)
class Order:
    """An expected order with its absolute tolerance on the observed order."""

    expected: float
    tol: float
    measured: str = ""

    def approx(self):
        return pytest.approx(self.expected, abs=self.tol)


#: Central gap of the Eshel-Elrod problem (1-D), uniform refinement of the graded mesh,
#: levels 0-3, by pressure order: P1 (lumped sink) 2, P2 with the Hermite web 4
#: (superconvergent point value). tests/test_fe1d.py.
GAP_1D = {1: Order(2.0, 0.3, "2.00"), 2: Order(4.0, 0.3, "4.00")}

#: Central gap of the 2-D film + 1-D web (Eshel-Elrod, lambda = 10), refinement in both
#: directions, levels 0-2, by pressure order: Q1 2, Q2 4. tests/test_fe2d.py.
GAP_2D = {1: Order(2.0, 0.2, "1.99"), 2: Order(4.0, 0.3, "3.98")}

#: The same on a grooved roller's periodic cell (groove depth 0.5, the step in the gap on
#: element edges): the smooth orders are kept. tests/test_grooves.py.
GAP_GROOVED = {1: Order(2.0, 0.2, "1.99"), 2: Order(4.0, 0.3, "3.98")}

#: The reduced convergence study (base case at 40 m/s, ``quick=True``): observed order of
#: h_center with linear pressure elements, by model. tests/test_studies.py.
GAP_STUDY = {("fe1d", 1): Order(2.0, 0.3), ("fe2d", 1): Order(2.0, 0.3)}

#: Manufactured solution of the 2-D compressible Reynolds operator with the permeation sink
#: (tests/test_mms.py): (L2 order, H1 seminorm order) by element.
REYNOLDS_2D = {"Q1": (Order(2.0, 0.15), Order(1.0, 0.15)),
               "Q2": (Order(3.0, 0.15), Order(2.0, 0.15))}

#: Manufactured solution of the beam with cubic Hermite elements (tests/test_mms.py):
#: L2, H1 seminorm and H2 seminorm orders.
BEAM_HERMITE = (Order(4.0, 0.15), Order(3.0, 0.15), Order(2.0, 0.15))
