"""Command-line options that do not apply to a subcommand's mode are refused, not ignored
(issue 24), with one line naming the option and the mode (exit status 2). Each refused case below
was silently accepted before (the option dropped); each accepted case is its option's own mode,
answered as before. The audit of every subcommand (`screwkit <command> --help`):

- analyze: --pose with a snapshot and --latex with --no-superbracket were already refused (kept
  here as the reference); an option with a value given twice dropped the first.
- graph: --pose with a snapshot (refused); --equivalent with each --format applies (a TOML file of
  the equivalent graph reads back).
- screw: --point applies to --revolute only.
- map: --grid sets N for axes given as LO HI; a coordinate given twice dropped its first range.
- path, table4, list: every option applies in every mode (--robot is the one repeatable option).
"""

import pytest

from screwkit.interface.cli import main

SNAPSHOT = "examples/planar_3rpr.toml"
MAP = ["map", "h4", "--quantity", "verdict", "--out"]

REFUSED = [
    (["screw", "--prismatic", "0", "0", "1", "--point", "1", "2", "3"], r"--point applies to --revolute only; --prismatic carries no point"),
    (["screw", "--plucker", "0", "0", "1", "0", "0", "0", "--point", "1", "2", "3"], r"--point applies to --revolute only; --plucker carries no point"),
    ([*MAP, "{out}", "--x", "-10", "10", "3", "--y", "-10", "10", "3", "--grid", "7"], r"--grid sets N for the axes given as LO HI, and no axis is .*drop --grid"),
    ([*MAP, "{out}", "--x", "-10", "10", "3", "--y", "5", "--z", "-750", "--grid", "7"], r"--grid sets N for the axes given as LO HI, and no axis is"),
    ([*MAP, "{out}", "--x", "0", "1", "--x", "2", "3", "--y", "0", "1"], r"--x given twice; give it once"),
    (["analyze", "h4", "--pose", "0", "0", "-750", "0", "--pose", "0", "0", "-700", "0"], r"--pose given twice; give it once"),
    (["analyze", "h4", "--rtol", "1e-9", "--rtol", "1e-8"], r"--rtol given twice; give it once"),
    (["analyze", "h4", "--length-scale", "10", "--length-scale", "20"], r"--length-scale given twice"),
    (["graph", "h4", "--format", "dot", "--format", "json"], r"--format given twice"),
    (["graph", "h4", "--out", "{out}", "--out", "{out}"], r"--out given twice"),
    (["path", "h4", "--from", "0", "0", "-750", "0", "--to", "0", "0", "-700", "0", "--samples", "5", "--samples", "9"], r"--samples given twice"),
    (["table4", "--grid", "2", "--grid", "3"], r"--grid given twice"),
    ([*MAP, "{out}", "--out", "{out}", "--x", "0", "1", "--y", "0", "1"], r"--out given twice"),
    # refused before issue 24 too: the references of the messages above
    (["analyze", SNAPSHOT, "--pose", "1", "2", "3"], r"is a snapshot \(one configuration\); --pose does not apply"),
    (["graph", SNAPSHOT, "--pose", "1", "2", "3"], r"is a snapshot \(one configuration\); --pose does not apply"),
    (["analyze", "h4", "--latex", "--no-superbracket"], r"--latex prints the superbracket's conditions; drop --no-superbracket"),
]


@pytest.mark.parametrize(("argv", "pattern"), REFUSED)
def test_an_option_outside_its_mode_is_refused(tmp_path, capsys, argv, pattern):
    status = main([a.replace("{out}", str(tmp_path / "m.json")) for a in argv])
    err = capsys.readouterr().err
    assert status == 2, err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert __import__("re").search(pattern, err), err


ACCEPTED = [
    ["screw", "--revolute", "0", "0", "1", "--point", "1", "2", "3"],
    [*MAP, "{out}", "--x", "-10", "10", "--y", "-10", "10", "3", "--grid", "4"],
    [*MAP, "{out}", "--x", "-10", "10", "3", "--y", "-10", "10", "3"],
    ["table4", "--robot", "h4", "--robot", "v4", "--grid", "2", "--refine", "0"],
]


@pytest.mark.parametrize("argv", ACCEPTED)
def test_each_option_in_its_own_mode_is_answered(tmp_path, capsys, argv):
    assert main([a.replace("{out}", str(tmp_path / "m.json")) for a in argv]) == 0, capsys.readouterr().err


def test_grid_counts_when_an_axis_is_given_as_lo_hi(tmp_path, capsys):
    out = tmp_path / "m.json"
    assert main([*MAP, str(out), "--x", "-10", "10", "--y", "-10", "10", "3", "--grid", "4"]) == 0
    assert "x in [-10, 10] mm (4 values) x y in [-10, 10] mm (3 values)" in capsys.readouterr().out
    assert main([*MAP, str(out), "--x", "-10", "10", "--y", "-10", "10", "3"]) == 0
    assert "(50 values)" in capsys.readouterr().out  # the documented default
