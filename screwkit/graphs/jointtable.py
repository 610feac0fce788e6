"""A mechanism's joints over a batch of configurations: the structure once, the screws batched.

A :class:`JointTable` is the input of the analysis core (docs/architecture.md §1a): its joints' names, types
and links (:class:`JointSpec`, hashable, so the structure is analysed once,
:func:`screwkit.graphs.topology.topology`) and every joint's screws stacked over a leading batch
shape. A family's ``joints(config)`` returns one; :meth:`JointTable.from_graph` makes one from any
twist graph and :meth:`JointTable.graph` gives back the twist graph of one configuration.

Examples
--------
>>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[[0, 0, 1.0, 0, 0, 0]]] * 3, True)])
>>> table.batch_shape, table.specs[0].actuated
((3,), True)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from .joints import JOINT_TYPES, Joint
from .twistgraph import check_link_name, check_twist_graph, graph_anchor, twist_graph

__all__ = ["MAX_SCREW_MAGNITUDE", "JointSpec", "JointTable"]

Array = np.ndarray


def _refuse_symbolic(*screws: Any) -> None:
    if B.is_symbolic(*screws):
        raise ScrewkitTypeError(
            "Expected numeric joint screws for the analysis core, got symbolic entries; substitute "
            "values for the symbols (sympy's subs) first, or use screwkit.generic_analysis (a family's "
            "generic answers; also what wrench_analysis and classify return for a symbolic graph)."
        )


@dataclass(frozen=True)
class JointSpec:
    """One joint of a mechanism's structure: everything but its screws (hashable).

    Attributes
    ----------
    name : str
    type : str
        One of :data:`~screwkit.graphs.joints.JOINT_TYPES`.
    parent, child : hashable
        The links it joins (its twists are the child's relative to the parent).
    dof : int
    actuated : bool

    Examples
    --------
    >>> JointSpec("A1", "R", "base", "arm1", 1, True).dof
    1
    """

    name: str
    type: str
    parent: Any
    child: Any
    dof: int
    actuated: bool = False


@functools.lru_cache(maxsize=256)
def _check_specs(specs: tuple[JointSpec, ...], types: tuple[tuple[type, ...], ...]) -> None:
    """Refuse joints a twist graph would refuse (names, types, links, flags), once per structure."""
    names: set[str] = set()
    for spec in specs:
        if not isinstance(spec.name, str) or not spec.name:
            raise ScrewkitTypeError(f"Expected joint names to be non-empty strings, got {spec.name!r}.")
        if spec.name in names:
            raise ScrewkitValueError(f"Duplicate joint name {spec.name!r}: joint names must be unique.")
        names.add(spec.name)
        if spec.type not in JOINT_TYPES:
            raise ScrewkitValueError(
                f"Joint {spec.name!r}: expected `type` to be one of {sorted(JOINT_TYPES)}, got {spec.type!r}."
            )
        check_link_name(spec.parent, f"the parent link of joint {spec.name!r}")
        check_link_name(spec.child, f"the child link of joint {spec.name!r}")
        if not isinstance(spec.actuated, bool | np.bool_):
            raise ScrewkitTypeError(
                f"Joint {spec.name!r}: expected `actuated` to be True or False, got {spec.actuated!r}."
            )
        if spec.actuated and (spec.dof != 1 or spec.type.startswith("v")):
            raise ScrewkitValueError(
                f"Joint {spec.name!r}: expected an actuated joint to be a one-freedom joint that is not "
                f"virtual, got a {spec.type} joint with {spec.dof} freedom(s)."
            )


#: Largest screw coordinate a :class:`JointTable` takes (a point 1e100 length units away): beyond it
#: the rank kernels' norms and the superbracket's products would overflow.
MAX_SCREW_MAGNITUDE = 1e100


@dataclass(frozen=True, eq=False)
class JointTable:
    """A mechanism's joints over a batch of configurations: the structure once, the screws batched.

    The input of the analysis core (docs/architecture.md §1a): a family's ``joints(config)`` returns one, and
    :meth:`from_graph` makes one (a batch of one) from any twist graph.

    Attributes
    ----------
    base, platform : hashable
    specs : tuple of JointSpec
    screws : numpy.ndarray, shape (..., rows, 6)
        Every joint's screws stacked in the order of ``specs`` (read-only floats).
    dof : int or None
        The platform's nominal mobility (None: the number of actuated joints).
    anchor : numpy.ndarray, shape (..., 3), or None
        A point that moves with the mechanism, fixing its reference point along the axes when they
        are all parallel (a planar mechanism; :func:`screwkit.graphs.twistgraph.graph_frame`).
    mobility : int or None
        The mechanism's mobility at generic configurations when it is known (a catalog family's,
        checked by the catalog's facts; graph attribute ``mobility``): the ``dof`` check
        (:func:`screwkit.core.mobility.settled_dof`) takes it instead of computing it. None: computed.
    free : int, default 0
        Freedoms of the platform that no actuator is meant to drive: 3 for a point task, whose
        platform is a task link on a spherical joint at the point (its rotations stay free;
        :mod:`screwkit.robots.point_task`). The global wrench system's nominal order is ``6 − free``.

    Examples
    --------
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]] * 2, True)])
    >>> table.batch_shape, table.joint_screws("P").shape
    ((2,), (2, 1, 6))
    >>> table[1].graph().edges["B", "E", "P"]["joint"].actuated
    True
    """

    base: Any
    platform: Any
    specs: tuple[JointSpec, ...]
    screws: Array
    dof: int | None = None
    anchor: Array | None = None
    mobility: int | None = None
    free: int = 0

    def __post_init__(self) -> None:
        if not (isinstance(self.free, int | np.integer) and 0 <= self.free <= 6):
            raise ScrewkitValueError(f"Expected `free` to be an integer in 0..6, got {self.free!r}.")
        check_link_name(self.base, "the table's base link")
        check_link_name(self.platform, "the table's platform link")
        if not (isinstance(self.specs, tuple) and all(isinstance(spec, JointSpec) for spec in self.specs)):
            raise ScrewkitTypeError(f"Expected `specs` to be a tuple of JointSpec, got {self.specs!r}.")
        # the flags' and links' types join the key: JointSpec(actuated=0) == JointSpec(actuated=False)
        types = tuple((type(s.actuated), type(s.parent), type(s.child)) for s in self.specs)
        try:
            hash(self.specs)
        except TypeError:  # an unhashable link: checked (and refused) without the cache
            _check_specs.__wrapped__(self.specs, types)
        _check_specs(self.specs, types)
        rows = sum(spec.dof for spec in self.specs)
        _refuse_symbolic(self.screws)
        given = self.screws
        owned = isinstance(given, np.ndarray) and given.dtype == float and given.base is None
        # a read-only float array owning its data (another table's, or from_rows') is kept as is
        screws = given if owned and not given.flags.writeable else B.as_array(given, "screws")
        if screws.ndim < 2 or screws.shape[-2:] != (rows, 6):
            raise ScrewkitValueError(
                f"Expected `screws` of shape (..., {rows}, 6) for the table's joints, got {screws.shape}."
            )
        if screws.size == 0 and rows:  # an empty batch: the posed path refuses it too
            raise ScrewkitValueError(
                f"Expected `screws` to hold at least one configuration, got batch shape {screws.shape[:-2]}."
            )
        largest = np.maximum(screws.max(), -screws.min()) if screws.size else 0.0  # NaN or inf propagate
        if not np.isfinite(largest):
            raise ScrewkitValueError("Expected finite joint screws, got NaN or infinity.")
        if largest > MAX_SCREW_MAGNITUDE:
            raise ScrewkitValueError(
                f"Expected joint screw coordinates up to {MAX_SCREW_MAGNITUDE:g} in size (norms and "
                f"products must not overflow), got {largest:g}."
            )
        columns = screws.reshape(-1, 6)  # column by column: faster than a reduction over six
        zero = columns[:, 0] == 0
        for k in range(1, 6):
            zero &= columns[:, k] == 0
        zero = zero.reshape(screws.shape[:-1])
        if zero.any():
            where = np.argwhere(zero)[0]
            row, starts = int(where[-1]), np.cumsum([spec.dof for spec in self.specs])
            name = self.specs[int(np.searchsorted(starts, row, side="right"))].name
            raise ScrewkitValueError(
                f"Joint {name!r}: expected non-zero screws, got a zero row"
                + (f" at batch index {tuple(int(i) for i in where[:-1])}." if len(where) > 1 else ".")
            )
        screws.flags.writeable = False
        object.__setattr__(self, "screws", screws)
        if self.anchor is not None:
            anchor = np.broadcast_to(np.asarray(self.anchor, dtype=float), (*screws.shape[:-2], 3)).copy()
            anchor.flags.writeable = False
            object.__setattr__(self, "anchor", anchor)

    @classmethod
    def from_rows(
        cls,
        base: Any,
        platform: Any,
        rows: list[tuple[Any, Any, str, str, Any, bool]],
        *,
        dof: int | None = None,
        anchor: Any = None,
        mobility: int | None = None,
    ) -> JointTable:
        """A table from ``(parent, child, name, type, screws (..., dof_j, 6), actuated)`` rows.

        Parameters
        ----------
        base, platform : hashable
            The fixed link and the end effector.
        rows : list of tuple
            ``(parent, child, name, type, screws, actuated)`` per joint, ``screws`` of shape
            ``(..., dof_j, 6)`` (batch shapes broadcast together).
        dof : int, optional
            The platform's nominal mobility (default: the number of actuated joints).
        anchor : array_like, shape (..., 3), optional
            A point that moves with the mechanism (see the class).
        mobility : int, optional
            The mechanism's mobility at generic configurations, when known.

        Returns
        -------
        JointTable

        Examples
        --------
        >>> JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[0, 0, 1.0, 0, 0, 0]], False)]).specs[0]
        JointSpec(name='R', type='R', parent='B', child='E', dof=1, actuated=False)
        """
        for row in rows:
            if not (isinstance(row, tuple | list) and len(row) == 6):
                raise ScrewkitTypeError(
                    f"Expected `rows` of (parent, child, name, type, screws, actuated), got {row!r}."
                )
        _refuse_symbolic(*(screws for *_, screws, _ in rows))
        arrays = [
            B.as_array(screws, f"screws of joint {name!r}", (None, 6)) for _, _, name, _, screws, _ in rows
        ]
        batch = np.broadcast_shapes(*(a.shape[:-2] for a in arrays)) if arrays else ()
        specs = tuple(
            JointSpec(name, kind, parent, child, array.shape[-2], actuated)
            for (parent, child, name, kind, _, actuated), array in zip(rows, arrays, strict=True)
        )
        stacked = (
            np.concatenate([np.broadcast_to(a, (*batch, *a.shape[-2:])) for a in arrays], axis=-2)
            if arrays
            else np.zeros((0, 6))
        )
        stacked.flags.writeable = False  # fresh: the table takes it without a copy
        return cls(base, platform, specs, stacked, dof, anchor, mobility)

    @classmethod
    def from_graph(cls, graph: Any, *, joint_key: str = "joint") -> JointTable:
        """The table of a twist graph at its configuration (a batch of one pose: shape ``()``).

        Parameters
        ----------
        graph : networkx.MultiDiGraph
            A twist graph (checked).
        joint_key : str, default "joint"
            The edge attribute holding the joints.

        Returns
        -------
        JointTable

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))])
        >>> JointTable.from_graph(G).batch_shape
        ()
        """
        check_twist_graph(graph, joint_key=joint_key)
        joints = list(graph.edges(keys=True, data=joint_key))  # any order: the core sorts by name
        rows = [(u, v, key, joint.type, joint.screws, joint.actuated) for u, v, key, joint in joints]
        table = cls.from_rows(
            graph.graph["base"],
            graph.graph["platform"],
            rows,
            dof=graph.graph.get("dof"),
            anchor=graph_anchor(graph, joint_key=joint_key),
            mobility=graph.graph.get("mobility"),
        )
        free = graph.graph.get("free", 0)  # a point task's (screwkit.robots.point_task)
        return replace(table, free=free) if free else table

    def __repr__(self) -> str:
        """One line: base, platform, the joints by type and the batch shape.

        Returns
        -------
        str
        """
        kinds: dict[str, int] = {}
        for spec in self.specs:
            kinds[spec.type] = kinds.get(spec.type, 0) + 1
        joints = ", ".join(f"{count} {kind}" for kind, count in kinds.items())
        actuated = sum(spec.actuated for spec in self.specs)
        return (
            f"JointTable({self.base!r} to {self.platform!r}: {len(self.specs)} joints ({joints}), "
            f"{actuated} actuated, batch shape {self.batch_shape})"
        )

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """The leading batch shape of :attr:`screws`."""
        return self.screws.shape[:-2]

    def __len__(self) -> int:
        if not self.batch_shape:
            raise TypeError("a JointTable of one configuration has no length")
        return self.batch_shape[0]

    def __getitem__(self, index: Any) -> JointTable:
        anchor = None if self.anchor is None else self.anchor[index]
        screws = self.screws[index]
        return JointTable(
            self.base, self.platform, self.specs, screws, self.dof, anchor, self.mobility, self.free
        )

    def joint_screws(self, name: str) -> Array:
        """The screws of one joint over the batch, ``(..., dof_j, 6)``.

        Parameters
        ----------
        name : str
            The joint's name.

        Returns
        -------
        numpy.ndarray, shape (..., dof_j, 6)

        Examples
        --------
        >>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[0, 0, 1.0, 0, 0, 0]], False)])
        >>> table.joint_screws("R")
        array([[0., 0., 1., 0., 0., 0.]])
        """
        start = 0
        for spec in self.specs:
            if spec.name == name:
                return self.screws[..., start : start + spec.dof, :]
            start += spec.dof
        raise ScrewkitValueError(f"Expected the name of a joint of the table, got {name!r}.")

    def graph(self, index: Any = ()) -> Any:
        """The twist graph (:class:`networkx.MultiDiGraph`) of one configuration of the batch.

        Parameters
        ----------
        index : int or tuple, default ()
            The configuration of the batch (a full index into :attr:`batch_shape`).

        Returns
        -------
        networkx.MultiDiGraph

        Raises
        ------
        ScrewkitValueError
            If ``index`` does not pick exactly one configuration of the batch.

        Examples
        --------
        >>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[0, 0, 1.0, 0, 0, 0]], False)])
        >>> sorted(table.graph().edges(keys=True))
        [('B', 'E', 'R')]
        """
        wrong = ScrewkitValueError(
            f"Expected `index` to pick one configuration of the batch of shape {self.batch_shape}, "
            f"got {index!r}."
        )
        try:
            picked = self.screws[index]
        except (IndexError, TypeError) as err:  # out of range, or not an index
            raise wrong from err
        if picked.shape != self.screws.shape[-2:]:  # several configurations, or too many indices
            raise wrong
        one = self[index]
        joints, start = [], 0
        for spec in one.specs:
            screws = one.screws[start : start + spec.dof]
            start += spec.dof
            joint = Joint(spec.name, spec.type, screws, spec.actuated, spec.type.startswith("v"))
            joints.append((spec.parent, spec.child, joint))
        graph = twist_graph(one.base, one.platform, joints, dof=one.dof)
        if one.mobility is not None:
            graph.graph["mobility"] = one.mobility
        if one.free:
            graph.graph["free"] = one.free
        if one.anchor is not None:
            graph.graph["anchor"] = one.anchor.tolist()
        return graph
