"""The command line: output compared with the library's own report; bad arguments."""

import json
import math
import re

import numpy as np
import pytest

from screwkit import Screw
from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.robots.catalog import list_mechanisms, load_mechanism

from ..robots.test_h4 import singular_pose


@pytest.fixture(scope="module")
def h4_json():
    """`screwkit analyze h4 --pose ... --json` output, and the library's report at the same pose."""
    import contextlib
    import io

    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        status = main(["analyze", "h4", "--pose", "30", "-20", "-750", "17", "--json"])
    pose = np.array([30.0, -20.0, -750.0, math.radians(17.0)])
    return status, json.loads(output.getvalue()), analyze("h4", pose)


def test_analyze_json_equals_the_library_report(h4_json):
    status, printed, report = h4_json
    assert status == 0
    assert printed == json.loads(json.dumps(report.to_dict(), ensure_ascii=False))


def test_analyze_json_content_is_the_h4_of_paper_002(h4_json):
    _, printed, _ = h4_json
    assert printed["pose"]["phi"] == pytest.approx(math.radians(17.0))
    assert printed["diagram"]["lines"] == ["ab", "cd", "ef", "gh", "ij", "kj"]
    assert printed["superbracket"]["simplification"]["factored"]["text"] == "-[gikj][a b d ḟ][c g ḣ j]"
    labels = [c["label"] for c in printed["superbracket"]["conditions"]]
    assert labels == ["constraint", "actuation"]
    assert printed["verdict"]["verdict"] == "regular"
    assert printed["wrenches"]["global_order"] == 6
    kinds = [w["kind"] for w in printed["wrenches"]["actuation"]]
    assert kinds == ["force (finite line)"] * 4


def test_analyze_text_has_every_section(capsys):
    assert main(["analyze", "h4"]) == 0
    text = capsys.readouterr().out
    for heading in ("twist graph", "wrench systems", "wrench diagram", "superbracket", "conditions", "verdict"):
        assert f"\n{heading}" in text
    assert str(analyze("h4")) == text.rstrip("\n")


def test_analyze_latex_prints_the_h4_conditions(capsys):
    assert main(["analyze", "h4", "--latex"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == r"\begin{align*}" and lines[-1] == r"\end{align*}"
    assert lines[1] == r"[ab,\,cd,\,ef,\,gh,\,ij,\,kj] &= -[gikj][abd\dot{f}][cg\dot{h}j] \\"
    # paper 002 Eqs. (6) and (7), labelled constraint and actuation
    assert lines[2].startswith(r"\text{constraint}:\quad [gikj] = 0 &\iff \left(\mathbf{i} \times")
    assert lines[3].startswith(r"\text{actuation}:\quad [abd\dot{f}][cg\dot{h}j] = 0 &\iff")


def test_analyze_a_singular_pose_reports_the_label(capsys):
    pose = singular_pose(1)  # a root of paper 002's Eq. (7)
    args = [repr(float(pose[0])), repr(float(pose[1])), repr(float(pose[2])), repr(math.degrees(pose[3]))]
    assert main(["analyze", "h4", "--no-superbracket", "--json", "--pose", *args]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["verdict"]["labels"] == ["actuation"]
    assert printed["superbracket"] is None and printed["superbracket_note"] == "not computed"


def test_analyze_a_snapshot_file(capsys, tmp_path):
    from ..robots.test_catalog import EXAMPLES

    assert main(["analyze", str(EXAMPLES / "planar_3rpr.toml"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["verdict"]["verdict"] == "regular" and printed["pose"] is None


def test_list(capsys):
    assert main(["list", "--json"]) == 0
    entries = json.loads(capsys.readouterr().out)
    assert [e["name"] for e in entries] == list_mechanisms()
    assert entries[0]["title"] == load_mechanism(entries[0]["name"]).name


def test_screw_command_json_matches_library(capsys):
    assert main(["screw", "--revolute", "0", "0", "2", "--point", "1", "2", "3", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    expected = Screw.revolute([0, 0, 2], [1, 2, 3]).to_dict()
    assert printed["kind"] == expected["kind"] == "zero pitch"
    np.testing.assert_allclose(printed["coords"], expected["coords"])


def test_no_command_prints_help(capsys):
    assert main([]) == 0
    assert "usage: screwkit" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "status", "message"),
    [
        (["analyze", "h5"], 2, "screwkit analyze: error: unknown mechanism 'h5': expected one of"),
        (["analyze", "h4", "--pose", "1", "2", "3"], 2, "--pose expects 4 finite numbers (X Y Z PHI), got 1.0 2.0 3.0"),
        (["analyze", "h4", "--pose", "0", "0", "x", "0"], 2, "argument --pose: invalid float value: 'x'"),
        (["analyze", "h4", "--pose", "0", "0", "nan", "0"], 2, "--pose expects 4 finite numbers"),
        (["analyze", "h4", "--pose", "0", "0", "-2000", "17"], 1, "screwkit analyze: error: Pose (x, y, z, phi) = (0, 0, -2000, 0.296706 rad = 17 deg) is out of reach"),
        (["analyze", "missing.toml"], 1, "missing.toml: cannot read the file"),
        (["frobnicate"], 2, "invalid choice: 'frobnicate'"),
        (["analyze", "h4", "--latex", "--no-superbracket"], 2, "--latex prints the superbracket's conditions"),
        (["analyze", "h4", "--latex", "--json"], 2, "argument --json: not allowed with argument --latex"),
        (["screw", "--revolute", "0", "0", "1"], 2, "screwkit screw: error: --revolute needs --point X Y Z"),
        (["screw", "--prismatic", "0", "0", "0"], 2, "--prismatic: Expected `direction` to be a non-zero direction"),
        (["screw", "--revolute", "0", "0", "0", "--point", "0", "0", "0"], 2,
         "screwkit screw: error: --revolute: Expected `direction` to be a non-zero direction"),
        # one rule in every command (issue 19): a value the analysis refuses as an argument is bad input
        # (2, as argparse's usage errors), an analysis that cannot be done is 1
        (["map", "h4", "--quantity", "condition:99", "--z", "-800", "-700", "--phi", "0", "10", "--out", "m.json"],
         2, "screwkit map: error: Expected `quantity` 'condition:K' with K in 0..1"),
        (["map", "examples/planar_3rpr.toml", "--quantity", "lti", "--x", "0.5", "0.6", "--y", "0.35", "0.45",
          "--out", "m.json"], 2, "quantity 'wrench_lti'"),
    ],
)
def test_bad_arguments_exit_non_zero_with_one_line(argv, status, message, capsys):
    assert main(argv) == status
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.count("\n") == 1 and message in captured.err, captured.err


def test_out_of_reach_names_the_limbs(capsys):
    main(["analyze", "h4", "--pose", "0", "0", "-2000", "0"])
    assert "limb(s) 1, 2, 3, 4" in capsys.readouterr().err


def test_negative_pose_coordinates_in_exponent_form(capsys):
    # argparse's own pattern took -7.5e2 for an option ("unrecognized arguments")
    assert main(["analyze", "h4", "--pose", "0", "0", "-7.5e2", "-1e1", "--no-superbracket", "--json"]) == 0
    pose = json.loads(capsys.readouterr().out)["pose"]
    assert pose["z"] == -750.0 and pose["phi"] == pytest.approx(math.radians(-10.0))


def test_text_report_falls_back_where_stdout_cannot_encode(capsys, monkeypatch):
    import io
    import sys

    stream = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    monkeypatch.setattr(sys, "stdout", stream)
    assert main(["analyze", "h4"]) == 0
    stream.flush()
    text = stream.buffer.getvalue().decode("ascii")
    assert "\\u1e1f" in text  # the dotted f of the factored superbracket, escaped


def test_a_mistyped_mechanism_name_gets_the_closest_one(capsys):
    assert main(["analyze", "quatro"]) == 2
    assert "unknown mechanism 'quatro' (did you mean 'quattro'?)" in capsys.readouterr().err


def test_progress_names_each_stage_in_order(capsys, monkeypatch):
    from pathlib import Path

    import screwkit as sk
    from screwkit.interface.report import STAGES

    monkeypatch.chdir(Path(__file__).resolve().parents[2])
    seen = []
    analyze("h4", progress=seen.append)
    assert seen == list(STAGES)
    assert main(["analyze", "examples/planar_3rpr.toml", "--progress"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert [line.split(" s  ", 1)[1] for line in err] == [f"{stage} ..." for stage in STAGES]
    assert main(["analyze", "h4", "--no-superbracket", "--no-progress"]) == 0
    assert capsys.readouterr().err == ""
    with pytest.raises(sk.ScrewkitTypeError, match="Expected `progress` to be callable, got int"):
        analyze("h4", progress=5)


def test_screw_text_gives_the_axis(capsys):
    # by hand: the revolute about z through (1, 2, 0) is (0, 0, 1; p x w) = (0, 0, 1; 2, -1, 0)
    assert main(["screw", "--revolute", "0", "0", "1", "--point", "1", "2", "0"]) == 0
    assert capsys.readouterr().out.strip() == (
        "screw (0, 0, 1; 2, -1, 0)  pitch 0  kind zero pitch  axis through (1, 2, 0) along (0, 0, 1)"
    )


def test_the_text_report_prints_no_negative_zero(capsys):
    # a new user saw "direction (-0, 0, 1) through (-0, 89.75, -0)" at --rtol 0.05: a -0.0 coordinate
    # is printed as 0
    assert main(["analyze", "h4", "--rtol", "0.05", "--no-superbracket"]) == 0
    text = capsys.readouterr().out
    assert "through (" in text and "rank tolerance: rtol = 0.05 (default 1e-09)" in text
    assert not re.search(r"(?<![\w.])-0(?![.\de])", text), text


@pytest.mark.parametrize(
    ("arguments", "status"),
    [(["analyze", "planar_3rrp", "--no-superbracket"], 0), (["list", "--json"], 0),
     (["analyze", "no_such_robot"], 2), (["analyze", "h4", "--pose", "0", "0", "-5000", "0"], 1)],
)
def test_the_command_gives_mains_output_and_exit_status(arguments, status, capsys):
    # `python -m screwkit` (and the console script) run console(): main(), then its objects frozen
    # for the exit; the same output, error message and exit status as main() in this process
    import os
    import subprocess
    import sys

    expected = main(arguments)
    out, err = capsys.readouterr()
    done = subprocess.run([sys.executable, "-m", "screwkit", *arguments], capture_output=True, text=True,
                          timeout=120, encoding="utf-8", env={**os.environ, "PYTHONIOENCODING": "utf-8"})
    assert (done.returncode, done.stdout, done.stderr) == (status, out, err)
    assert expected == status and (out if status == 0 else err)  # something was written


def test_a_given_length_scale_is_used_said_and_in_the_json(capsys):
    assert main(["analyze", "h4", "--no-superbracket", "--json"]) == 0
    default = json.loads(capsys.readouterr().out)
    derived = analyze("h4", superbracket=False).analysis.length_scale
    assert default["verdict"]["length_scale"] == derived and default["verdict"]["rtol"] == 1e-9
    assert main(["analyze", "h4", "--no-superbracket"]) == 0
    assert "length scale" not in capsys.readouterr().out
    assert main(["analyze", "h4", "--no-superbracket", "--length-scale", "5000"]) == 0
    assert "length scale: 5000 mm (given; default: derived from the screws)" in capsys.readouterr().out
    assert main(["analyze", "h4", "--no-superbracket", "--length-scale", "5000", "--json"]) == 0
    given = json.loads(capsys.readouterr().out)["verdict"]
    assert given["length_scale"] == 5000.0 and given["closeness"] != default["verdict"]["closeness"]
    assert given["verdict"] == default["verdict"]["verdict"] == "regular"


def test_a_given_length_scale_reaches_graphs_and_batches():
    h4 = load_mechanism("h4")
    report = analyze(h4.twist_graph(), length_scale=5000.0, superbracket=False)
    assert report.given_length_scale == 5000.0 and report.analysis.length_scale == 5000.0
    posed = h4.at([[0, 0, -750, 0], [30, -20, -750, 0.3]], length_scale=5000.0)
    assert posed.singularities.analysis.length_scale.tolist() == [5000.0, 5000.0]
    assert posed[1].analysis.length_scale == 5000.0 and "length_scale=5000" in repr(posed)
    assert posed[1].singularity.closeness == {k: float(v[1]) for k, v in posed.closeness.items()}


def test_map_writes_a_png(tmp_path):
    # the README's `screwkit map ... --out lti.png`: drawn by screwkit.interface.plot.save_map_png
    # (WorkspaceMap.save writes data only); lost once in a merge, with no test to say so
    pytest.importorskip("matplotlib")
    out = tmp_path / "lti.png"
    argv = ["map", "h4", "--quantity", "lti", "--z", "-1000", "-550", "--phi", "-45", "45", "--grid", "4",
            "--out", str(out), "--no-progress"]
    assert main(argv) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
