"""Tests of the command line: compared with the library's own results."""

import json

import numpy as np
import pytest

from screwkit import Screw
from screwkit.cli import main


def test_screw_command_json_matches_library(capsys):
    assert main(["screw", "--revolute", "0", "0", "2", "--point", "1", "2", "3", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    expected = Screw.revolute([0, 0, 2], [1, 2, 3]).to_dict()
    assert printed["kind"] == expected["kind"] == "zero pitch"
    np.testing.assert_allclose(printed["coords"], expected["coords"])
    np.testing.assert_allclose(printed["point"], [1, 2, 0])


def test_screw_command_text(capsys):
    assert main(["screw", "--prismatic", "0", "1", "0"]) == 0
    assert "pitch inf  kind infinite pitch" in capsys.readouterr().out


def test_no_command_prints_help(capsys):
    assert main([]) == 0
    assert "usage: screwkit" in capsys.readouterr().out


def test_error_revolute_without_point(capsys):
    assert main(["screw", "--revolute", "0", "0", "1"]) == 2
    assert capsys.readouterr().err.strip() == "screwkit screw: error: --revolute needs --point X Y Z"


def test_error_zero_direction_is_one_line_on_stderr(capsys):
    assert main(["screw", "--prismatic", "0", "0", "0"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Expected `direction` to be a non-zero direction" in err


def test_error_unparsable_number_exits_2():
    with pytest.raises(SystemExit) as exit_info:
        main(["screw", "--prismatic", "0", "x", "0"])
    assert exit_info.value.code == 2
