"""Enclosures of a loop-closure mechanism's kinematics and actuation condition over boxes of pose
space (:class:`LoopClosureModel`). One algorithm: the Krawczyk operator on the loop equations, then
the actuation determinant over the joint boxes it proves.

A mechanism from :func:`screwkit.mechanism` has no closed form: its joint values at a pose are found
by continuation from the reference configuration (:mod:`screwkit.core.loop_closure`). Certification
encloses them instead. With the platform placed at a pose ``u`` (its coordinates fix its whole
pose), each limb, a serial chain from the base to the platform, closes on its own:

``F_k(θ_k, u) = (vee(R_k(θ_k) R(u)ᵀ - R(u) R_k(θ_k)ᵀ), p_k(θ_k) - p(u)) = 0``,

``(R_k, p_k) = Π exp(ŝ_j θ_j)`` the product of exponentials of the limb's joint screws at the
reference (Murray, Li & Sastry 1994, Eq. 3.22; a spherical joint's rotation offset placed before its
three exponentials, as in :mod:`screwkit.core.kinematic_model`) and ``(R(u), p(u))`` the platform's
displacement at ``u``. Over a box ``U`` of poses: the continuation's joint values ``y`` at the box's
centre (the branch connected to the reference), a box ``X ∋ y`` inflated until the Krawczyk operator
maps it into its interior (:mod:`screwkit.analysis.krawczyk`, epsilon inflation after Rump), which
proves that for every pose of ``U`` exactly one ``θ_k ∈ X`` closes limb ``k`` and that the limb's
Jacobian, hence its twists, is regular there: the pose is reachable and not serial singular. The
trace of ``R_k R(u)ᵀ`` is proved positive over ``X × U``, so the zero closes the loop (a rotation by
π would also zero the skew part).

The actuation condition: the wrench of limb ``k``'s actuated joint is reciprocal to the limb's passive
twists, ``c_k`` their generalised cross product (the cofactors of the passive twists, so that
``c_k·t = det[passive; t]``, nonzero on the actuated twist where the limb is regular); the actuation
wrenches are dependent iff ``D = det[c_1 … c_d] = 0`` (the global wrench system loses rank: an
actuation singularity). ``D`` is enclosed over the joint boxes in a centred form, row by row
(``D`` is linear in each row): ``D(θ) ∈ D(m) + Σ_k det[c_<k(m), ∇c_k(X_k) (X_k - m_k), c_>k(X)]``.

Covered (:meth:`LoopClosureModel.of` refuses the rest, naming the reason): a platform joined to the
base by ``d`` limbs, each a serial chain of R, P, H, C, U and S joints (lower pairs with screws; no
Π parallelogram, whose motion is not a product of its screws' exponentials) with exactly ``d`` joint
variables and one actuated joint of one variable, where ``d`` is the number of the loop equations
that are not identically zero: 6 in space, 3 for a planar mechanism in a plane ``z = const`` with
its axes along ``z`` (its out-of-plane equations are zero exactly, and so are its planarity
wrenches' changes: no constraint singularity), and coordinates along the base axes that fix the
platform's pose. No limb then has a constraint wrench nor an internal motion, so there is no
constraint singularity to exclude. Witnesses are signs of ``D`` at points whose joint values are
enclosed from their box's ``X`` (the same branch).

Examples
--------
>>> rpr = sk.mechanism("examples/planar_3rpr.toml")  # a planar 3-RPR snapshot
>>> model = LoopClosureModel.of(rpr)
>>> model.dimension, model.limbs, sorted(model.functions())
(3, 3, ['actuation', 'serial:1', 'serial:2', 'serial:3'])
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ..algebra.rigid_motions import rotation_log
from ..core.loop_closure import close_loops
from ..exceptions import ScrewkitValueError
from .interval_motions import Vector, cofactors, determinant
from .intervals import Enclosure
from .krawczyk import implicit_rates, interval_matrix_vector, krawczyk, matrix_times_interval
from .serial_limbs import Group, evaluate_group, grouped, limbs_of, platform_constants

__all__ = ["COVERED_JOINTS", "LoopClosureModel"]

Array = np.ndarray

#: Joint types whose motion is the product of their screws' exponentials.
COVERED_JOINTS = ("R", "P", "H", "C", "U", "S")
#: Rounds of epsilon inflation before a box is left unproved.
INFLATIONS = 5
#: Krawczyk iterations narrowing a point's joint values from its box's.
POINT_ITERATIONS = 3
#: Boxes whose verified joint values are remembered (points are evaluated within their box).
MEMO_BOXES = 65536
#: Bisection steps refining a witness (each a Krawczyk enclosure at the points): the bracket
#: shrinks by 2⁻¹⁶.
WITNESS_STEPS = 16

_STATEMENTS = {
    "actuation": "det[c_1 ... c_d] = 0, c_k the wrench of limb k's actuated joint (reciprocal to its "
    "passive joints' twists): the actuation wrenches are dependent, an actuation singularity",
    "serial": "limb {i}'s loop closure not proved unique and regular over the box (Krawczyk): at its "
    "reach or serial singular",
}


def _refuse(mechanism: Any, reason: str) -> ScrewkitValueError:
    return ScrewkitValueError(
        "Expected `mechanism` among what certification covers (loop-closure mechanisms: a platform on d "
        f"serial limbs of {', '.join(COVERED_JOINTS)} joints, each with d joint variables and one "
        f"actuated, coordinates along the base axes fixing its pose), got "
        f"{getattr(mechanism, 'name', type(mechanism).__name__)} ({reason})."
    )


class LoopClosureModel:
    """The Krawczyk enclosure of a loop-closure mechanism (module docstring); build with :meth:`of`.

    Attributes
    ----------
    name : str
    pose_names : tuple of str
    limbs : int
        ``d``.
    dimension : int
        ``d``, the loop equations per limb (6 in space, 3 in the plane).
    kinematics : GraphKinematics
    witness_steps : int
        :data:`WITNESS_STEPS`, read by :func:`screwkit.analysis.certify.certify`.
    """

    def __init__(self, mechanism: Any, groups: list[Group], live: list[int], platform: dict[str, Any]):
        self.name = mechanism.name
        self.pose_names = tuple(mechanism.pose_names)
        self.kinematics = mechanism.parameters
        self.limbs = sum(len(group.members) for group in groups)
        self.dimension = len(live)
        self._groups = groups
        self._live = live
        self._platform = platform
        self._spherical = sorted({j for group in groups for f in group.factors for j in f.joints})
        self._memo: dict[bytes, tuple[Array, ...]] = {}
        self.witness_steps = WITNESS_STEPS

    @classmethod
    def of(cls, mechanism: Any, options: Mapping[str, Any] | None = None) -> LoopClosureModel:
        """The model of a mechanism from :func:`screwkit.mechanism`, or a one-line refusal naming
        what is not covered.

        Parameters
        ----------
        mechanism : Mechanism
            Of the ``loop_closure`` family.
        options : mapping, optional
            Must be empty (the branch is the reference's).

        Returns
        -------
        LoopClosureModel

        Raises
        ------
        ScrewkitValueError
            For a mechanism outside the covered class (module docstring), or options.

        Examples
        --------
        >>> LoopClosureModel.of(sk.mechanism(load_mechanism("h4").twist_graph()))
        Traceback (most recent call last):
        ...
        screwkit.exceptions.ScrewkitValueError: Expected `mechanism` among what certification covers ...
        """
        if getattr(mechanism, "family", None) != "loop_closure":
            raise _refuse(mechanism, f"family {getattr(mechanism, 'family', None)!r}, not loop_closure")
        if options:
            raise ScrewkitValueError(
                f"Expected no `mode` for a loop-closure mechanism, got {dict(options)!r}."
            )
        kinematics = mechanism.parameters
        model, coordinates = kinematics.model, kinematics.coordinates
        if kinematics.point_task or not kinematics.complete:
            raise _refuse(mechanism, "its coordinates do not fix the platform's whole pose")
        directions = np.asarray(coordinates.directions, dtype=float)
        axes = np.round(directions)  # the axes the names say (the directions agree to 1e-12)
        along = np.isin(axes, (0.0, 1.0)).all() and bool((axes.sum(axis=1) == 1.0).all())
        if not along or np.abs(directions - axes).max() > 1e-12 or np.any(kinematics.angle_offsets):
            raise _refuse(mechanism, f"coordinates {coordinates.names} are not along the base axes")
        odd = sorted({kind for kind in model.types.values() if kind not in COVERED_JOINTS})
        if odd:
            raise _refuse(
                mechanism, f"joints of type {', '.join(odd)}: no product of exponentials to enclose"
            )
        try:
            limbs = limbs_of(mechanism)
        except ScrewkitValueError as error:
            raise _refuse(mechanism, str(error)) from None
        platform = platform_constants(model, coordinates)
        groups = grouped(limbs)
        live = cls._live_equations(mechanism, groups, platform)
        return cls(mechanism, groups, live, platform)

    @staticmethod
    def _live_equations(mechanism: Any, groups: list[Group], platform: dict[str, Any]) -> list[int]:
        """The loop equations that are not exact zeros (read off a dry run at the reference), checked
        to be as many as each limb's variables and as the limbs."""
        pose = np.asarray(mechanism.default_pose, dtype=float)[None]
        lives, count = set(), 0
        for group in groups:
            size, d = group.columns.shape
            count += size
            zeros = np.zeros((size, d))
            turns = {j: np.zeros((1, 3)) for f in group.factors for j in f.joints}
            residual, _, twists = evaluate_group(
                group,
                zeros,
                zeros,
                np.repeat(pose, size, 0),
                np.repeat(pose, size, 0),
                platform,
                turns,
                twists=True,
            )
            live = tuple(j for j, e in enumerate(residual) if e is not None)
            moving = {j for t in twists for j, e in enumerate(t) if e is not None}
            if len(live) != d or not moving <= set(live):
                raise _refuse(
                    mechanism,
                    f"a limb through {group.columns.shape[1]} joint variables for {len(live)} "
                    "loop equations: an internal motion or a missing freedom",
                )
            lives.add(live)
        if len(lives) != 1 or count != len(next(iter(lives))):
            raise _refuse(mechanism, f"{count} limbs for loop equations {sorted(lives)} per limb")
        return list(next(iter(lives)))

    def functions(self) -> dict[str, str]:
        """The functions enclosed, with what their vanishing (or their proof failing) means: the
        limbs' closures and the actuation determinant; no limb has a constraint wrench.

        Returns
        -------
        dict of str to str
            ``"actuation"``, ``"serial:1"`` .. ``"serial:<limbs>"``.

        Examples
        --------
        >>> sorted(LoopClosureModel.of(sk.mechanism("examples/planar_3rpr.toml")).functions())[:2]
        ['actuation', 'serial:1']
        """
        out = {"actuation": _STATEMENTS["actuation"]}
        for i in range(self.limbs):
            out[f"serial:{i + 1}"] = _STATEMENTS["serial"].format(i=i + 1)
        return out

    def evaluate(self, pose: list[Enclosure], *, singular: bool = True) -> dict[str, Enclosure]:
        """Enclose the functions over a batch of boxes of pose space: ``serial:k`` is ``[1, 1]`` where
        limb ``k``'s closure is proved unique and regular over the box (else the whole line: never
        proved unreachable), ``actuation`` encloses ``D`` where every limb's is.

        Parameters
        ----------
        pose : list of Enclosure
            The pose coordinates over the boxes (API units).
        singular : bool, default True
            Also the actuation function.

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> rpr = sk.mechanism("examples/planar_3rpr.toml")  # a planar 3-RPR snapshot
        >>> model = LoopClosureModel.of(rpr)
        >>> centre = np.array([0.55, 0.4, 0.0])
        >>> box = Enclosure.variables((centre - 0.001)[None], (centre + 0.001)[None], gradient=False)
        >>> values = model.evaluate(box)
        >>> bool(values["serial:1"].lo[0] > 0 and values["actuation"].excludes_zero()[0])
        True
        """
        lo, hi = np.stack([p.lo for p in pose], axis=1), np.stack([p.hi for p in pose], axis=1)
        xlo, xhi, proved, turns = self._verified(lo, hi)
        return self._functions_over(xlo, xhi, proved, turns, lo, hi, singular)

    def evaluate_points(self, points: list[Enclosure], boxes: list[Enclosure]) -> dict[str, Enclosure]:
        """Enclose the functions at points, each with the joint values of its box's branch: the box's
        verified joint box narrowed by :data:`POINT_ITERATIONS` Krawczyk steps at the point.

        Parameters
        ----------
        points : list of Enclosure
            The points' coordinates (degenerate boxes).
        boxes : list of Enclosure
            The box holding each point.

        Returns
        -------
        dict of str to Enclosure

        Examples
        --------
        >>> model = LoopClosureModel.of(sk.mechanism("examples/planar_3rpr.toml"))
        >>> point = np.array([[0.5505, 0.3995, 0.0002]])
        >>> box = Enclosure.variables(np.array([[0.549, 0.399, -0.001]]), np.array([[0.551, 0.401, 0.001]]),
        ...                           gradient=False)
        >>> d = model.evaluate_points(Enclosure.variables(point, point, gradient=False), box)["actuation"]
        >>> float(d.hi[0] - d.lo[0]) < 1e-4 * float(abs(d.lo[0]))  # the point's D, sign certified
        True
        """
        plo, phi = np.stack([p.lo for p in points], axis=1), np.stack([p.hi for p in points], axis=1)
        blo, bhi = np.stack([p.lo for p in boxes], axis=1), np.stack([p.hi for p in boxes], axis=1)
        xlo, xhi, proved, turns = self._verified(blo, bhi)
        xlo, xhi, proved = xlo.copy(), xhi.copy(), proved.copy()
        for group in self._groups:
            members = list(group.members)
            rows = np.flatnonzero(proved[:, members].all(axis=1))
            if not rows.size:
                continue
            a, b = self._stacked(group, xlo[rows]), self._stacked(group, xhi[rows])
            size = len(members)
            tile = (np.tile(plo[rows], (size, 1)), np.tile(phi[rows], (size, 1)))
            a, b = self._narrowed(group, a, b, *tile, self._turns(turns[rows]))
            empty = np.any(a > b, axis=1).reshape(size, len(rows))  # cannot happen inside a verified box
            for i, member in enumerate(members):
                proved[rows[empty[i]], member] = False
            self._unstack(group, xlo, rows, a)
            self._unstack(group, xhi, rows, b)
        return self._functions_over(xlo, xhi, proved, turns, plo, phi, True)

    def _narrowed(
        self, group: Group, a: Array, b: Array, lo: Array, hi: Array, turns: dict[str, Array]
    ) -> tuple[Array, Array]:
        """Joint boxes ``[a, b]`` (holding the unique zero for each pose of ``[lo, hi]``) narrowed by
        :data:`POINT_ITERATIONS` Krawczyk steps, each intersected with the last box."""
        for _ in range(POINT_ITERATIONS):
            y = np.clip(0.5 * (a + b), a, b)
            f = self._residual(group, y, y, lo, hi, turns)
            jacobian, _ = self._jacobian(group, a, b, lo, hi, turns)
            k_lo, k_hi, _ = krawczyk(f, jacobian, y, (a, b))
            a, b = np.maximum(a, k_lo), np.minimum(b, k_hi)
        return a, b

    def _stacked(self, group: Group, values: Array) -> Array:
        """``(B, n)`` model columns → ``(g B, d)``, the group's members one after another."""
        return np.concatenate([values[:, columns] for columns in group.columns])

    @staticmethod
    def _unstack(group: Group, values: Array, rows: Array, stacked: Array) -> None:
        for i, part in enumerate(np.split(stacked, len(group.members))):
            values[np.ix_(rows, group.columns[i])] = part

    def _turns(self, turns: Array) -> dict[str, Array]:
        return {name: turns[:, 3 * i : 3 * i + 3] for i, name in enumerate(self._spherical)}

    def _functions_over(
        self, xlo: Array, xhi: Array, proved: Array, turns: Array, lo: Array, hi: Array, singular: bool
    ) -> dict[str, Enclosure]:
        out = {
            f"serial:{k + 1}": Enclosure(
                np.where(proved[:, k], 1.0, -np.inf), np.where(proved[:, k], 1.0, np.inf)
            )
            for k in range(self.limbs)
        }
        if singular:
            d_lo, d_hi = np.full(len(lo), -np.inf), np.full(len(lo), np.inf)
            rows = np.flatnonzero(proved.all(axis=1))
            if rows.size:
                value = self._condition(xlo[rows], xhi[rows], lo[rows], hi[rows], turns[rows])
                d_lo[rows], d_hi[rows] = value.lo, value.hi
            out["actuation"] = Enclosure(d_lo, d_hi)
        return out

    def _verified(self, lo: Array, hi: Array) -> tuple[Array, Array, Array, Array]:
        """Per box: the joint boxes ``(B, n)`` (model columns), which limbs are proved ``(B, limbs)``
        and the spherical joints' offsets as rotation vectors ``(B, 3 s)``, remembered per box."""
        keys = [lo[i].tobytes() + hi[i].tobytes() for i in range(len(lo))]
        missing = [i for i, key in enumerate(keys) if key not in self._memo]
        if missing:
            found = self._prove(lo[missing], hi[missing])
            if len(self._memo) + len(missing) > MEMO_BOXES:
                self._memo.clear()
            for j, i in enumerate(missing):
                self._memo[keys[i]] = tuple(part[j] for part in found)
        rows = [self._memo[key] for key in keys]
        xlo, xhi, proved, turns = (np.array([row[n] for row in rows]) for n in range(4))
        return xlo, xhi, proved, turns

    def _prove(self, lo: Array, hi: Array) -> tuple[Array, Array, Array, Array]:
        """The Krawczyk proof per limb from the continuation's joint values at the boxes' centres."""
        model = self.kinematics.model
        kinematics = self.kinematics  # its coordinates' angle offsets are zero (of())
        closed = close_loops(model, kinematics.task, kinematics.task.scaled_targets(0.5 * (lo + hi)))
        theta, offsets = model.recentred(closed.theta, closed.offsets)
        turns = np.concatenate(
            [rotation_log(offsets[key][:, :3, :3]) for key in self._spherical] or [np.zeros((len(lo), 0))],
            axis=1,
        )
        xlo, xhi = np.full(theta.shape, -np.inf), np.full(theta.shape, np.inf)
        proved = np.zeros((len(lo), self.limbs), dtype=bool)
        rows = np.flatnonzero(closed.reached)
        for group in self._groups:
            size = len(group.members)
            a, b, ok = self._inflate(
                group,
                self._stacked(group, theta[rows]),
                np.tile(lo[rows], (size, 1)),
                np.tile(hi[rows], (size, 1)),
                self._turns(turns[rows]),
            )
            self._unstack(group, xlo, rows, a)
            self._unstack(group, xhi, rows, b)
            for i, member in enumerate(group.members):
                proved[rows, member] = np.split(ok, size)[i]
        return xlo, xhi, proved, turns

    def _inflate(
        self, group: Group, y: Array, lo: Array, hi: Array, turns: dict[str, Array]
    ) -> tuple[Array, Array, Array]:
        """Epsilon inflation (Rump): ``X = y ± 2|C F(y, U)|``, then while ``K(X) ⊄ int X`` the hull of
        ``K(X)`` and ``X`` widened by half about ``y``; the proved boxes end as ``K(X) ∩ X``."""
        f_lo, f_hi = self._residual(group, y, y, lo, hi, turns)
        (j_lo, j_hi), _ = self._jacobian(group, y, y, lo, hi, turns)
        middle = 0.5 * (j_lo + j_hi)
        usable = np.all(np.isfinite(middle), axis=(1, 2))
        middle = np.where(usable[:, None, None], middle, np.eye(y.shape[1]))
        usable &= np.abs(np.linalg.det(middle)) > 1e-12
        inverse = np.linalg.inv(np.where(usable[:, None, None], middle, np.eye(y.shape[1])))
        step = np.abs(np.einsum("bij,bj->bi", inverse, 0.5 * (f_lo + f_hi)))
        step += np.einsum("bij,bj->bi", np.abs(inverse), 0.5 * (f_hi - f_lo))
        floor = 1e-12 * (1.0 + np.abs(y))
        a, b = y - 2.0 * step - floor, y + 2.0 * step + floor
        out_lo, out_hi = np.full_like(y, -np.inf), np.full_like(y, np.inf)
        proved = np.zeros(len(y), dtype=bool)
        active = np.flatnonzero(usable & np.all(np.isfinite(a) & np.isfinite(b), axis=1))
        for _ in range(INFLATIONS):
            if not active.size:
                break
            jacobian, trace = self._jacobian(
                group,
                a[active],
                b[active],
                lo[active],
                hi[active],
                turns,
                (active, len(y) // len(group.members)),
            )
            k_lo, k_hi, ok = krawczyk(
                (f_lo[active], f_hi[active]), jacobian, y[active], (a[active], b[active])
            )
            ok &= trace.lo > 0  # the closure is a rotation by less than π/2: not a spurious zero at π
            done = active[ok]
            out_lo[done] = np.maximum(k_lo[ok], a[done])
            out_hi[done] = np.minimum(k_hi[ok], b[done])
            proved[done] = True
            rest, k_lo, k_hi = active[~ok], k_lo[~ok], k_hi[~ok]
            # drop the boxes whose K(X) is no longer finite or grows past twice X (no contraction)
            finite = np.all(
                np.isfinite(k_lo) & np.isfinite(k_hi) & (k_hi - k_lo <= 2.0 * (b[rest] - a[rest])), axis=1
            )
            rest, k_lo, k_hi = rest[finite], k_lo[finite], k_hi[finite]
            centre = y[rest]
            a[rest] = centre - 1.5 * np.maximum(centre - np.minimum(k_lo, a[rest]), 0.0) - floor[rest]
            b[rest] = centre + 1.5 * np.maximum(np.maximum(k_hi, b[rest]) - centre, 0.0) + floor[rest]
            active = rest
        done = np.flatnonzero(proved)
        if done.size:  # one more Krawczyk step narrows the proved boxes (each holds every zero)
            sub = (done, len(y) // len(group.members))
            a, b = out_lo[done], out_hi[done]
            jacobian, _ = self._jacobian(group, a, b, lo[done], hi[done], turns, sub)
            k_lo, k_hi, _ = krawczyk((f_lo[done], f_hi[done]), jacobian, y[done], (a, b))
            out_lo[done], out_hi[done] = np.maximum(a, k_lo), np.minimum(b, k_hi)
        return out_lo, out_hi, proved

    def _residual(
        self, group: Group, a: Array, b: Array, lo: Array, hi: Array, turns: dict[str, Array]
    ) -> tuple[Array, Array]:
        residual, _, _ = evaluate_group(group, a, b, lo, hi, self._platform, turns)
        live = [residual[j] for j in self._live]
        return np.stack([r.lo for r in live], axis=1), np.stack([r.hi for r in live], axis=1)  # type: ignore[union-attr]

    def _jacobian(
        self,
        group: Group,
        a: Array,
        b: Array,
        lo: Array,
        hi: Array,
        turns: dict[str, Array],
        rows: tuple[Array, int] | None = None,
    ) -> tuple[tuple[Array, Array], Enclosure]:
        residual, trace, _ = evaluate_group(
            group, a, b, lo, hi, self._platform, turns, gradient=True, rows=rows
        )
        live = [residual[j] for j in self._live]
        d = a.shape[1]
        glo = np.stack([_gradient(r, d)[0] for r in live], axis=1)
        ghi = np.stack([_gradient(r, d)[1] for r in live], axis=1)
        return (glo, ghi), trace

    def _condition(self, xlo: Array, xhi: Array, lo: Array, hi: Array, turns: Array) -> Enclosure:
        """``D`` over the pose boxes (module docstring): each wrench row as a function of the pose,
        ``c_k(u_c) + ∇_u c_k·[-r, r]`` with ``∇_u c_k = ∇_θ c_k(X_k) dθ_k/du`` and ``dθ_k/du`` enclosed
        by :func:`~screwkit.analysis.krawczyk.implicit_rates` over ``X_k × U``, intersected with
        ``c_k(X_k)``; the matrix preconditioned by ``P = W(m)⁻¹`` (a float matrix):
        ``D = det(W P) / det(P)``, both determinants of nearly diagonal interval matrices."""
        centre = np.clip(0.5 * (lo + hi), lo, hi)
        radius = np.where(hi > lo, np.nextafter(np.maximum(centre - lo, hi - centre), np.inf), 0.0)
        offsets = self._turns(turns)
        rows: list[Vector] = [[] for _ in range(self.limbs)]
        centres: list[Vector] = [[] for _ in range(self.limbs)]
        derivatives: list[list[tuple[Array, Array] | None]] = [[] for _ in range(self.limbs)]
        for group in self._groups:
            size = len(group.members)
            a, b = self._stacked(group, xlo), self._stacked(group, xhi)
            tile = (np.tile(lo, (size, 1)), np.tile(hi, (size, 1)))
            middle = np.tile(centre, (size, 1))
            ca, cb = self._narrowed(group, a, b, middle, middle, offsets) if radius.max() > 0 else (a, b)
            _, _, twists = evaluate_group(group, ca, cb, middle, middle, self._platform, offsets, twists=True)
            at_centre = self._wrench(group, twists)
            spread: list[Array | None] = [None] * len(at_centre)
            slopes: list[tuple[Array, Array] | None] = [None] * len(at_centre)  # ∂c/∂u over U, (g B, n)
            over: Vector = [None] * len(at_centre)
            if radius.max() > 0:
                _, _, twists = evaluate_group(
                    group, a, b, *tile, self._platform, offsets, gradient=True, twists=True
                )
                over = self._wrench(group, twists)
                residual, _, _ = evaluate_group(
                    group, a, b, *tile, self._platform, offsets, gradient=True, pose_gradient=True
                )
                live = [residual[j] for j in self._live]
                d = a.shape[1]
                glo = np.stack([_gradient(r, d + lo.shape[1])[0] for r in live], axis=1)
                ghi = np.stack([_gradient(r, d + lo.shape[1])[1] for r in live], axis=1)
                rates = implicit_rates((glo[..., :d], ghi[..., :d]), (glo[..., d:], ghi[..., d:]))
                sides = np.tile(radius, (size, 1))
                for i, c in enumerate(over):
                    if c is not None:
                        r_lo, r_hi = interval_matrix_vector(
                            np.swapaxes(rates[0], 1, 2), np.swapaxes(rates[1], 1, 2), *_gradient(c, d)
                        )
                        with np.errstate(invalid="ignore"):
                            total = np.nextafter(
                                (np.maximum(np.abs(r_lo), np.abs(r_hi)) * sides).sum(axis=1)
                                * (1.0 + 2.0**-40),
                                np.inf,
                            )
                        spread[i] = np.where(np.isnan(total), np.inf, total)
                        slopes[i] = (r_lo, r_hi)
            for m, member in enumerate(group.members):
                part = slice(m * len(lo), (m + 1) * len(lo))
                rows[member] = [
                    _centred(c, e, s, part) for c, e, s in zip(at_centre, over, spread, strict=True)
                ]
                centres[member] = [
                    None if c is None else Enclosure(c.lo[part], c.hi[part]) for c in at_centre
                ]
                derivatives[member] = [None if s is None else (s[0][part], s[1][part]) for s in slopes]
        # the mean-value form in the pose, D(u_c) + Σ_l ∂D/∂u_l(U) [-r_l, r_l] with
        # ∂D/∂u_l = Σ_k det(W with row k := ∂c_k/∂u_l) (D is linear in each row), intersected with
        # the direct determinant, preconditioned: det(W P) / det(P), P = W(u_c)⁻¹ a float matrix
        # (the rows c_k P nearly the unit rows)
        d, count = self.dimension, len(lo)
        value = determinant(centres)
        assert value is not None
        width = np.zeros(count)
        minors = (
            [cofactors([rows[j] for j in range(d) if j != k]) for k in range(d)] if radius.max() > 0 else []
        )
        for axis in range(lo.shape[1] if radius.max() > 0 else 0):
            slope: Enclosure | None = None  # ∂D/∂u over U along this axis, signed
            for k in range(d):  # minors[k]·t = det[rows other than k; t]
                rate = [
                    None if s is None else Enclosure(s[0][:, axis], s[1][:, axis]) for s in derivatives[k]
                ]
                term = _dot_rows(minors[k], rate)
                if term is not None:
                    term = term * (-1.0 if (d - 1 - k) % 2 else 1.0)  # row k moved last
                    slope = term if slope is None else slope + term
            if slope is not None:
                with np.errstate(invalid="ignore"):
                    size = np.maximum(np.abs(slope.lo), np.abs(slope.hi)) * radius[:, axis]
                    size = np.nextafter(size, np.inf)
                    width = np.nextafter(width + size, np.inf)
        width = np.where(np.isnan(width), np.inf, np.nextafter(width * (1.0 + 2.0**-40), np.inf))
        zero = np.zeros(count)
        middle = np.moveaxis(
            np.array([[zero if e is None else 0.5 * (e.lo + e.hi) for e in row] for row in centres]), -1, 0
        )
        usable = np.all(np.isfinite(middle), axis=(1, 2))
        middle = np.where(usable[:, None, None], middle, np.eye(d))
        with np.errstate(invalid="ignore", over="ignore"):
            usable &= np.abs(np.linalg.det(middle)) > 1e-300
        p = np.linalg.inv(np.where(usable[:, None, None], middle, np.eye(d)))
        turned = determinant([_times(row, p) for row in rows])
        scale = determinant([[Enclosure(p[:, i, j], p[:, i, j]) for j in range(d)] for i in range(d)])
        assert turned is not None and scale is not None
        direct = turned * scale.reciprocal()
        return Enclosure(
            np.maximum(np.nextafter(value.lo - width, -np.inf), direct.lo),
            np.minimum(np.nextafter(value.hi + width, np.inf), direct.hi),
        )

    def _wrench(self, group: Group, twists: list[Vector]) -> Vector:
        passive = [[t[j] for j in self._live] for i, t in enumerate(twists) if i != group.actuated]
        return cofactors(passive)


def _centred(
    at_centre: Enclosure | None, over: Enclosure | None, spread: Array | None, part: slice
) -> Enclosure | None:
    """One member's entry of a wrench: its value at the centre pose widened by ``spread`` (the
    mean-value theorem in the pose), intersected with its direct enclosure over the joint box."""
    if at_centre is None:
        return None
    if over is None or spread is None:
        return Enclosure(at_centre.lo[part], at_centre.hi[part])
    lo = np.maximum(np.nextafter(at_centre.lo[part] - spread[part], -np.inf), over.lo[part])
    hi = np.minimum(np.nextafter(at_centre.hi[part] + spread[part], np.inf), over.hi[part])
    return Enclosure(lo, hi)


def _gradient(e: Enclosure | None, dims: int) -> tuple[Array, Array]:
    """An enclosure's gradient bounds (zero for a fixed one)."""
    assert e is not None
    if e.glo is None or e.ghi is None:
        zero = np.zeros((len(e.lo), dims))
        return zero, zero
    return e.glo, e.ghi


def _times(row: Any, p: Array) -> Vector:
    """The interval row vector ``row`` (entries None for exact zeros) times the float matrices ``p``
    ``(B, d, d)``, enclosed."""
    zero = np.zeros(len(p))
    lo = np.array([zero if e is None else e.lo for e in row]).T[..., None]
    hi = np.array([zero if e is None else e.hi for e in row]).T[..., None]
    out_lo, out_hi = matrix_times_interval(np.swapaxes(p, 1, 2), lo, hi)
    return [Enclosure(out_lo[:, j, 0], out_hi[:, j, 0]) for j in range(p.shape[1])]


def _dot_rows(a: Vector, b: Vector) -> Enclosure | None:
    """``Σ a_i b_i`` of interval rows."""
    total = None
    for x, y in zip(a, b, strict=True):
        if x is not None and y is not None:
            total = x * y if total is None else total + x * y
    return total
