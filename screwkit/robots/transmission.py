"""Transmission indices from the actuation wrenches and the platform twists, for any mechanism.

The composer's own quantity (:attr:`screwkit.robots.posed.PosedMechanism.wrench_transmission`):
computed from the wrench systems and the Jacobians the posed mechanism already holds, for any
family or twist graph. :func:`transmission_ratio` is the virtual coefficient of one wrench and one
twist over its largest value (Wang, Wu & Liu 2010; Chen & Angeles 2007), :func:`wrench_transmission`
the input and output transmission per actuated joint and their LTI (range [0, 1]).
:class:`Transmission` is the one result class of every transmission index, with a leading batch
shape: per actuated joint here, per pose for paper 004's ``κ``, ``ζ`` and LTI ``η``
(:func:`screwkit.papers.paper_004.transmission`).

Examples
--------
>>> result = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]]).wrench_transmission
>>> result.input.shape, result.lti.shape, result.actuated_joints[:2]
((2, 4), (2,), ('A1', 'A2'))
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..core.jacobian_matrices import Jacobians
from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = ["Transmission", "transmission_ratio", "wrench_transmission"]


@dataclass(frozen=True)
class Transmission:
    """Input and output transmission and their local transmission index (LTI), with a leading
    batch shape ``...`` (one class for every transmission index of screwkit).

    Per actuated joint (:func:`wrench_transmission`: ``input`` and ``output`` of shape
    ``(..., n)``, ``actuated_joints`` naming the last axis) or per pose (paper 004's indices,
    :func:`screwkit.papers.paper_004.transmission`: ``input`` = ``κ`` and ``output`` = ``ζ`` of
    Eq. (15), ``lti`` = ``η`` of Eq. (16), each of shape ``(...)``, no joints named).

    Attributes
    ----------
    input : numpy.ndarray, shape (..., n) or (...)
        The input (motion) transmission: ``ITI_j`` per actuated joint, or ``κ = min_i |cos μ_i|``.
    output : numpy.ndarray, shape (..., n) or (...)
        The output (force) transmission: ``OTI_j`` per actuated joint, or ``ζ = |cos σ|``.
    lti : numpy.ndarray, shape (...)
        ``min`` of the inputs and outputs, in [0, 1]; NaN only where a pose was asked to be marked
        out of reach (``unreachable="nan"``).
    actuated_joints : tuple of str
        The actuated joints of the last axis of ``input`` and ``output`` (empty per pose).
    """

    input: np.ndarray
    output: np.ndarray
    lti: np.ndarray
    actuated_joints: tuple[str, ...] = ()

    def __repr__(self) -> str:
        """One line: the LTI (over a batch: its shape and range) and the joints.

        Returns
        -------
        str

        Examples
        --------
        >>> Transmission(np.array([0.5, 0.9]), np.array([1.0, 0.7]), np.array(0.5), ("A1", "A2"))
        Transmission(lti 0.5; per joint A1, A2)
        """
        lti = np.asarray(self.lti, dtype=float)
        if lti.ndim == 0:
            value = f"lti {lti:.3g}"
        else:
            low, high = np.nanmin(lti, initial=np.inf), np.nanmax(lti, initial=-np.inf)
            value = f"shape={lti.shape}, lti {low:.3g} to {high:.3g}"
        joints = f"; per joint {', '.join(self.actuated_joints)}" if self.actuated_joints else ""
        return f"Transmission({value}{joints})"

    @property
    def per_joint(self) -> bool:
        """bool: Whether ``input`` and ``output`` have an axis of actuated joints."""
        return np.ndim(self.input) > np.ndim(self.lti)

    @property
    def reachable(self) -> np.ndarray:
        """numpy.ndarray of bool, shape (...): False where the pose was out of reach (NaN there)."""
        return ~np.isnan(np.asarray(self.lti, dtype=float))

    @property
    def kappa(self) -> np.ndarray:
        """numpy.ndarray: Paper 004's name of :attr:`input` (``κ``, Eq. 15)."""
        return self.input

    @property
    def zeta(self) -> np.ndarray:
        """numpy.ndarray: Paper 004's name of :attr:`output` (``ζ``, Eq. 15)."""
        return self.output

    @property
    def eta(self) -> np.ndarray:
        """numpy.ndarray: Paper 004's name of :attr:`lti` (``η``, Eq. 16)."""
        return self.lti

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready.

        Returns
        -------
        dict
            ``input``, ``output``, ``lti`` (nested lists; NaN as None), then ``actuated_joints``
            (per joint) or ``reachable`` (per pose).

        Examples
        --------
        >>> Transmission(np.array([0.5, np.nan]), np.array([1.0, np.nan]), np.array([0.5, np.nan])).to_dict()
        {'input': [0.5, None], 'output': [1.0, None], 'lti': [0.5, None], 'reachable': [True, False]}
        """
        out = {"input": _plain(self.input), "output": _plain(self.output), "lti": _plain(self.lti)}
        if self.per_joint:
            return {**out, "actuated_joints": list(self.actuated_joints)}
        return {**out, "reachable": self.reachable.tolist()}


def _plain(values: Any) -> Any:
    """Nested lists of floats, NaN as None."""
    array = np.asarray(values, dtype=float)
    if array.ndim == 0:
        return None if math.isnan(array) else float(array)
    return [_plain(item) for item in array]


def transmission_ratio(
    wrench: Any, twist: Any, *, point: Any = None, length_scale: float = 1.0, rtol: float = B.DEFAULT_RTOL
) -> np.ndarray:
    """``|W ∘ T| / max``: the virtual coefficient of a wrench and a twist over its largest value.

    Two bounds, both from the reciprocal product ``W ∘ T = f·(v(q) + h ω)`` of a wrench
    ``W = (f; q × f + h f)`` (pitch ``h``, through ``q``) and a twist ``T = (ω; v_0)`` whose point
    ``q`` moves at ``v(q) = v_0 + ω × q``:

    * ``point`` given (the point of application ``q``: on the wrench's axis, or off it by what the
      wrench is defined up to, e.g. a limb's constraint wrenches, which do no work on the twist):
      the maximum over the directions of a force of the same size at ``q``, ``|f| |v(q) + h ω|``, so
      the ratio is the cosine of the pressure angle between the force and the velocity of its point
      of application (Wang, Wu & Liu, Mech. Mach. Theory 45(10), 2010, paper 004's ref. [38]; with
      ``q = B_i`` it is paper 004's ``|cos μ_i|``, Eq. 11);
    * ``point=None``: the maximum over the angle ``θ`` of the two axes at fixed distance ``d`` and
      pitches, ``|f| |ω| √((h_W + h_T)² + d²)``, from ``$_1 ∘ $_2 = (h_1 + h_2) cos θ - d sin θ``
      for unit screws (Chen & Angeles, "Generalized transmission index and transmission quality for
      spatial linkages", Mech. Mach. Theory 42(9), 2007). It needs no point but is 1 for any force
      normal to a rotation axis (planar linkages) except through it: give points there.

    A pure couple ``m`` against a twist: ``|m·ω| / (|m| |ω|)``; a force against a translation
    ``v``: ``|f·v| / (|f| |v|)``; a couple against a translation cannot act (ratio 0). Range [0, 1],
    invariant under rigid motions and changes of the length unit; 0 where the wrench does no work.

    Parameters
    ----------
    wrench, twist : array_like, shape (..., 6)
        Conventions of :mod:`screwkit.algebra.screw`.
    point : array_like, shape (..., 3), optional
        The wrench's point of application.
    length_scale : float
        Used only to decide which screws are couples or translations (relative to ``rtol``).
    rtol : float

    Returns
    -------
    numpy.ndarray, shape (...)

    Examples
    --------
    A unit force through ``(1, 0, 0)`` against a unit rotation about ``z`` through the origin: along
    ``y`` it pushes its point straight along its velocity (1); along ``(0, 1, 1)/√2`` at 45 degrees
    to it; along ``x`` not at all.

    >>> from screwkit.algebra import screw as S
    >>> spin = S.revolute_twist([0, 0, 1], [0, 0, 0])
    >>> forces = [S.force(f, [1, 0, 0]) for f in ([0, 1, 0], [0, 1, 1], [1, 0, 0])]
    >>> [round(float(transmission_ratio(f, spin, point=[1, 0, 0])), 6) for f in forces]
    [1.0, 0.707107, 0.0]
    """
    w = B.as_array(wrench, "wrench", (6,), symbolic=False).astype(float)
    t = B.as_array(twist, "twist", (6,), symbolic=False).astype(float)
    w, t = np.broadcast_arrays(w, t)
    f, m, omega, v = w[..., :3], w[..., 3:], t[..., :3], t[..., 3:]
    product = np.abs(np.sum(f * v, axis=-1) + np.sum(m * omega, axis=-1))
    nf, nm = np.linalg.norm(f, axis=-1), np.linalg.norm(m, axis=-1)
    nw, nv = np.linalg.norm(omega, axis=-1), np.linalg.norm(v, axis=-1)
    finite_wrench = nf > rtol * nm / length_scale
    finite_twist = nw > rtol * nv / length_scale
    safe_f, safe_w = np.where(finite_wrench, nf, 1.0), np.where(finite_twist, nw, 1.0)
    wrench_pitch = np.sum(f * m, axis=-1) / safe_f**2
    if point is not None:
        q = B.as_array(point, "point", (3,), symbolic=False).astype(float)
        moving = v + np.cross(omega, q) + wrench_pitch[..., None] * omega
        force_bound = nf * np.linalg.norm(moving, axis=-1)
    else:
        pitch_sum = wrench_pitch + np.sum(omega * v, axis=-1) / safe_w**2
        offset = np.cross(omega, v) / safe_w[..., None] ** 2 - np.cross(f, m) / safe_f[..., None] ** 2
        normal = np.cross(f / safe_f[..., None], omega / safe_w[..., None])
        sine = np.linalg.norm(normal, axis=-1)
        skew = np.abs(np.sum(offset * normal, axis=-1)) / np.where(sine > 1e-12, sine, 1.0)
        parallel = np.linalg.norm(np.cross(offset, f / safe_f[..., None]), axis=-1)
        force_bound = nf * nw * np.hypot(pitch_sum, np.where(sine > 1e-12, skew, parallel))
    bound = np.select(
        [finite_wrench & finite_twist, finite_wrench, finite_twist],
        [force_bound, nf * nv, nm * nw],
        default=0.0,
    )
    ratio = np.divide(product, bound, out=np.zeros_like(product), where=bound > 0)
    return np.minimum(ratio, 1.0)




def _driven_link_points(
    jacobians: Any, wrenches: np.ndarray, *, output: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Per limb, where the actuation wrench acts on the link the actuator drives (``output``: on the
    platform): the point of the wrench's line nearest (least squares) to the zero-pitch axes of that
    link's other joints in the limb (a spherical joint's three axes meet at its centre; a
    revolute's axis crosses the line), shape ``(..., n, 3)``, and whether one was found ``(..., n)``
    (no such axis, or all parallel to the line: the common-normal bound is used)."""
    analysis = jacobians.analysis
    table = analysis.table
    specs = {spec.name: spec for spec in table.specs}
    offsets = dict(zip(specs, np.cumsum([0] + [spec.dof for spec in table.specs[:-1]]).tolist(), strict=True))
    screws = np.asarray(table.screws, dtype=float)
    points = np.zeros((*wrenches.shape[:-1], 3))
    found = np.zeros(wrenches.shape[:-1], dtype=bool)
    for k, plan in enumerate(analysis.topology.limbs):
        actuated = specs[plan.actuated_joint]
        driven = actuated.parent if actuated.child == table.base else actuated.child
        if output:
            driven = table.platform
        rows = [
            offsets[name] + r
            for name in plan.joints
            if name != plan.actuated_joint and driven in (specs[name].parent, specs[name].child)
            for r in range(specs[name].dof)
        ]
        lines = screws[..., rows, :]  # (..., k, 6)
        s, s0 = lines[..., :3], lines[..., 3:]
        size = np.linalg.norm(s, axis=-1)
        pitch_part = np.abs(np.sum(s * s0, axis=-1))
        usable = (size > 0) & (pitch_part <= 1e-9 * size * np.linalg.norm(lines, axis=-1))
        safe = np.where(size > 0, size, 1.0)[..., None]
        unit, anchor = s / safe, np.cross(s, s0) / safe**2
        f, m = wrenches[..., k, :3], wrenches[..., k, 3:]
        nf = np.linalg.norm(f, axis=-1)[..., None]
        direction = f / np.where(nf > 0, nf, 1.0)
        foot = np.cross(f, m) / np.where(nf > 0, nf, 1.0) ** 2
        # x = foot + t d minimises sum_k |(x - r_k) x s_k|^2: t = sum d.M_k(r_k - foot) / sum d.M_k d
        along = np.sum(direction[..., None, :] * unit, axis=-1)  # d.s_k
        weight = np.where(usable, 1.0, 0.0)
        offset = anchor - foot[..., None, :]
        numerator = np.sum(weight * (np.sum(direction[..., None, :] * offset, axis=-1)
                                     - along * np.sum(unit * offset, axis=-1)), axis=-1)
        denominator = np.sum(weight * (1.0 - along**2), axis=-1)
        ok = (denominator > 1e-9) & (nf[..., 0] > 0)
        t = np.divide(numerator, denominator, out=np.zeros_like(numerator), where=ok)
        points[..., k, :] = foot + t[..., None] * direction
        found[..., k] = ok
    return points, found




def wrench_transmission(
    jacobians: Any, *, input_points: Any = None, output_points: Any = None
) -> Transmission:
    """A transmission index for any mechanism, from its actuation wrenches and platform twists.

    In the style of Wang, Wu & Liu (2010, paper 004's ref. [38]): with the actuation wrench ``w_j``
    of limb ``j`` (:func:`screwkit.core.wrenches.wrench_analysis`), the twist ``$_j`` of its actuated
    joint, and the platform twist ``$_Oj`` that actuator ``j`` alone produces (the twist of the
    basis reciprocal to every other actuation wrench: the null vector of ``A`` without row ``j``),

    * input transmission ``ITI_j = |w_j ∘ $_j| / max`` and output ``OTI_j = |w_j ∘ $_Oj| / max``,
      each with a bound of :func:`transmission_ratio`: for the input at ``input_points[j]``, by
      default the point where ``w_j`` acts on the link the actuator drives (the point of its line
      nearest the zero-pitch axes of that link's other joints; the common-normal bound where there
      is none); for the output likewise at ``output_points[j]``, by default where ``w_j`` meets the
      axes of the limb's joints on the platform (the common-normal bound where there are none, e.g.
      a limb ending in a prismatic joint, or on a sub-platform: there a planar force against a
      rotation normal to it always scores 1 but at the singularity, a known weakness of that bound);
    * ``LTI = min(min_j ITI_j, min_j OTI_j)`` (Eq. 16 of paper 004 has the same form).

    All three lie in [0, 1] and do not change under rigid motions or a change of length unit. A
    serial singularity (``B_jj = 0``) gives ``ITI_j = 0``; an actuation singularity (``A`` loses
    rank) gives ``OTI_j = 0`` for the limbs involved.

    Relation to paper 004 (derived; ``tests/papers/test_paper_004.py`` checks both). For a four-limb robot
    ``w_i`` is a force along the parallelogram (unit ``w_i``, through ``B_i``) and ``$_i`` the
    rotation about ``u_i`` through ``A_i`` (pitches 0). With the point of application ``B_i``
    (``posed.wrench_transmission`` passes it), ``v(B_i) = b u_i × v_i`` and
    ``ITI_i = |w_i·(u_i × v_i)| = |cos μ_i|`` (Eq. 11): ``min_i ITI_i`` *is* paper 004's ``κ``.
    Without a point, the common-normal bound gives ``ITI_i = |sin ∠(w_i, u_i)|``
    ``= √(κ_i² + (w_i·v_i)²) ≥ κ_i`` (``u_i``, ``v_i``, ``u_i × v_i`` orthonormal), equal to
    ``κ_i`` exactly where ``w_i ⟂ v_i``. Neither depends on the representative of ``w_i`` modulo
    the limb's constraint couple ``u_i × w_i`` (it does no work on ``$_i``, and adding it shifts the
    force's line along ``u_i``, which moves neither ``B_i`` nor the common normal). The output
    indices are not paper 004's ``ζ`` (the pressure angle between the two sub-platforms' planes,
    Eq. 13): ``OTI_j`` uses the actuation wrench as the core gives it (a unit force; for a limb with
    constraint wrenches ``$_Oj`` is reciprocal to them, the bound is not, so it depends on that
    representative).

    Parameters
    ----------
    jacobians : Jacobians
        From :func:`screwkit.core.jacobians.jacobians_from_wrenches` or ``posed.jacobians``; ``A`` must
        be square (one actuator per degree of freedom of the basis).
    input_points, output_points : array_like, shape (..., n, 3), optional
        Points of application of the actuation wrenches on the actuated link and on the platform,
        in the order of ``jacobians.actuated_joints``.

    Returns
    -------
    Transmission
        Per actuated joint: ``input`` (``ITI_j``) and ``output`` (``OTI_j``) of shape ``(..., n)``,
        ``lti`` of shape ``(...)``, ``actuated_joints``.

    Raises
    ------
    ScrewkitTypeError
        Not a Jacobians from a wrench analysis.
    ScrewkitValueError
        ``A`` is not square, or points of the wrong shape.

    Examples
    --------
    The slider-crank of :func:`screwkit.core.jacobians.jacobians_from_wrenches` (crank 1, coupler 2)
    at ``θ = 60°``: the coupler pushes the crank pin nearly along the pin's velocity (input 0.997,
    at the pin) and the slider at ``asin(√3/4)`` to its path (output ``√13/4 = 0.901``).

    >>> from screwkit.core.jacobians import jacobians_from_wrenches
    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> pin = [0.5, np.sqrt(3.0) / 2, 0.0]
    >>> slider = [0.5 + np.sqrt(4.0 - 0.75), 0.0, 0.0]
    >>> G = twist_graph("ground", "slider", [
    ...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("crank", "coupler", revolute("R1", [0, 0, 1], pin)),
    ...     ("coupler", "slider", revolute("R2", [0, 0, 1], slider)),
    ...     ("ground", "slider", prismatic("P", [1, 0, 0]))], dof=1)
    >>> jac = jacobians_from_wrenches(wrench_analysis(G), [[0, 0, 0, 1, 0, 0]])
    >>> result = wrench_transmission(jac, input_points=[pin])
    >>> result.input.round(6).tolist(), result.output.round(6).tolist(), round(float(result.lti), 6)
    ([0.997131], [0.901388], 0.901388)
    """
    if not isinstance(jacobians, Jacobians) or jacobians.analysis is None:
        raise ScrewkitTypeError(
            "Expected `jacobians` to be a Jacobians from a wrench analysis (jacobians_from_wrenches), got "
            f"{type(jacobians).__name__}."
        )
    forward = np.asarray(jacobians.A)
    n, dof = forward.shape[-2:]
    if n != dof:
        raise ScrewkitValueError(
            f"Expected a square A (one actuator per twist of the basis) for the output transmission, got "
            f"A of shape {(n, dof)}"
            + (
                " (redundantly actuated: no platform twist comes from one actuator alone, so OTI_j does not "
                "exist)."
                if n > dof
                else "."
            )
        )
    wrenches = np.asarray(jacobians.wrenches)
    # what the driven link receives: the wrench, or in a compound leg analysed as a whole its part
    # on the actuator's own branch (screwkit.core.wrench_systems.WrenchAnalysis.branch_rows)
    branches = np.asarray(jacobians.analysis.branch_rows, dtype=float)
    twists = np.asarray(jacobians.analysis.actuated_twists, dtype=float)
    basis = np.asarray(jacobians.twist_basis)
    points = [None if p is None else B.as_array(p, name, (None, 3), symbolic=False)
              for name, p in (("input_points", input_points), ("output_points", output_points))]
    for name, array in zip(("input_points", "output_points"), points, strict=True):
        if array is not None and array.shape[-2] != n:
            raise ScrewkitValueError(f"Expected `{name}` to have shape (..., {n}, 3), got {array.shape}.")
    if points[0] is None and n:
        found, located = _driven_link_points(jacobians, branches)
        iti = np.where(
            located,
            transmission_ratio(branches, twists, point=found),
            transmission_ratio(branches, twists),
        )
    else:
        iti = transmission_ratio(branches, twists, point=points[0]) if n else np.zeros(forward.shape[:-1])
    iti = np.where(np.asarray(jacobians.serial), 0.0, iti)
    if n == 0:
        return Transmission(iti, iti, np.ones(forward.shape[:-2]), jacobians.actuated_joints)
    others = np.stack([np.delete(forward, j, axis=-2) for j in range(n)], axis=-3)  # (..., n, n-1, dof)
    if n > 1:
        scale = np.linalg.norm(others, axis=-2, keepdims=True)  # column scaling: mixed units
        scale = np.where(scale > 0, scale, 1.0)
        coefficients = np.linalg.svd(others / scale)[2][..., -1, :] / scale[..., 0, :]
    else:
        coefficients = np.ones((*forward.shape[:-2], 1, 1))
    output_twists = np.einsum("...jk,...kc->...jc", coefficients, basis)
    if points[1] is None:
        found, located = _driven_link_points(jacobians, wrenches, output=True)
        oti = np.where(
            located,
            transmission_ratio(wrenches, output_twists, point=found),
            transmission_ratio(wrenches, output_twists),
        )
    else:
        oti = transmission_ratio(wrenches, output_twists, point=points[1])
    lti = np.minimum(iti.min(axis=-1), oti.min(axis=-1))
    return Transmission(iti, oti, lti, jacobians.actuated_joints)


