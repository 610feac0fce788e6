"""Redundant actuation: the freedoms a mechanism's actuators drive, and its degree of redundancy.

A mechanism is *redundantly actuated* when it has more actuated joints ``n`` than freedoms ``dof``
(its mobility at generic configurations, :mod:`screwkit.core.mobility`). Its actuators then drive
the platform through the global wrench system ``W^c + W^a`` (the constraint wrenches and *all* the
actuation wrenches, paper 002 Eq. 4): the platform is controlled, every external wrench balanced
by constraint reactions and actuator forces, exactly when ``W^c + W^a`` spans all six wrenches.
This is the non-redundant criterion unchanged (Zlatanov, Bonev & Gosselin 2002, ICRA, "Constraint
singularities of parallel mechanisms"): with more actuation wrenches than needed the set where it
fails is smaller, since one actuator's wrench can make up for another's (Merlet, *Parallel Robots*,
2nd ed., Springer 2006, ch. 6, singular configurations; the rank of the ``n × dof`` matrix ``A`` of
Gosselin & Angeles 1990 generalised: ``rank A < dof``, :mod:`screwkit.core.jacobians`). The
actuation singularities of a redundantly actuated mechanism are therefore where
``order(W^c) = 6 − dof`` and ``order(W^c + W^a) < 6`` (:mod:`screwkit.core.verdicts`).

The freedoms the actuators drive at a pose are the rank of the actuation wrenches modulo the
constraint wrenches, ``order(W^c + W^a) − order(W^c)`` (``= rank A`` for a basis of the platform's
twists: ``A = W^a ∘ T`` has the kernel ``W^a ∩ T^⊥ = W^a ∩ W^c``). The **degree of redundancy**
at a pose is ``n`` minus those freedoms: the dimension of the actuator forces in equilibrium with
constraint reactions alone, the internal forces (preload) the actuators can set without loading
the platform (the null space of ``Aᵀ``; Nahon & Angeles, "Force optimization in redundantly-actuated
closed kinematic chains", ICRA 1989). It is ``n − dof`` at a regular pose, 0 for a non-redundant
mechanism at a regular pose, and grows at a singular pose, where the actuators drive fewer freedoms
(a non-redundant mechanism at an actuation singularity has one such self-stress).

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> slider = twist_graph("B", "E", [("B", "E", prismatic("P1", [1, 0, 0], actuated=True)),
...                                 ("B", "E", prismatic("P2", [1, 0, 0], actuated=True))])
>>> generic_driven_freedoms(slider, 1)  # two actuators side by side driving one slide
1
"""

from __future__ import annotations

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitValueError
from .motion import generic_configurations
from .wrench_systems import analyze_table

__all__ = ["DRIVEN_SAMPLES", "DRIVEN_SEED", "generic_driven_freedoms"]

#: Generic configurations the driven freedoms are read from (their most common value), and the seed of
#: the random motion that reaches them (fixed: the same graph always gets the same answer).
DRIVEN_SAMPLES = 3
DRIVEN_SEED = 20261128


def generic_driven_freedoms(
    graph: nx.MultiDiGraph,
    dof: int,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> int | None:
    """The freedoms the actuated joints drive at generic configurations of the graph's mechanism.

    The most common ``order(W^c + W^a) − order(W^c)`` (module docstring) over :data:`DRIVEN_SAMPLES`
    configurations reached by :func:`~screwkit.core.motion.generic_configurations`, analysed with the
    nominal ``dof`` (:func:`~screwkit.core.wrench_systems.analyze_table`, ``rtol`` and ``length_scale``
    as there). Fewer than ``min(n, dof)`` means that actuator flags leave the platform uncontrolled
    at every configuration (two actuators on one freedom, an actuator in a loop it cannot drive).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (numbers), at any pose.
    dof : int
        The mechanism's mobility.
    joint_key : str, default "joint"
    rtol : float, default 1e-9
    length_scale : float, optional

    Returns
    -------
    int or None
        None when no generic configuration could be reached.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> coaxial = twist_graph("B", "E", [("B", "L", revolute("A1", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...                                  ("L", "E", revolute("A2", [0, 0, 1], [0, 0, 0], actuated=True))])
    >>> generic_driven_freedoms(coaxial, 1)  # each actuator's twist is its limb's other one
    0
    """
    try:
        table = generic_configurations(
            graph, np.random.default_rng(DRIVEN_SEED), DRIVEN_SAMPLES, joint_key=joint_key, rtol=rtol
        )
    except ScrewkitValueError:
        return None
    analysis = analyze_table(table, dof=dof, rtol=rtol, length_scale=length_scale, views=False)
    driven = np.asarray(analysis.global_order) - np.asarray(analysis.constraint_order)
    return int(np.bincount(driven.ravel()).argmax())
