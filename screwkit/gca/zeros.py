"""Sampling and numeric zero tests, the first steps of the simplification (``gca.md`` §6): draw
configurations from a mechanism's sampler, find its structurally zero brackets
(:func:`structural_zeros`) and sub-sums (:func:`drop_zero_subsums`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra import projective as P
from ..algebra.checks import checked_rtol
from ..exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from .brackets import BracketPolynomial

__all__ = [
    "Sampler",
    "checked_positive_int",
    "draw_samples",
    "drop_structural_zeros",
    "drop_vanishing_subsums",
    "drop_zero_subsums",
    "structural_zeros",
    "vanishing_brackets",
]


#: A sampler draws one configuration satisfying a mechanism's incidences: ``rng -> {label: (4,)}``.
Sampler = Callable[[np.random.Generator], Mapping[str, Any]]

# --------------------------------------------------------------------------------------------------
# Sampling and numeric zero tests
# --------------------------------------------------------------------------------------------------


def checked_positive_int(value: Any, name: str) -> int:
    """A positive integer argument, checked.

    Parameters
    ----------
    value : object
    name : str
        The argument's name, for the message.

    Returns
    -------
    int

    Raises
    ------
    ScrewkitValueError
        If ``value`` is not a positive integer (booleans are refused).

    Examples
    --------
    >>> checked_positive_int(np.int64(3), "n_samples")
    3
    """
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ScrewkitValueError(f"Expected `{name}` to be a positive integer, got {value!r}.")
    return int(value)


def draw_samples(
    sampler: Any, n_samples: int, rng: np.random.Generator, labels: Iterable[str] | None = None
) -> dict[str, np.ndarray]:
    """Draw ``n_samples`` configurations and stack them: label -> (n_samples, 4) float array.

    The Python loop only *draws* configurations (the sampler's contract is one configuration per
    call); every evaluation afterwards is vectorised over the stacked samples.

    Parameters
    ----------
    sampler : callable
        ``rng -> {label: point (4,)}``.
    n_samples : int
    rng : numpy.random.Generator
    labels : iterable of str, optional
        The labels kept (default: those of the first draw).

    Returns
    -------
    dict of str to numpy.ndarray, shape (n_samples, 4)

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError, DegenerateGeometryError
        For a sampler that is not callable, a missing label, a point of the wrong shape, the zero
        vector.

    Examples
    --------
    >>> samples = draw_samples(lambda rng: {"a": rng.normal(size=4)}, 3, np.random.default_rng(0))
    >>> samples["a"].shape
    (3, 4)
    """
    if not callable(sampler):
        raise ScrewkitTypeError(
            f"Expected `sampler` to be a callable rng -> {{label: point (4,)}}, "
            f"got {type(sampler).__name__}."
        )
    n = checked_positive_int(n_samples, "n_samples")
    draws = [sampler(rng) for _ in range(n)]
    if not all(isinstance(d, Mapping) for d in draws):
        raise ScrewkitTypeError(
            f"Expected `sampler(rng)` to return a mapping label -> point (4,), "
            f"got {type(draws[0]).__name__}."
        )
    wanted = sorted(draws[0]) if labels is None else sorted(set(labels))
    out = {}
    for label in wanted:
        missing = [i for i, d in enumerate(draws) if label not in d]
        if missing:
            raise ScrewkitValueError(
                f"Expected `sampler(rng)` to give a point for label {label!r}, missing in draw "
                f"{missing[0]} (labels {sorted(draws[missing[0]])})."
            )
        name = f"sampler(rng)[{label!r}]"
        stacked = np.stack([B.as_array(d[label], name, (4,), symbolic=False) for d in draws])
        if stacked.ndim != 2:
            raise ScrewkitValueError(
                f"Expected `{name}` to be one point of shape (4,), got {stacked.shape[1:]}."
            )
        if np.any(np.all(stacked == 0, axis=-1)):
            raise DegenerateGeometryError(
                f"Expected `{name}` to be a projective point, got the zero vector."
            )
        out[label] = stacked
    return out


def _relative_brackets(
    samples: Mapping[str, np.ndarray], quads: Sequence[Sequence[str]]
) -> np.ndarray:
    """``|[pqrs]| / (|p||q||r||s|)`` (≤ 1, Hadamard) for each quad: (n_samples, n_quads)."""
    if not quads:
        return np.zeros((next(iter(samples.values())).shape[0], 0))
    labels = sorted({label for quad in quads for label in quad})
    index = {label: i for i, label in enumerate(labels)}
    stacked = np.stack([samples[label] for label in labels])  # (n_labels, n_samples, 4)
    rows = np.array([[index[label] for label in quad] for quad in quads])  # (n_quads, 4)
    gathered = stacked[rows]  # (n_quads, 4, n_samples, 4)
    values = P.bracket_unchecked(*(gathered[:, i] for i in range(4)))
    norms = np.linalg.norm(gathered, axis=-1).prod(axis=1)
    return (np.abs(values) / norms).T


def vanishing_brackets(
    samples: Mapping[str, np.ndarray], quads: Sequence[tuple[str, ...]], rtol: float
) -> dict[tuple[str, ...], bool]:
    """Whether each bracket (distinct labels) vanishes on every sample (relative to Hadamard).

    Parameters
    ----------
    samples : mapping of str to numpy.ndarray, shape (n_samples, 4)
        Stacked samples (:func:`draw_samples`).
    quads : sequence of tuple of str
        The brackets' labels (four distinct labels each).
    rtol : float
        ``|[pqrs]| <= rtol · |p||q||r||s|`` counts as zero.

    Returns
    -------
    dict of tuple of str to bool

    Examples
    --------
    >>> e = np.eye(4)[None]
    >>> vanishing_brackets({"a": e[:, 0], "b": e[:, 1], "c": e[:, 2], "d": e[:, 0] + e[:, 1]},
    ...                    [("a", "b", "c", "d")], 1e-9)
    {('a', 'b', 'c', 'd'): True}
    """
    zero = np.all(_relative_brackets(samples, quads) <= rtol, axis=0)
    return dict(zip(quads, (bool(z) for z in zero), strict=True))


def drop_structural_zeros(
    poly: BracketPolynomial, samples: Mapping[str, np.ndarray], rtol: float
) -> BracketPolynomial:
    """:func:`structural_zeros` on samples already drawn.

    Parameters
    ----------
    poly : BracketPolynomial
    samples : mapping of str to numpy.ndarray, shape (n_samples, 4)
        Stacked samples (:func:`draw_samples`).
    rtol : float
        Relative zero threshold of a bracket (:func:`vanishing_brackets`).

    Returns
    -------
    BracketPolynomial
        The monomials none of whose brackets vanishes on every sample.

    Examples
    --------
    >>> e = np.eye(4)[None]
    >>> samples = {"a": e[:, 0], "b": e[:, 1], "c": e[:, 2], "d": e[:, 3], "e": e[:, 0] + e[:, 1]}
    >>> str(drop_structural_zeros(BracketPolynomial.parse("[abcd] + [abce]"), samples, 1e-9))
    '[abcd]'
    """
    quads = sorted({key for m in poly.terms for key in m.canonical[1]})
    zero = vanishing_brackets(samples, quads, rtol)
    return BracketPolynomial(m for m in poly.terms if not any(zero[k] for k in m.canonical[1]))


def structural_zeros(
    poly: BracketPolynomial,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rtol: float = 1e-9,
    rng: np.random.Generator | int = 0,
) -> BracketPolynomial:
    """Drop the monomials that vanish on every configuration the sampler draws (``gca.md`` §6.2).

    A bracket is taken as zero on a sample when ``|[pqrs]| <= rtol · |p||q||r||s|`` (the Hadamard
    bound, so the test is independent of units and of the points' scaling); a monomial is dropped
    when one of its brackets is zero on all ``n_samples`` samples. This catches repeated points,
    four infinite points and every incidence the sampler respects (collinear, coplanar points).

    Parameters
    ----------
    poly : BracketPolynomial
    sampler : callable
        ``rng -> {label: point (4,)}``, one random configuration satisfying the incidences.
    n_samples : int, default 20
    rtol : float, default 1e-9
        Relative zero threshold of a bracket (structural zeros are at round-off level, ~1e-16).
    rng : numpy.random.Generator or int, default 0
        The generator passed to ``sampler`` (or its seed).

    Returns
    -------
    BracketPolynomial
        The surviving monomials.

    Examples
    --------
    >>> def collinear(rng):  # a, b, c on one line
    ...     a, b = rng.normal(size=4), rng.normal(size=4)
    ...     return {"a": a, "b": b, "c": 2 * a - 3 * b, "d": rng.normal(size=4),
    ...             "e": rng.normal(size=4)}
    >>> str(structural_zeros(BracketPolynomial.parse("[abcd] + [abde]"), collinear))
    '[abde]'
    """
    samples = draw_samples(sampler, n_samples, np.random.default_rng(rng), poly.labels)
    return drop_structural_zeros(poly, samples, checked_rtol(rtol))


def drop_vanishing_subsums(
    poly: BracketPolynomial, samples: Mapping[str, np.ndarray], rtol: float, max_terms: int
) -> BracketPolynomial:
    """:func:`drop_zero_subsums` on samples already drawn.

    Parameters
    ----------
    poly : BracketPolynomial
    samples : mapping of str to numpy.ndarray, shape (n_samples, 4)
        Stacked samples (:func:`draw_samples`).
    rtol : float
        A subset vanishes when its sum is at most ``rtol`` times the sum of the monomials'
        absolute values on every sample.
    max_terms : int
        Polynomials with more monomials are returned unchanged.

    Returns
    -------
    BracketPolynomial

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> samples = {x: rng.normal(size=(4, 4)) for x in "abcef"}
    >>> samples["d"] = samples["b"] + samples["c"]  # so [abde] = [abce]
    >>> poly = BracketPolynomial.parse("[abde] - [abce] + [abef]")
    >>> str(drop_vanishing_subsums(poly, samples, 1e-9, 16))
    '[abef]'
    """
    k = len(poly)
    if k < 2 or k > max_terms:
        return poly
    arrays = {label: samples[label] for label in poly.labels}
    values = np.stack(poly._term_values(arrays), axis=-1)  # (n_samples, k)
    scale = np.abs(values).sum(axis=-1, keepdims=True)
    drop = (np.arange(2**k)[:, None] >> np.arange(k)) & 1  # (2^k, k): 1 = dropped
    vanishing = np.all(np.abs(values @ drop.T) <= rtol * scale, axis=0)
    best = int(np.argmax(np.where(vanishing, drop.sum(axis=1), -1)))
    return BracketPolynomial(m for m, d in zip(poly.terms, drop[best], strict=True) if not d)


def drop_zero_subsums(
    poly: BracketPolynomial,
    sampler: Sampler,
    *,
    n_samples: int = 20,
    rtol: float = 1e-9,
    max_terms: int = 16,
    rng: np.random.Generator | int = 0,
) -> BracketPolynomial:
    """Drop the largest set of monomials whose *sum* vanishes on every sampled configuration.

    A numeric stand-in for the syzygies of ``gca.md`` §6.3: on the incidence variety some sums of
    non-zero monomials vanish (Grassmann–Plücker relations combined with the incidences). All
    ``2^k`` subsets are scored at once (vectorised); a subset vanishes when its sum is at most
    ``rtol`` times the sum of the monomials' absolute values on every sample. Verify the result
    with :func:`~screwkit.gca.simplify.check_proportional`;
    :func:`~screwkit.gca.simplify.simplify_superbracket` does.

    Parameters
    ----------
    poly : BracketPolynomial
    sampler : callable
        ``rng -> {label: point (4,)}`` (see :func:`structural_zeros`).
    n_samples : int, default 20
    rtol : float, default 1e-9
    max_terms : int, default 16
        Polynomials with more monomials are returned unchanged (the search is ``2^k``).
    rng : numpy.random.Generator or int, default 0

    Returns
    -------
    BracketPolynomial
        Equal to ``poly`` on the sampled variety, with fewer monomials if a subsum vanishes.

    Examples
    --------
    >>> def sampler(rng):  # d = b + c, so [abde] = [abbe] + [abce] = [abce]
    ...     pts = {x: rng.normal(size=4) for x in "abcef"}
    ...     return {**pts, "d": pts["b"] + pts["c"]}
    >>> str(drop_zero_subsums(BracketPolynomial.parse("[abde] - [abce] + [abef]"), sampler))
    '[abef]'
    """
    samples = draw_samples(sampler, n_samples, np.random.default_rng(rng), poly.labels)
    return drop_vanishing_subsums(
        poly, samples, checked_rtol(rtol), checked_positive_int(max_terms, "max_terms")
    )
