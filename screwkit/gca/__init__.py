"""Brackets, the 24-term superbracket expansion and its simplification (Grassmann–Cayley algebra).

Conventions (``gca.md`` §1, the *reference convention*): a projective point is
``(x, y, z, w)`` with the weight last, finite ``(r, 1)``, infinite ``(d, 0)``. The bracket
``[pqrs]`` is the determinant of the 4×4 matrix whose rows are p, q, r, s. The line through p and
q has the Plücker vector (ray order, direction first) ``L(p, q) = (p_w q − q_w p ; p × q)``, the
seed paper's zero-pitch wrench ``(s, r × s)`` (paper 002, §5.1). The superbracket
``[ab, cd, ef, gh, ij, kl]`` is the determinant of the 6×6 matrix whose rows are
``L(a, b), …, L(k, l)`` (White 2005, "Grassmann–Cayley algebra and robotics applications";
paper 002, §5.2). In this convention it equals the 24-term bracket
polynomial of ``gca.md`` §2.1 with constant exactly +1 (:func:`superbracket_expansion`).

The package has four layers; its modules, in import order notation → brackets → dotted → zeros →
expansion → factoring → factored → simplify → vector_forms → exact_proofs → condition_patterns →
conditions and diagram → diagram_lines → diagram_incidence → diagram_points → diagram_recipes →
diagram_placement → superbracket_analysis, each import only earlier ones:

* exact bracket algebra: :mod:`~screwkit.gca.notation` (labels, signs, printed and parsed text),
  :mod:`~screwkit.gca.brackets` (:class:`Bracket`, :class:`BracketMonomial`, :class:`BracketPolynomial`:
  integer or rational coefficients, canonical forms, evaluation on numeric batches or exact sympy
  points through :mod:`screwkit.algebra.projective`'s bracket and join), and :mod:`~screwkit.gca.dotted`, the
  dotted notation of McMillan & White (1991), :class:`DottedMonomial` and :class:`DottedSum`
  (``gca.md`` §3);
* the superbracket, :mod:`~screwkit.gca.expansion`: :func:`superbracket` (the 6×6 determinant, always
  the ground truth), :func:`superbracket_expansion`, :func:`superbracket_grouped` and the ordering
  search :func:`best_ordering`;
* the simplification procedure of ``gca.md`` §6, each step checked numerically on configurations
  drawn from a *sampler* (a callable ``rng -> {label: point (4,)}`` whose configurations satisfy
  the mechanism's incidences): :mod:`~screwkit.gca.zeros` (:func:`structural_zeros`,
  :func:`drop_zero_subsums`, also used by the ordering search), :mod:`~screwkit.gca.factoring`
  (bracket polynomials factored over the rationals), :mod:`~screwkit.gca.factored`
  (:func:`collect_factors`) and :mod:`~screwkit.gca.simplify` (:func:`check_proportional`, and the
  whole chain :func:`simplify_superbracket`);
* the interpretation of the factors (``gca.md`` §5): :mod:`~screwkit.gca.vector_forms`,
  :mod:`~screwkit.gca.exact_proofs`, :mod:`~screwkit.gca.condition_patterns` and
  :mod:`~screwkit.gca.conditions` (symbolic: they import sympy), and the wrench diagrams of
  mechanisms, :mod:`~screwkit.gca.diagram` and the modules named there, up to
  :mod:`~screwkit.gca.superbracket_analysis` (they import the wrench core). This ``__init__``
  imports neither group; it loads on first use the names of theirs users reach for: the condition
  interpreter :func:`~screwkit.gca.conditions.condition` (a bracket factor → its statement, vector
  form and proved constant, a :class:`~screwkit.gca.conditions.Condition`), the diagram of any
  mechanism with its generic-configuration sampler
  (:func:`~screwkit.gca.diagram_placement.graph_diagram`,
  :func:`~screwkit.gca.diagram_placement.graph_sampler`) and what happens where a factor vanishes
  (:func:`~screwkit.gca.factor_kinds.vanishing_kind`). The diagram's points at any pose are
  ``screwkit.diagram_points`` (here the name is its module's, :mod:`~screwkit.gca.diagram_points`).

Labels are short strings: a letter followed by letters or digits (``"a"``, ``"r1"``). A bracket may
be written ``"gikj"`` (single letters) or ``"r1 r2 r3 r4"`` (separated by spaces).

Notes
-----
Checked against the sources (tests/test_gca_*.py):

* The 24-term formula of ``gca.md`` §2.1 equals the 6×6 determinant exactly (a proof on all
  369 600 balanced basis configurations, see the test's docstring); the constants of §2.3 hold.
* ``gca.md`` §3 divides the alternation by ``∏_b k_b!`` with ``k_b`` the dotted positions in bracket
  b; with several dot kinds in one bracket the divisor must be taken per bracket *and* kind
  (``[e f ġ ï][ḣ j̈ k l]`` has four terms, not one).
* Paper 002, Eq. (5): the printed second line ``[gikj][abdf][cghj]`` lost the dots of
  ``[gikj][a b d ḟ][c g ḣ j]``; the undotted product is not proportional to the superbracket. In
  the reference convention the superbracket of ``[ab, cd, ef, gh, ij, kj]`` is
  ``−[gikj][a b d ḟ][c g ḣ j]`` (the paper states it "up to a scalar multiple").
* ``gca.md`` §6.4: with the H4's incidences (a, c, j and e, g, j collinear) the ordering
  ``[ab, ij, cd, kj, ef, gh]`` leaves 9 non-zero template monomials that combine into 5, and the
  counts over the 46 080 orderings range from 4 to 18 (the paper's order gives 5, so it is not
  the best); the quoted 13 (like terms not combined) and 5…20 hold only if they are ignored.

References
----------
.. [1] N. L. White, "Grassmann–Cayley algebra and robotics applications", Handbook of Geometric
   Computing, Part VIII, pp. 629–656, Springer, 2005.
.. [2] T. McMillan and N. L. White, "The dotted straightening algorithm", Journal of Symbolic
   Computation 11, pp. 471–482, 1991.
.. [3] S. Amine, D. Kanaan, S. Caro, P. Wenger, "Singularity analysis of lower-mobility parallel
   robots with an articulated nacelle", ARK 2010 (paper 002), §5, Eqs. (5)–(7).

Examples
--------
>>> from screwkit.gca import Bracket, BracketPolynomial
>>> Bracket("gikj") * Bracket("abdf") - Bracket("abdh") * Bracket("cgfj")
BracketPolynomial('[gikj][abdf] - [abdh][cgfj]')
>>> Bracket("bacd") == -Bracket("abcd")
True
>>> import screwkit.gca as gca
>>> print(gca.condition(Bracket("gikj"), finite="g", infinite="ijk").statement)
i, k and j are collinear in the plane at infinity (the directions i, k, j are parallel to one plane)
"""

from typing import Any

from .brackets import Bracket, BracketMonomial, BracketPolynomial
from .dotted import DottedMonomial, DottedSum
from .expansion import (
    OrderingSearch,
    best_ordering,
    superbracket,
    superbracket_expansion,
    superbracket_grouped,
)
from .factored import FactoredForm, collect_factors
from .simplify import (
    Proportionality,
    Simplification,
    check_proportional,
    simplify_superbracket,
)
from .zeros import drop_zero_subsums, structural_zeros

#: Names of the symbolic and the diagram modules, loaded on first use (``gca.condition``).
_LAZY = {
    "Condition": "conditions",
    "condition": "conditions",
    "graph_diagram": "diagram_placement",
    "graph_sampler": "diagram_placement",
    "vanishing_kind": "factor_kinds",
}


def __getattr__(name: str) -> Any:
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from importlib import import_module  # the module caches itself in sys.modules

    return getattr(import_module(f".{_LAZY[name]}", __name__), name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "Bracket",
    "BracketMonomial",
    "BracketPolynomial",
    "Condition",
    "DottedMonomial",
    "DottedSum",
    "FactoredForm",
    "OrderingSearch",
    "Proportionality",
    "Simplification",
    "best_ordering",
    "check_proportional",
    "collect_factors",
    "condition",
    "drop_zero_subsums",
    "graph_diagram",
    "graph_sampler",
    "simplify_superbracket",
    "structural_zeros",
    "superbracket",
    "superbracket_expansion",
    "superbracket_grouped",
    "vanishing_kind",
]
