"""The HTML of an :class:`~screwkit.interface.analysis_report.AnalysisReport` for Jupyter: its sections
as headings and its lists as tables (the wrenches on the platform, the wrench diagram's lines and
points, the superbracket's conditions), the same content as the report's text.

Examples
--------
>>> from screwkit.interface.report import analyze
>>> page = report_html(analyze("h4", superbracket=False))
>>> page.count("<table>") >= 4, "<h4>wrench systems</h4>" in page
(True, True)
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from typing import Any

from ..algebra.display import html_section, html_table, number_text

__all__ = ["report_html"]


def _vector(values: Any) -> str:
    return "(" + ", ".join(number_text(v, 4) for v in values) + ")"


def _line_cells(item: dict[str, Any]) -> list[str]:
    """Kind, direction, a point, pitch of a wrench or twist described as a line."""
    if item.get("point") is None:
        return [item["kind"], _vector(item["direction"]) if "direction" in item else "", "", ""]
    return [item["kind"], _vector(item["direction"]), _vector(item["point"]), number_text(item["pitch"], 3)]


def _pre(lines: list[str]) -> str:
    return "<pre>" + html.escape("\n".join(lines)) + "</pre>"


def report_html(report: Any, tail: Sequence[str] = ()) -> str:
    """The report as HTML: a heading, the pose, the twist graph, the platform's twists and the
    wrenches (tables), the wrench diagram (lines and points), the superbracket and its conditions
    (table), the verdict, the Jacobians and the transmission.

    Parameters
    ----------
    report : AnalysisReport
    tail : sequence of str, optional
        Lines of text shown last, preformatted (the report's Jacobians and transmission).

    Returns
    -------
    str
        HTML (every text escaped).

    Examples
    --------
    >>> from screwkit.interface.report import analyze
    >>> "<th>vanishes here</th>" in report_html(analyze("h4"))
    True
    """
    unit = report.length_unit
    where = html.escape(report.pose_words())
    out = [f"<h3>{html.escape(report.name)}</h3><p>{html.escape(report.source)}<br>pose: {where}</p>"]
    summary = report.graph_summary()
    joints = ", ".join(f"{count} {kind}" for kind, count in summary["joints"].items())
    out.append(
        html_section(
            "twist graph",
            _pre(
                [
                    f"{summary['links']} links, joints: {joints}; {summary['loops']} loops",
                    f"actuated: {', '.join(summary['actuated'])}",
                ]
            ),
        )
    )
    wrenches = report.wrenches()
    twists = wrenches["platform_twists"]
    header = ["kind", "direction", f"point ({unit})" if unit else "point", "pitch"]
    out.append(
        html_section(
            f"platform twist system: {twists['motion_type']} (order {wrenches['platform_twist_order']})",
            html_table(header, [_line_cells(t) for t in twists["basis"]]),
        )
    )
    rows = [["constraint", item["leg"], *_line_cells(item)] for item in wrenches["constraint"]]
    rows += [["actuation", item["joint"], *_line_cells(item)] for item in wrenches["actuation"]]
    out.append(
        html_section(
            "wrench systems",
            html_table(["role", "leg or joint", *header], rows)
            + f"<p>global wrench system: order {wrenches['global_order']}</p>",
        )
    )
    diagram = report.diagram
    lines = [
        ("".join(line), name, role)
        for line, name, role in zip(diagram.lines, diagram.line_names, diagram.roles, strict=True)
    ]
    points = [(p.label, "yes" if p.at_infinity else "", p.description) for p in diagram.points]
    out.append(
        html_section(
            f"wrench diagram {diagram.line_text()}",
            html_table(["line", "wrench", "role"], lines)
            + html_table(["point", "at infinity", "description"], points)
            + "".join(f"<p>degenerate here: {html.escape(reason)}</p>" for reason in diagram.degenerate),
        )
    )
    out.append(html_section("superbracket", _superbracket_html(report)))
    out.append(report.verdict._repr_html_())
    if tail:
        out.append(_pre(list(tail)))
    return "".join(out)


def _superbracket_html(report: Any) -> str:
    result = report.superbracket
    if result is None:
        return f"<p>{html.escape(report.superbracket_note)}</p>"
    factored = (
        result.statement()  # redundant actuation: the six-line subsets
        if hasattr(result, "subsets")
        else f"{report.diagram.line_text()} = {result.simplification.factored}"
    )
    rows = [
        [
            "never (a structural factor)" if constant else label,
            str(condition.factor),
            condition.statement,
            str(condition.expression),
            number_text(value, 6),
            "yes" if vanishes else "",
        ]
        for condition, label, value, vanishes, constant in zip(
            result.conditions, result.labels, result.values, result.vanishing, result.constant, strict=True
        )
    ]
    header = ["label", "factor = 0", "when", "vector form", "value here", "vanishes here"]
    return f"<p>{html.escape(factored)}</p><p>{html.escape(report.superbracket_note)}</p>" + html_table(
        header, rows
    )
