"""The README's Python examples run, and say what they claim."""

import contextlib
import io
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S)


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_example_runs(index, monkeypatch):
    monkeypatch.chdir(ROOT)
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        exec(compile(BLOCKS[index], f"README block {index}", "exec"), {})  # our own README, not user input
    for expected in re.findall(r"# prints: (.*)", BLOCKS[index]):
        assert expected.strip() in output.getvalue(), (expected, output.getvalue())


def test_readme_has_the_two_commands():
    text = (ROOT / "README.md").read_text()
    assert "<!-- ci:install -->" in text and "<!-- ci:test -->" in text
    assert os.path.exists(ROOT / ".ci" / "run")
