"""Weak forms as data, and the two assemblies generated from them.

A weak form is declared once (:class:`WeakForm`): its residual terms, each a coefficient times
an operator on the test function, and its Jacobian blocks, each a coefficient times an
operator on the test function times an operator on the trial function,

    F_i  = sum_terms  int c(x) op(phi_i) dx,
    J_ij = sum_blocks int c(x) op(phi_i) op'(psi_j) dx,

over fields named in the declaration ("p" the film pressure, "w" the web deflection) and the
operators ``val``, ``dx`` (d/dX), ``dz`` (d/dZ, 2-D only) and ``dxx`` (d2/dX2). The
coefficients are arrays at the quadrature points that one function computes from the state
(:mod:`webfem.fem.forms`: the single physics-aware place), or a name of a scalar, or a number.
A coefficient written ``"-name"`` enters with its sign flipped.

From a declaration this module generates

* :func:`skfem_forms`: scikit-fem's ``LinearForm`` and ``BilinearForm`` (the readable
  reference; one call of the kernel per pair of local basis functions), and
* :class:`FastForm`: the same integrals contracted over all elements at once from the bases'
  arrays read once per mesh (:class:`webfem.fem.fast.BasisData`), into a sparsity pattern
  built once per mesh (:class:`webfem.fem.fast.Pattern`), so a Jacobian is one refill of a
  CSR matrix's data.

The fast form also takes a field on another mesh: the web's Hermite functions at the 2-D
film's quadrature points (:meth:`Space.from_arrays` of the transfer matrices), so the film-web
blocks of the 2-D model come from the same declaration. tests/test_forms.py assembles every
declaration both ways and compares them to 1e-12.

Examples
--------
>>> import numpy as np
>>> from skfem import Basis, ElementLineP1, MeshLine
>>> from webfem.fem.fast import BasisData
>>> mass = WeakForm("mass", ("p",), terms=(Term("p", "val", "f"),),
...                 blocks=(Block("p", "val", "p", "val", 1.0),))
>>> b = BasisData(Basis(MeshLine(np.linspace(0.0, 1.0, 5)), ElementLineP1()))
>>> fast = FastForm([Part((mass,), {"p": Space.from_basis(b)}, b.dx)], b.N)
>>> float(fast.jacobian([{}]).sum()), float(fast.residual([{"f": np.ones_like(b.dx)}]).sum())
(1.0, 1.0)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, LinearForm

from .fast import contract_laid, contract_layout, pattern_of, test_layout

__all__ = ["Term", "Block", "WeakForm", "Space", "Part", "FastForm", "skfem_forms", "coefficient",
           "OPERATORS"]

#: The operators a term may apply to a test or trial function.
OPERATORS = ("val", "dx", "dz", "dxx")


@dataclass(frozen=True)
class Term:
    """A residual term: int ``coef`` ``op``(test of ``field``)."""

    field: str
    op: str
    coef: str | float


@dataclass(frozen=True)
class Block:
    """A Jacobian term: int ``coef`` ``op``(test of ``field``) ``trial_op``(trial of
    ``trial``)."""

    field: str
    op: str
    trial: str
    trial_op: str
    coef: str | float


@dataclass(frozen=True)
class WeakForm:
    """A named declaration: its ``fields``, residual ``terms`` and Jacobian ``blocks``
    (``blocks`` may be empty for a form assembled only as a residual)."""

    name: str
    fields: tuple[str, ...]
    terms: tuple[Term, ...] = ()
    blocks: tuple[Block, ...] = ()

    def __post_init__(self):
        for t in self.terms + self.blocks:
            ops = (t.op,) + ((t.trial_op,) if isinstance(t, Block) else ())
            fields = (t.field,) + ((t.trial,) if isinstance(t, Block) else ())
            if any(o not in OPERATORS for o in ops) or any(f not in self.fields
                                                         for f in fields):
                raise ValueError(f"{self.name}: {t} uses an unknown operator or field")


def coefficient(values: dict, coef):
    """The value of a term's coefficient: a number, ``values[name]`` or its negative."""
    if not isinstance(coef, str):
        return coef
    if coef.startswith("-"):
        return -values[coef[1:]]
    return values[coef]


# -- the scikit-fem reference ----------------------------------------------------------------
def _operator(f, op: str):
    if op == "val":
        return f
    if op == "dx":
        return f.grad[0]
    if op == "dz":
        return f.grad[1]
    return f.hess[0, 0]


def _present(f, op: str) -> bool:
    return op != "dz" or f.grad.shape[0] > 1


def skfem_forms(forms, fields: tuple[str, ...]) -> tuple[LinearForm, BilinearForm]:
    """scikit-fem's residual and Jacobian forms of the declarations ``forms`` on a basis whose
    components are ``fields`` (in order; a composite element has one per field). Terms of a
    field the basis does not hold are left out, and so are ``dz`` terms in 1-D. The
    coefficients are the keyword arguments of ``assemble``."""
    terms = [t for form in forms for t in form.terms if t.field in fields]
    blocks = [b for form in forms for b in form.blocks
              if b.field in fields and b.trial in fields]
    n = len(fields)

    def residual(*args):
        tests, w = dict(zip(fields, args[:n])), args[n]
        return sum(coefficient(w, t.coef) * _operator(tests[t.field], t.op) for t in terms
                   if _present(tests[t.field], t.op))

    def jacobian(*args):
        trials, tests = dict(zip(fields, args[:n])), dict(zip(fields, args[n:2 * n]))
        w = args[2 * n]
        return sum(coefficient(w, b.coef) * _operator(tests[b.field], b.op)
                   * _operator(trials[b.trial], b.trial_op) for b in blocks
                   if _present(tests[b.field], b.op) and _present(trials[b.trial], b.trial_op))

    return LinearForm(residual), BilinearForm(jacobian)


# -- the fast assembly ---------------------------------------------------------------------------
@dataclass
class Space:
    """A field's local functions at one set of quadrature points: their global DOFs
    (local function, element) and, per operator, their values (local function, element,
    point)."""

    dofs: np.ndarray
    ops: dict = field(default_factory=dict)

    @classmethod
    def from_basis(cls, b, component: int = 0, offset: int = 0) -> "Space":
        """Component ``component`` of a :class:`~webfem.fem.fast.BasisData` (its DOFs
        shifted by ``offset``, for a field that follows another in the unknowns)."""
        grad = b.grad_c[component]
        ops = {"val": b.phi_c[component], "dx": grad[:, 0]}
        if grad.shape[1] > 1:
            ops["dz"] = grad[:, 1]
        if b.hess_c[component] is not None:
            ops["dxx"] = b.hess_c[component]
        return cls(b.dofs_of(component) + offset, ops)

    @classmethod
    def from_arrays(cls, values: np.ndarray, dofs: np.ndarray, offset: int = 0) -> "Space":
        """A field given by its values at another basis's quadrature points (the web's
        Hermite functions at the film's points: ``M_loc``, ``M_dofs`` of
        :func:`webfem.fem.transfer.quadrature_matrices`)."""
        return cls(np.asarray(dofs) + offset, {"val": np.asarray(values)})


@dataclass
class Part:
    """Declarations assembled on one set of quadrature points: the ``forms``, the fields'
    :class:`Space` objects there and the quadrature weights ``dx`` (element, point)."""

    forms: tuple
    spaces: dict
    dx: np.ndarray


def _layout_of(space, ops: list, built: list) -> np.ndarray:
    """The test layout (:func:`webfem.fem.fast.test_layout`) of ``space``'s operators
    ``ops``: a view of one in ``built`` ((space, operators, layout) triples) whose operators
    hold ``ops`` as a run, else built and added to it."""
    for other, their, layout in built:
        if other is not space:
            continue
        for i in range(len(their) - len(ops) + 1):
            if their[i:i + len(ops)] == ops:
                nq = layout.shape[1] // len(their)
                return layout[:, i * nq:(i + len(ops)) * nq, :]
    layout = test_layout([space.ops[o] for o in ops])
    built.append((space, ops, layout))
    return layout


def _leads(group, ops) -> tuple[int, ...] | None:
    """For a group of blocks of one field (test and trial), the index of the first block of
    each test operator of ``ops`` where each has that operator on its trial side too (the
    film's d/dX-d/dX, d/dZ-d/dZ and value-value blocks), else None."""
    first = []
    for o in ops:
        i = next(i for i, b in enumerate(group) if b.op == o)
        if group[i].trial_op != o:
            return None
        first.append(i)
    return tuple(first)


class FastForm:
    """The declarations of every :class:`Part` assembled over all elements at once into one
    system of ``n`` unknowns (one sparsity pattern: the film + web system of a mesh).

    The Jacobian's blocks are grouped per part by (test field, trial field) and, within a
    group, by the test operator: the trial sides of one test operator are summed and every
    test operator of a group contracted in one batched matrix product
    (:func:`webfem.fem.fast.contract_layout`). Blocks with a number for a coefficient, or a
    scalar (e.g. the bending group ``Dn``), are contracted with a unit coefficient once,
    when first needed, and scaled.
    """

    def __init__(self, parts, n: int):
        self.parts, self.n = list(parts), int(n)
        self._terms, self._groups, self._layouts, self._unit = [], [], [], {}
        #: per part, the groups of one field whose first block of each test operator has
        #: that operator on its trial side too: their index in the group, in the layout's
        #: order of the operators (:meth:`blocks`)
        self._leads = []
        pairs = []
        for part in self.parts:
            sp_ = part.spaces
            self._terms.append([t for f in part.forms for t in f.terms
                                if t.field in sp_ and t.op in sp_[t.field].ops])
            groups = {}
            for f in part.forms:
                for b in f.blocks:
                    if (b.field in sp_ and b.trial in sp_ and b.op in sp_[b.field].ops
                            and b.trial_op in sp_[b.trial].ops):
                        groups.setdefault((b.field, b.trial), []).append(b)
            ops = {key: list(dict.fromkeys(b.op for b in group))
                   for key, group in groups.items()}
            layouts, built = {}, []
            # the most operators first: a group whose test operators are a run of another's
            # (the film's p-w group: d/dX, d/dZ of the p-p group's d/dX, d/dZ, val) takes a
            # view of that layout's rows (the same matrices to the bit, one layout fewer:
            # 126 MB at 3.9e5 unknowns)
            for key in sorted(groups, key=lambda k: -len(ops[k])):
                layouts[key] = (ops[key], _layout_of(sp_[key[0]], ops[key], built))
            self._groups.append(groups)
            self._layouts.append(layouts)
            self._leads.append({key: _leads(group, ops[key]) for key, group in groups.items()
                                if key[0] == key[1]})
            pairs += [(sp_[fi].dofs, sp_[fj].dofs) for fi, fj in groups]
        self.pattern = pattern_of(pairs, (self.n, self.n)) if pairs else None

    def residual(self, values) -> np.ndarray:
        """F from each part's coefficient arrays (``values``: one dict per part)."""
        F = np.zeros(self.n)
        for part, terms, vals in zip(self.parts, self._terms, values):
            local = {}
            for t in terms:
                c = coefficient(vals, t.coef) * part.dx
                piece = np.einsum("ieq,eq->ie", part.spaces[t.field].ops[t.op], c)
                local[t.field] = piece if t.field not in local else local[t.field] + piece
            for name, piece in local.items():
                F += np.bincount(part.spaces[name].dofs.ravel(), weights=piece.ravel(),
                                 minlength=self.n)
        return F

    def _unit_block(self, k: int, b: Block) -> np.ndarray:
        if (k, b) not in self._unit:
            part = self.parts[k]
            self._unit[k, b] = contract_layout(test_layout(part.spaces[b.field].ops[b.op]),
                                               part.spaces[b.trial].ops[b.trial_op] * part.dx)
        return self._unit[k, b]

    def blocks(self, values) -> list[np.ndarray]:
        """Each group's element matrices (test function, trial function, element), in the
        pattern's order.

        The weighted trial sides of a group are summed straight into the left operand of
        :func:`webfem.fem.fast.contract_layout`, laid out as it lays them out ((element,
        trial function, test operator x point)): the same values in the same matrix
        product, without the per-operator arrays, their stack and its transposed copy
        (three arrays of the group's size: ~570 MB at 3.9e5 unknowns, held beside the
        factorisation Newton keeps for its chord steps)."""
        out = []
        for k, (part, groups, vals) in enumerate(zip(self.parts, self._groups, values)):
            for key, group in groups.items():
                ops, layout = self._layouts[k][key]
                coefs = [coefficient(vals, b.coef) for b in group]
                total = None
                for b, c in zip(group, coefs):
                    if np.ndim(c) == 0:
                        piece = float(c) * self._unit_block(k, b)
                        total = piece if total is None else total + piece
                used = [o for o in ops if any(b.op == o and np.ndim(c) > 0
                                              for b, c in zip(group, coefs))]
                if used:
                    slot = {o: i for i, o in enumerate(used)}
                    trial, filled, led = None, set(), ()
                    lead = self._leads[k].get(key)
                    if lead is not None and used == ops and all(np.ndim(coefs[i]) > 0
                                                                for i in lead):
                        # each test operator's first block in one product, the rest added
                        trial = self._lead_terms(part, layout, [coefs[i] for i in lead])
                        filled, led = set(ops), lead
                    for i, (b, c) in enumerate(zip(group, coefs)):
                        if np.ndim(c) == 0 or i in led:
                            continue
                        term = part.spaces[b.trial].ops[b.trial_op] * (c * part.dx)
                        if trial is None:
                            nj, ne, nq = term.shape
                            trial = np.empty((ne, nj, len(used), nq))
                        at = trial[:, :, slot[b.op], :]
                        if b.op in filled:
                            at += term.transpose(1, 0, 2)
                        else:
                            at[...] = term.transpose(1, 0, 2)
                            filled.add(b.op)
                        del term
                    lay = layout if len(used) == len(ops) else test_layout(
                        [part.spaces[key[0]].ops[o] for o in used])
                    piece = contract_laid(lay, trial.reshape(trial.shape[0],
                                                             trial.shape[1], -1))
                    del trial
                    total = piece if total is None else total + piece
                out.append(total)
        return out

    @staticmethod
    def _lead_terms(part, layout, coefs) -> np.ndarray:
        """The trial sides (element, trial function, test operator, point) of a group's
        leading blocks (:func:`_leads`), each its operator times (coefficient x dx), in one
        product: the layout holds those operators' values already, as (element, operator x
        point, function). Why: filled one operator at a time, each product was written
        into the trial array in runs of one element's points (9 values), and those strided
        writes were most of the film's Jacobian assembly (the same products, so the same
        bits)."""
        ne, nq = np.shape(part.dx)
        weights = np.empty((ne, 1, len(coefs), nq))
        for s, c in enumerate(coefs):
            np.multiply(c, part.dx, out=weights[:, 0, s, :])
        # C order, as the contraction reads it (numpy would lay the product out like the
        # transposed layout: another matrix product path, other bits)
        trial = np.empty((ne, layout.shape[2], len(coefs), nq))
        np.multiply(layout.transpose(0, 2, 1), weights.reshape(ne, 1, len(coefs) * nq),
                    out=trial.reshape(ne, layout.shape[2], len(coefs) * nq))
        return trial

    def jacobian(self, values) -> sp.csr_matrix:
        """The Jacobian from each part's coefficient arrays."""
        return self.pattern.matrix(self.blocks(values))
