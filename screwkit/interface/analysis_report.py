"""The report of :func:`screwkit.interface.report.analyze`: what it found, as JSON-ready data and as text.

:class:`AnalysisReport` holds the stages' results (twist graph and equivalent graph, wrench
analysis, verdict, wrench diagram, superbracket, Jacobians, transmission indices) and renders them:
:meth:`~AnalysisReport.to_dict` (the ``--json`` output, documented in the README) and ``str()`` (the
text of ``screwkit analyze``): what the mechanism is, which wrenches act on its platform (each as a
line: kind, direction, a point, pitch, :func:`describe_wrench`), the diagram's twelve points in
words, the factored superbracket, each factor as a geometric statement and a vector form with its
label, the verdict with its closeness measures, the Jacobians and the transmission indices.

Examples
--------
>>> from screwkit.interface.report import analyze
>>> report = analyze("h4", superbracket=False)
>>> str(report).splitlines()[0].split()[0], report.to_dict()["verdict"]["verdict"]
('H4', 'regular')
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.motion_type import motion_type
from ..core.finite_mobility import MobilityReading
from ..core.jacobian_matrices import Jacobians
from ..core.mode_search import OperationModes
from ..core.mode_transitions import ModesAtPose
from ..core.singularity import SingularityReport
from ..core.wrenches import WrenchAnalysis
from ..graphs.loops import fundamental_loops
from ..robots.angles import pose_text
from ._report_conditions import condition_lines
from .screw_descriptions import describe_twist, describe_wrench

if TYPE_CHECKING:  # the diagram and GCA stack loads when a report is made, not on `import screwkit`
    from ..gca.diagram import WrenchDiagram
    from ..gca.grassmann import GrassmannClass
    from ..gca.redundant_conditions import RedundantSuperbracket
    from ..gca.superbracket_analysis import SuperbracketAnalysis

__all__ = ["AnalysisReport"]

Array = np.ndarray


_SNAPSHOT_JACOBIANS = "not computed"


@dataclass(frozen=True, eq=False)
class AnalysisReport:
    """Everything :func:`~screwkit.interface.report.analyze` found (see the module docstring).

    Attributes
    ----------
    name, source, length_unit : str
    pose : numpy.ndarray or None
        In the length unit and radians (None for a snapshot).
    pose_names : tuple of str
    graph, equivalent : networkx.MultiDiGraph
        The physical twist graph and its equivalent graph (closed sub-loops as virtual chains).
    analysis : WrenchAnalysis
    verdict : SingularityReport
    diagram : WrenchDiagram
    superbracket : SuperbracketAnalysis, RedundantSuperbracket or None
        (a redundantly actuated mechanism's: the superbrackets of its six-line subsets)
        None when not computed, when the mechanism has no diagram, or when its diagram does not
        exist at the pose (e.g. a limb at a serial singularity); ``superbracket_note`` says which.
    superbracket_note : str
        How structural zeros were confirmed, or why there is no factorization.
    jacobians : Jacobians or None
        ``A χ̇ = B θ̇`` over the family's nominal twists at the pose, with the Gosselin–Angeles
        type (:mod:`screwkit.interface.report`); None for a snapshot, or when the basis is refused
        at the pose.
    jacobians_note : str
        What the Jacobians' columns are, or why there are none.
    transmission : dict or None
        The transmission indices at the pose
        (:func:`screwkit.papers.paper_004_summary.transmission_summary`: the wrench-based
        ITI/OTI/LTI, and paper 004's κ, ζ, η for the four-limb family); None for a snapshot.
    given_length_scale : float or None
        The characteristic length the caller gave (None: derived from the screws; the one used is
        ``analysis.length_scale``).
    angle_names : tuple of str
        The pose coordinates that are angles (shown in degrees).
    mobility : MobilityReading or None
        The instantaneous and finite mobility at the configuration
        (:func:`screwkit.core.finite_mobility.mobility_reading`; a graph's report), shown when they
        differ or the finite one is undecided; None when not read.
    modes_at_pose : ModesAtPose or None
        The operation modes through the pose (:func:`screwkit.core.mode_transitions.modes_at`; None
        where not tested): where several meet, the report says so and gives the pose's verdict in each.
    operation_modes : OperationModes or None
        The modes found (:func:`screwkit.core.mode_search.find_operation_modes`; a graph's report),
        shown when more than one: "4 operation modes: 3T (this one), 3R, 2T1R and 3T (turned 180°
        about (0, 0, 1)) (found in ...)".
    """

    name: str
    source: str
    length_unit: str
    pose: Array | None
    pose_names: tuple[str, ...]
    graph: nx.MultiDiGraph
    equivalent: nx.MultiDiGraph
    analysis: WrenchAnalysis
    verdict: SingularityReport
    diagram: WrenchDiagram
    superbracket: SuperbracketAnalysis | RedundantSuperbracket | None
    superbracket_note: str
    jacobians: Jacobians | None = None
    jacobians_note: str = _SNAPSHOT_JACOBIANS
    transmission: dict[str, Any] | None = None
    given_length_scale: float | None = None
    angle_names: tuple[str, ...] = ()
    mobility: MobilityReading | None = None
    modes_at_pose: ModesAtPose | None = None
    operation_modes: OperationModes | None = None

    def graph_summary(self) -> dict[str, Any]:
        """Links, joints by type, actuated joints, loops; and the equivalent graph's virtual joints.

        Returns
        -------
        dict
            ``links``, ``joints`` (count by type), ``actuated`` (joint names), ``loops`` and
            ``equivalent`` (its ``links``, ``virtual_joints`` by type and ``loops``), JSON-ready.

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> summary = analyze("h4", superbracket=False).graph_summary()
        >>> summary["actuated"], summary["equivalent"]["virtual_joints"]  # per 4S loop: 2 vR, 2 vP
        (['A1', 'A2', 'A3', 'A4'], {'vP': 8, 'vR': 8})
        """
        joints = Counter(j.type for _, _, j in self.graph.edges(data="joint"))
        virtual = Counter(j.type for _, _, j in self.equivalent.edges(data="joint") if j.virtual)
        return {
            "links": self.graph.number_of_nodes(),
            "joints": dict(sorted(joints.items())),
            "actuated": sorted(k for _, _, k, j in self.graph.edges(keys=True, data="joint") if j.actuated),
            "loops": len(fundamental_loops(self.graph)),
            "equivalent": {
                "links": self.equivalent.number_of_nodes(),
                "virtual_joints": dict(sorted(virtual.items())),
                "loops": len(fundamental_loops(self.equivalent)),
            },
        }

    def wrenches(self) -> dict[str, Any]:
        """The platform's twist order and every wrench as a line.

        Returns
        -------
        dict
            ``platform_twist_order``, ``platform_twists`` (its ``motion_type`` and a readable
            ``basis``, each twist as :func:`describe_twist`), ``leg_motion_types``, the
            ``constraint`` and ``actuation`` wrenches (each as :func:`describe_wrench`, with its leg
            or actuated joint) and ``global_order``, JSON-ready.

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> wrenches = analyze("h4", superbracket=False).wrenches()
        >>> wrenches["platform_twist_order"], [w["joint"] for w in wrenches["actuation"]]
        (4, ['A1', 'A2', 'A3', 'A4'])
        """
        scale = self.analysis.length_scale
        platform = self.analysis.platform_twists
        legs = sorted(self.analysis.compound_legs, key=lambda leg: leg.name)  # each view built once
        unit = self.length_unit  # a helical freedom's pitch names it
        return {
            "platform_twist_order": platform.order,
            "platform_twists": {
                "motion_type": motion_type(platform, length_unit=unit),
                "basis": [
                    describe_twist(t, length_scale=scale)
                    for t in platform.readable_basis(near=self.analysis.reference_point)
                ],
            },
            "leg_motion_types": {leg.name: motion_type(leg.twist_system, length_unit=unit) for leg in legs},
            "constraint": [
                {"leg": leg.name, **describe_wrench(w, length_scale=scale)}
                for leg in legs
                for w in leg.constraint_wrenches.readable_basis()
            ]
            if legs
            else [
                {"leg": "mechanism", **describe_wrench(w, length_scale=scale)}
                for w in self.analysis.constraint_wrenches.readable_basis()
            ],
            "actuation": [
                {
                    "joint": limb.actuated_joint,
                    **(
                        describe_wrench(limb.actuation_wrench, length_scale=scale)
                        if limb.actuation_wrench is not None
                        else {"kind": "none (serial singularity)"}
                    ),
                }
                for limb in self.analysis.limbs
            ],
            "global_order": self.analysis.global_wrenches.order,
        }

    def wrench_lines(self) -> Array:
        """The platform's wrenches as rows: each leg's constraint wrenches (readable basis), then
        each limb's actuation wrench (none for a limb at a serial singularity).

        Returns
        -------
        numpy.ndarray, shape (n, 6)

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> analyze("h4", superbracket=False).wrench_lines().shape
        (6, 6)
        """
        legs = sorted(self.analysis.compound_legs, key=lambda leg: leg.name)
        systems = [leg.constraint_wrenches for leg in legs] or [self.analysis.constraint_wrenches]
        rows = [w for system in systems for w in system.readable_basis()]
        rows += [limb.actuation_wrench for limb in self.analysis.limbs if limb.actuation_wrench is not None]
        return np.array(rows, dtype=float).reshape(-1, 6)

    def grassmann(self) -> tuple[GrassmannClass | None, str]:
        """The Grassmann-geometry class of the wrench lines (:meth:`wrench_lines`) at a singular
        pose (:func:`screwkit.gca.grassmann.grassmann_class`, at the analysis' rank tolerance).

        Returns
        -------
        found : GrassmannClass or None
            None at a regular pose, or when a wrench is not a line (a non-zero finite pitch).
        note : str
            Why there is no class, or "" when there is one.

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> analyze("h4", superbracket=False).grassmann()
        (None, 'regular pose: the wrench lines are independent')
        """
        from ..exceptions import ScrewkitValueError
        from ..gca.grassmann import grassmann_class

        if not self.verdict.is_singular:
            return None, "regular pose: the wrench lines are independent"
        rows = self.wrench_lines()
        if not len(rows):
            return None, "no wrench acts on the platform"
        try:
            return grassmann_class(rows, rtol=self.analysis.rtol), ""
        except ScrewkitValueError as err:
            return None, f"no Grassmann class: {err}"

    def jacobian_summary(self) -> dict[str, Any] | None:
        """The Gosselin–Angeles type, ``det A``, ``det B``, closeness, ``A``, ``B`` (None: snapshot).

        Every key is present for a catalog mechanism; the values are None when the Jacobians were
        not computed (``note`` says why).

        Returns
        -------
        dict or None
            ``type``, ``det_A`` (None unless ``A`` is square), ``det_B``, ``closeness``,
            ``actuated_joints``, ``serial_limbs``, ``twist_basis``, ``A``, ``B``, ``rtol`` and
            ``note``, JSON-ready; None for a snapshot.

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> summary = analyze("planar_3rrp", superbracket=False).jacobian_summary()
        >>> summary["type"], summary["actuated_joints"]
        ('regular', ['limb1_R1', 'limb2_R1', 'limb3_R1'])
        """
        if self.pose is None and self.jacobians is None:  # a snapshot whose Jacobians are not defined
            return None
        jac = self.jacobians
        square = jac is not None and jac.A.shape[0] == jac.A.shape[1]
        return {
            "type": None if jac is None else jac.type,
            "det_A": jac.det_A if jac is not None and square else None,
            "det_B": None if jac is None else jac.det_B,
            "closeness": None if jac is None else dict(jac.closeness),
            "actuated_joints": None if jac is None else list(jac.actuated_joints),
            "serial_limbs": None if jac is None else list(jac.serial_limbs),
            "twist_basis": None if jac is None or jac.twist_basis is None else jac.twist_basis.tolist(),
            "A": None if jac is None else jac.A.tolist(),
            "B": None if jac is None else jac.B.tolist(),
            "rtol": None if jac is None else jac.rtol,
            "note": self.jacobians_note,
        }

    def to_dict(self) -> dict[str, Any]:
        """The whole report as JSON-ready data (documented in the README).

        Returns
        -------
        dict
            ``mechanism``, ``pose``, ``twist_graph`` (:meth:`graph_summary`), ``wrenches``
            (:meth:`wrenches`), ``diagram``, ``superbracket``, ``superbracket_note``, ``verdict``,
            ``grassmann`` (the wrench lines' Grassmann class at a singular pose, else None),
            ``jacobians`` (:meth:`jacobian_summary`), ``transmission``, ``modes_at_pose`` and
            ``operation_modes`` (a graph's; else None): the output of ``screwkit analyze --json``.

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> list(analyze("v4", superbracket=False).to_dict())[:3]
        ['mechanism', 'pose', 'twist_graph']
        """
        grassmann, _ = self.grassmann()
        return {
            "mechanism": {"name": self.name, "source": self.source, "length_unit": self.length_unit},
            "pose": None
            if self.pose is None
            else dict(zip(self.pose_names, self.pose.tolist(), strict=True)),
            "twist_graph": self.graph_summary(),
            "wrenches": self.wrenches(),
            "diagram": self.diagram.to_dict(),
            "superbracket": None if self.superbracket is None else self.superbracket.to_dict(),
            "superbracket_note": self.superbracket_note,
            "verdict": self.verdict.to_dict(),
            "grassmann": None if grassmann is None else grassmann.to_dict(),
            "jacobians": self.jacobian_summary(),
            "transmission": self.transmission,
            "modes_at_pose": None if self.modes_at_pose is None else self.modes_at_pose.to_dict(),
            "operation_modes": None if self.operation_modes is None else self.operation_modes.to_dict(),
        }

    def __str__(self) -> str:
        unit = self.length_unit
        out = [self.name if self.source == self.name else f"{self.name}  ({self.source})"]
        if self.pose is not None:
            out.append(f"pose: {self.pose_words()}")
        if self.analysis.rtol != B.DEFAULT_RTOL:  # the default is the README's; another is said
            out.append(f"rank tolerance: rtol = {self.analysis.rtol:g} (default {B.DEFAULT_RTOL:g})")
        if self.given_length_scale is not None:  # likewise (the default is derived from the screws)
            out.append(
                f"length scale: {self.given_length_scale:g} {unit} (given; default: derived from the screws)"
            )
        summary = self.graph_summary()
        joints = ", ".join(f"{count} {kind}" for kind, count in summary["joints"].items())
        out += [
            "",
            "twist graph",
            f"  {summary['links']} links, joints: {joints}; {summary['loops']} loops",
            f"  actuated: {', '.join(summary['actuated'])}",
        ]
        eq = summary["equivalent"]
        virtual = ", ".join(f"{count} {kind}" for kind, count in eq["virtual_joints"].items()) or "none"
        out.append(f"  equivalent graph: {eq['links']} links, {eq['loops']} loops, virtual joints: {virtual}")
        wrenches = self.wrenches()
        twists = wrenches["platform_twists"]
        out += [
            "",
            f"platform twist system: {twists['motion_type']} (order {wrenches['platform_twist_order']})",
            *(
                f"  translation along {_vector(item['direction'])}"
                if item["kind"] == "translation"
                else f"  {_line_text(item, unit)}"
                for item in twists["basis"]
            ),
            *(f"  {leg}: {kind}" for leg, kind in wrenches["leg_motion_types"].items()),
        ]
        if self.mobility is not None and (self.mobility.differs or self.mobility.finite is None):
            out += ["", str(self.mobility)]
        if self.operation_modes is not None and len(self.operation_modes) > 1:
            out += ["", self.operation_modes.describe()]  # where they meet: the modes_at lines below
        out += ["", f"wrench systems (platform twist system of order {wrenches['platform_twist_order']})"]
        for item in wrenches["constraint"]:
            out.append(f"  constraint ({item['leg']}): {_line_text(item, unit)}")
        for item in wrenches["actuation"]:
            out.append(f"  actuation {item['joint']}: {_line_text(item, unit)}")
        out.append(f"  global wrench system: order {wrenches['global_order']}")
        out += ["", str(self.diagram)]
        out += ["", "superbracket"]
        if self.superbracket is None:
            out.append(f"  {self.superbracket_note}")
        else:
            from ..gca.redundant_conditions import RedundantSuperbracket as Redundant

            if isinstance(self.superbracket, Redundant):  # redundant actuation: the six-line subsets
                out.append(f"  {self.superbracket.statement()}")
            else:
                simplification = self.superbracket.simplification
                out.append(f"  {self.diagram.line_text()} = {simplification.factored}")
                out.append(
                    f"  monomials: 24 in the expansion, {len(simplification.survivors)} not structurally zero"
                )
            out.append(f"  {self.superbracket_note}")
            result = self.superbracket
            if result.representation:
                out.append(
                    "  the diagram does not hold at this pose ("
                    + "; ".join(result.representation)
                    + "): the factored form is the design's, found at generic configurations, and each "
                    "condition is evaluated where its points exist"
                )
            out += ["", "conditions", *condition_lines(result, self.verdict.is_singular)]
        out += ["", "verdict", *("  " + line for line in str(self.verdict).splitlines())]
        if self.modes_at_pose is not None and self.modes_at_pose.meets:
            out += ["", *self.modes_at_pose.lines()]
        grassmann, _ = self.grassmann()
        if grassmann is not None:
            out += ["", *str(grassmann).splitlines()]
        if self.pose is not None or self.jacobians is not None:
            out += ["", *self._jacobian_lines()]
        if self.transmission is not None:
            out += ["", *_transmission_lines(self.transmission)]
        return "\n".join(out)

    def pose_words(self) -> str:
        """The pose in words, each coordinate with its unit (angles in degrees), or "a snapshot's
        configuration" when there is no pose (:func:`screwkit.robots.angles.pose_text`).

        Returns
        -------
        str

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> analyze("v4", superbracket=False).pose_words()
        'x = 0 mm, y = 0 mm, z = -750 mm, phi = 0 deg'
        """
        if self.pose is None:
            return "a snapshot's configuration"
        return pose_text(self.pose, self.pose_names, self.angle_names, self.length_unit)

    def __repr__(self) -> str:
        """A few lines: what was analysed where, the verdict and the factored superbracket
        (``print(report)`` gives the whole report).

        Returns
        -------
        str

        Examples
        --------
        >>> from screwkit.interface.report import analyze
        >>> analyze("h4", [0, 0, -750, 0.3])  # doctest: +ELLIPSIS
        AnalysisReport('H4' at x = 0 mm, y = 0 mm, z = -750 mm, phi = 17.19 deg)
          verdict: regular (dof 4): constraint order 2/2, global order 6/6
          superbracket: [ab, cd, ef, gh, ij, kj] = -[gikj][a b d ḟ][c g ḣ j]; constraint [gikj]; actuation ...
          print(report) for the whole report, report.to_dict() for its data
        """
        where = "" if self.pose is None else f" at {self.pose_words()}"
        if self.superbracket is None:
            superbracket = f"none ({self.superbracket_note})"
        else:
            result = self.superbracket
            found = "; ".join(
                f"{label} {c.factor}"
                for c, label, constant in zip(result.conditions, result.labels, result.constant, strict=True)
                if not constant
            )
            from ..gca.redundant_conditions import RedundantSuperbracket as Redundant

            superbracket = (
                result.statement()
                if isinstance(result, Redundant)
                else f"{self.diagram.line_text()} = {result.simplification.factored}"
            )
            superbracket += f"; {found}" if found else ""
        return "\n".join(
            [
                f"AnalysisReport({self.name!r}{where})",
                f"  verdict: {str(self.verdict).splitlines()[0]}",
                f"  superbracket: {superbracket}",
                "  print(report) for the whole report, report.to_dict() for its data",
            ]
        )

    def _repr_html_(self) -> str:
        """Jupyter: the report in sections, with tables of the wrenches, the diagram's points and
        the conditions (:func:`screwkit.interface.report_html.report_html`).

        Returns
        -------
        str
        """
        from .report_html import report_html

        tail = [*self._jacobian_lines()] if self.pose is not None else []
        if self.transmission is not None:
            tail += ["", *_transmission_lines(self.transmission)]
        return report_html(self, tail)

    def _jacobian_lines(self) -> list[str]:
        jac = self.jacobians
        out = [f"jacobians (Gosselin-Angeles): A χ̇ = B θ̇, χ = ({', '.join(self.pose_names)})"]
        if jac is None:
            return [*out, f"  {self.jacobians_note}"]
        head = "regular" if jac.type == "regular" else f"{jac.type} singularity"
        out.append(f"  type: {head}; rows (actuated joints): {', '.join(jac.actuated_joints)}")
        units = _determinant_units(jac, self.length_unit)
        det_a = f"det A = {jac.det_A:.6g}{units[0]}, " if jac.A.shape[0] == jac.A.shape[1] else ""
        out.append(f"  {det_a}det B = {jac.det_B:.6g}{units[1]}")
        out.append(
            f"  closeness (0 at a singularity): direct {jac.closeness['direct']:.3g}, "
            f"inverse {jac.closeness['inverse']:.3g}"
        )
        out.extend(f"  serial singularity of the limb of {name!r} (B_jj = 0)" for name in jac.serial_limbs)
        if "constraint" in self.verdict.labels and jac.type in ("regular", "inverse"):
            out.append(
                "  A only tests the nominal twists: the constraint singularity (a gained twist outside "
                "them) leaves it regular"
            )
        return out


def _transmission_lines(summary: dict[str, Any]) -> list[str]:
    out = ["transmission (in [0, 1]; 0 at a singularity)"]
    wrench, paper = summary["wrench"], summary["paper_004"]
    if wrench is not None:
        names = wrench["actuated_joints"]
        for key in ("input", "output"):
            values = ", ".join(f"{n} {v:.3g}" for n, v in zip(names, wrench[key], strict=True))
            out.append(f"  {key} (wrench-based): {values}")
        out.append(f"  LTI (wrench-based): {wrench['lti']:.3g}")
    if paper is not None:
        out.append(
            f"  paper 004: kappa {paper['input']:.3g}, zeta {paper['output']:.3g}, LTI eta {paper['lti']:.3g}"
        )
    out.append(f"  ({summary['note']})")
    return out


def _determinant_units(jac: Jacobians, unit: str) -> tuple[str, str]:
    """Units of det A and det B: the length to the number of rotations among the basis twists (A) and
    the actuated twists (B), when every row is a unit force (no units are claimed otherwise)."""
    assert jac.wrenches is not None and jac.twist_basis is not None and jac.analysis is not None
    if not unit or np.any(np.linalg.norm(jac.wrenches[:, :3], axis=-1) == 0):
        return "", ""
    twists = np.array([limb.actuated_twist for limb in jac.analysis.limbs]).reshape(-1, 6)

    def power(rows: Array) -> str:
        count = int(np.count_nonzero(np.linalg.norm(rows[:, :3], axis=-1)))
        return "" if count == 0 else f" {unit}" if count == 1 else f" {unit}^{count}"

    return power(jac.twist_basis), power(twists)


def _line_text(item: dict[str, Any], unit: str) -> str:
    if item.get("point") is None:
        if "direction" not in item:
            return item["kind"]
        return f"{item['kind']}, moment direction {_vector(item['direction'])}"
    return (
        f"{item['kind']}, direction {_vector(item['direction'])} through {_vector(item['point'])}"
        f"{' ' + unit if unit else ''}, pitch {item['pitch']:.3g}"
    )


def _vector(values: list[float]) -> str:
    """``(x, y, z)`` to 4 significant digits, a negative zero shown as 0 (``v + 0.0`` is +0.0 for -0.0).

    Examples
    --------
    >>> _vector([-0.0, 1.0, -2.5])
    '(0, 1, -2.5)'
    """
    return "(" + ", ".join(f"{v + 0.0:.4g}" for v in values) + ")"
