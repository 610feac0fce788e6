"""The docs pages' Python examples run, and say what they claim.

Each page under ``docs/`` (the guide included) is read in order: its ```python blocks share one
namespace, as a reader running them one after the other would; a ``# prints: X`` comment must find
``X`` in what the block printed, a ``# warns: W`` comment a warning of class ``W``, and a block written as an interactive session (``>>>``) is run
as a doctest. The README's blocks are checked by ``tests/test_readme.py``.
"""

import contextlib
import doctest
import io
import re
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = sorted(
    page for page in (*ROOT.joinpath("docs").glob("*.md"), *ROOT.joinpath("docs", "guide").glob("*.md"))
    if "```python" in page.read_text()
)


def _run_session(block: str, namespace: dict, name: str) -> None:
    test = doctest.DocTestParser().get_doctest(block, namespace, name, name, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    report = io.StringIO()
    runner.run(test, out=report.write)
    assert runner.failures == 0, report.getvalue()


@pytest.mark.parametrize("page", PAGES, ids=[str(page.relative_to(ROOT)) for page in PAGES])
def test_docs_page_examples_run(page, monkeypatch):
    monkeypatch.chdir(ROOT)
    namespace: dict = {}
    for index, block in enumerate(re.findall(r"```python\n(.*?)```", page.read_text(), flags=re.S)):
        name = f"{page.relative_to(ROOT)} block {index}"
        if block.lstrip().startswith(">>>"):
            _run_session(block, namespace, name)
            continue
        output = io.StringIO()
        with contextlib.redirect_stdout(output), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            exec(compile(block, name, "exec"), namespace)  # our own docs, not user input
        raised = {type(warning.message).__name__ for warning in caught}
        for expected in re.findall(r"# warns: (\w+)", block):
            assert expected in raised, (name, expected, raised)
        assert raised <= set(re.findall(r"# warns: (\w+)", block)), (name, "unannounced warnings", raised)
        for expected in re.findall(r"# prints: (.*)", block):
            assert expected.strip() in output.getvalue(), (name, expected, output.getvalue())


def test_docs_pages_have_examples():
    assert len(PAGES) >= 5, [str(page) for page in PAGES]
