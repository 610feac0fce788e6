"""Operation modes: generic configurations grouped by the platform's motion type and constraint order.

A mechanism may move in several operation modes: Tsai's 3-UPU translates (3T) in one and turns
(2T1R, its platform parallel to the base plane moving in it, and beyond) in others; the modes meet at
transition configurations, which are singularities of the configuration space (Zlatanov, Bonev &
Gosselin 2002, *Constraint singularities as C-space singularities*). Two generic configurations lie
in the same mode only if the platform's twist system has the same motion type there
(:func:`screwkit.algebra.motion_type.motion_type`: translations and other freedoms,
``t = order(T) + 3 − order(T + translations)``) and the constraint wrench system the same order; this
module groups a batch of configurations by that pair. It is a necessary condition, not a proof that
two configurations share a mode: two modes of the same motion type and constraint order read as one.

Examples
--------
>>> from screwkit.core.motion import generic_configurations
>>> from screwkit.core.wrench_systems import analyze_table
>>> graph = load_mechanism("planar_3rrp").twist_graph()
>>> table = generic_configurations(graph, np.random.default_rng(0), 4)
>>> [(mode.motion_type, len(mode.indices)) for mode in operation_modes(analyze_table(table))]
[('2T1R', 4)]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..algebra.motion_type import motion_type
from .wrench_systems import WrenchAnalysis

__all__ = ["OperationMode", "operation_modes", "reference_mode_indices"]


@dataclass(frozen=True)
class OperationMode:
    """One class of configurations of a batch (module docstring).

    Attributes
    ----------
    motion_type : str
        The platform's motion type, e.g. ``"3T"`` (a helical freedom's pitch left out: it varies
        along a mode).
    constraint_order : int
        The order of the constraint wrench system.
    indices : tuple of int
        The batch entries in this class.
    reference : bool
        True if the reference configuration (when one was given) has this motion type and
        constraint order.
    turn : tuple of float, optional
        For a mode without rotations, whose platform keeps one orientation, that orientation from
        the reference's: a rotation vector (radians, the graph's frame); None otherwise
        (:func:`screwkit.core.mode_search.find_operation_modes` sets it).
    """

    motion_type: str
    constraint_order: int
    indices: tuple[int, ...]
    reference: bool = False
    turn: tuple[float, float, float] | None = None

    @property
    def name(self) -> str:
        """The motion type, and a turned translational mode's turn.

        Returns
        -------
        str
            ``"3T"``, or ``"3T (turned 180° about (0, 0, 1))"`` for a mode whose platform keeps an
            orientation other than the reference's.

        Examples
        --------
        >>> OperationMode("3T", 3, (0,), turn=(0.0, 0.0, -np.pi)).name
        '3T (turned 180° about (0, 0, 1))'
        """
        if self.turn is None or np.linalg.norm(self.turn) == 0.0:
            return self.motion_type
        angle = float(np.linalg.norm(self.turn))
        direction = np.asarray(self.turn) / angle
        if np.pi - angle < 1e-6:  # a half turn about a and about −a are one: its largest component > 0
            direction = direction * np.sign(direction[np.argmax(np.abs(direction))])
        axis = ", ".join(f"{value + 0.0:.4g}" for value in np.round(direction, 12))
        return f"{self.motion_type} (turned {np.degrees(angle):.4g}° about ({axis}))"


#: Configurations closed by Newton's method to a residual of 1e-9 carry their twists to about that, so
#: their motion type is read at this tolerance (or the analysis' own, if looser): a pitch of 1e-9 lengths
#: is round-off, not a helical freedom (Tsai's 3-UPU seen in a half-turned frame once read one of 16
#: planar configurations "2T1H", pitch -1.4e-9 against a threshold of 7.9e-10).
CLOSED_RTOL = 1e-6


def _key(analysis: WrenchAnalysis) -> tuple[str, int]:
    """A closed configuration's motion type (its pitch left out) and constraint order; for a point task
    (``free`` rotations about the point, :mod:`screwkit.robots.point_task`) the point's motion type."""
    twists = analysis.platform_twists  # its rows: a screw system would be read at its own rtol
    rtol = max(CLOSED_RTOL, analysis.rtol)
    label = str(motion_type(twists.basis, rtol=rtol, length_scale=twists.length_scale)).split(" (pitch")[0]
    if analysis.free:
        label = _point_label(label)
    return label, int(analysis.constraint_order)


def _point_label(label: str) -> str:
    """The motion type of a point task's point from its task link's (``"2T3R"``: ``"2T"``).

    The task link's twists are the measured link's and every rotation about the point, so the
    translations among them are the velocities the point can have (a twist ``(ω; v_P)`` at the point
    less the rotation ``ω`` about it is the translation ``v_P``): the point's freedoms, all
    translations; the rotations in the label are the three free ones (and the link's own, which the
    task leaves free).
    """
    translations = label.split("T")[0] if "T" in label else "0"
    return f"{translations}T" if translations != "0" else "0"


def _rotations(label: str) -> int:
    """The freedoms other than translations in a motion type label (``"2T1R"``: 1, ``"1H"``: 1)."""
    return sum(int(part[:-1] or 1) for part in label.replace("T", "T ").split() if part[-1] in "RH")


def operation_modes(
    analysis: WrenchAnalysis, reference: WrenchAnalysis | None = None
) -> list[OperationMode]:
    """The classes of a batch of configurations by motion type and constraint order.

    Parameters
    ----------
    analysis : WrenchAnalysis
        A batch ``(n,)`` of configurations (e.g. :func:`~screwkit.core.motion.generic_configurations`'
        analysed).
    reference : WrenchAnalysis, optional
        One configuration (shape ``()``): the class with its motion type and constraint order comes
        first and is marked ``reference``.

    Returns
    -------
    list of OperationMode
        The reference's class first (if any), then by decreasing size, ties by first entry.

    Examples
    --------
    >>> from screwkit.core.motion import generic_configurations
    >>> from screwkit.core.wrench_systems import analyze_table
    >>> graph = load_mechanism("planar_3rrp").twist_graph()
    >>> batch = analyze_table(generic_configurations(graph, np.random.default_rng(0), 3))
    >>> [(mode.motion_type, mode.reference) for mode in operation_modes(batch, batch[0])]
    [('2T1R', True)]
    """
    classes: dict[tuple[str, int], list[int]] = {}
    for index in range(int(analysis.shape[0])):
        classes.setdefault(_key(analysis[index]), []).append(index)
    own = None if reference is None else _key(reference)
    modes = [
        OperationMode(key[0], key[1], tuple(indices), key == own) for key, indices in classes.items()
    ]
    return sorted(modes, key=lambda mode: (not mode.reference, -len(mode.indices), mode.indices[0]))


def reference_mode_indices(analysis: WrenchAnalysis, reference: WrenchAnalysis) -> np.ndarray:
    """Batch entries in the reference configuration's class (all entries if none is).

    Parameters
    ----------
    analysis : WrenchAnalysis
        A batch ``(n,)``.
    reference : WrenchAnalysis
        One configuration.

    Returns
    -------
    numpy.ndarray of int
        Sorted indices: the reference's class, or, where the reference lies in none of the batch's
        classes (at a configuration where modes meet), the class whose global wrench system has the
        highest order (a mode singular throughout has no diagram to analyse), then the fewest freedoms
        other than translations (a convention, not derived: Tsai's 3-UPU, designed to translate, is
        analysed in its 3T mode), then the largest.

    Examples
    --------
    >>> from screwkit.core import motion, wrench_systems
    >>> h4 = load_mechanism("h4").twist_graph()
    >>> draws = wrench_systems.analyze_table(motion.generic_configurations(h4, np.random.default_rng(1), 2))
    >>> reference_mode_indices(draws, draws[1]).tolist()
    [0, 1]
    """
    modes = operation_modes(analysis, reference)
    if not modes[0].reference:  # fullest global wrench system, then fewest freedoms not translations
        order = np.asarray(analysis.global_order)
        modes = sorted(modes, key=lambda mode: (-int(np.min(order[list(mode.indices)])),
                                                _rotations(mode.motion_type)))
    return np.array(modes[0].indices, dtype=int)
