"""The composer of one pose's report, registered from above (dependency inversion): the report is
composed in :mod:`screwkit.interface.report`, a layer above the robots, which the robots may not import
(docs/architecture.md §2); :meth:`screwkit.robots.posed.PosedMechanism.report` calls whatever
composer is registered here, and ``import screwkit`` registers the interface's (loaded on its first
call, so that the report's stack is not a cost of ``import screwkit``).

Examples
--------
>>> composer = report_composer()
>>> composer(load_mechanism("v4").at()[0], superbracket=False, progress=None).verdict.verdict
'regular'
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = ["register_report_composer", "report_composer"]

#: The registered composer (one slot): ``composer(posed_one_pose, *, superbracket, progress) -> report``.
_COMPOSER: list[Callable[..., Any]] = []


def register_report_composer(composer: Callable[..., Any]) -> None:
    """Register the function that composes the report of one pose, replacing the one registered.

    Parameters
    ----------
    composer : callable
        ``composer(posed, *, superbracket, progress) -> AnalysisReport`` for a posed mechanism of one
        pose (``import screwkit`` registers :func:`screwkit.interface.report.analyze`).

    Returns
    -------
    None

    Raises
    ------
    ScrewkitTypeError
        If ``composer`` is not callable.

    Examples
    --------
    >>> register_report_composer(report_composer())  # what import screwkit did
    """
    if not callable(composer):
        raise ScrewkitTypeError(f"Expected `composer` to be callable, got {type(composer).__name__}.")
    _COMPOSER[:] = [composer]


def report_composer() -> Callable[..., Any]:
    """The registered composer of one pose's report.

    Returns
    -------
    callable

    Raises
    ------
    ScrewkitValueError
        If none is registered (only when ``screwkit/__init__`` did not run to its end).

    Examples
    --------
    >>> callable(report_composer())
    True
    """
    if not _COMPOSER:
        raise ScrewkitValueError(
            "Expected a report composer to be registered (register_report_composer; import screwkit does), "
            "got none."
        )
    return _COMPOSER[0]
