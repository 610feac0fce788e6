"""The report's conditions section: each factor of the superbracket with its label, its statement, its
vector form and its value at the pose (:class:`screwkit.interface.analysis_report.AnalysisReport`)."""

from __future__ import annotations

import math

from ..gca.redundant_conditions import RedundantSuperbracket as Redundant
from ..gca.superbracket_analysis import VANISHING_RTOL, SuperbracketAnalysis


def condition_lines(result: SuperbracketAnalysis | Redundant, singular: bool) -> list[str]:
    """The conditions section's lines for ``result`` (a superbracket analysis, or a redundant mechanism's
    subsets); ``singular`` is the verdict's, which decides between "vanishes at this pose" and "near zero
    here" for a factor within :data:`~screwkit.gca.superbracket_analysis.VANISHING_RTOL` of its size."""
    out: list[str] = []
    # a redundant mechanism's conditions hold subset by subset: one alone is not a singularity
    subsets = result.subset_of if isinstance(result, Redundant) else None
    said: set[str] = set()
    for index, (condition, label, value, vanishes, constant) in enumerate(zip(
        result.conditions, result.labels, result.values, result.vanishing, result.constant,
        strict=True,
    )):
        if constant and str(condition.factor) in said:
            continue  # the same structural factor in another subset
        said.add(str(condition.factor))
        if constant:
            out.append(
                f"  {condition.factor} never vanishes on this mechanism: the same value on "
                "every generic configuration (a structural factor, not a singularity condition)"
            )
            out.append(f"    {condition.statement} (never, for this mechanism)")
            out.append(f"    vector form: {condition.expression}   (here: {value:.6g})")
            continue
        flag = "  <- vanishes at this pose" if vanishes else ""
        if vanishes and not singular:  # (the ranks' rtol is the finer test)
            flag = (
                f"  <- near zero here (within {VANISHING_RTOL:g} of its size), but the verdict, "
                "at its rank tolerance, reads regular: close to this singularity, not at it"
            )
        elif vanishes and result.representation:  # the ranks decide there, not the factor
            flag += " (where the diagram does not hold: the verdict below decides)"
        if subsets is None:
            out.append(f"  {label} singularity when {condition.factor} = 0{flag}")
        else:
            out.append(
                f"  subset {subsets[index] + 1}: {label} factor {condition.factor} = 0 (singular "
                f"only where every subset has a vanishing factor){flag}"
            )
        out += [f"    {text}" for text in (condition.statement, result.split_at_pose[index]) if text]
        here = f"{value:.6g}" if math.isfinite(value) else "not defined: " + result.undefined[index]
        out.append(f"    vector form: {condition.expression} = 0   (here: {here})")
    return out
