"""The notebooks of ``notebooks/`` run top to bottom (docs/architecture.md §7).

Each notebook is executed in a fresh Python kernel by nbclient, in the ``notebooks/`` folder, with
the package as installed; an error or a failed ``assert`` in any cell fails the test, with the
cell's traceback. Notebooks are committed without outputs, which is checked too. Each executed
notebook is saved for the docs build of the same session (``executed_notebooks`` in conftest.py).
"""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
#: Seconds one cell may take (each notebook runs in well under a minute on a 2-core machine).
CELL_TIMEOUT = 120
EXPECTED = [
    "01_h4_walkthrough.ipynb",
    "02_paper_004_robots.ipynb",
    "03_custom_mechanism.ipynb",
    "04_planar_3rrp.ipynb",
    "certify.ipynb",
]


def test_the_notebooks_are_there():
    assert sorted(p.name for p in NOTEBOOKS.glob("*.ipynb")) == EXPECTED


@pytest.mark.parametrize("name", EXPECTED)
def test_notebook_is_committed_without_outputs(name):
    notebook = nbformat.read(NOTEBOOKS / name, as_version=4)
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    assert code, f"{name} has no code cell"
    assert all(not cell.outputs and cell.execution_count is None for cell in code), (
        f"{name} is committed with outputs: clear them before committing"
    )


@pytest.mark.parametrize("name", EXPECTED)
def test_notebook_runs(name, monkeypatch, executed_notebooks):
    monkeypatch.setenv("MPLBACKEND", "Agg")  # no display; figures are still drawn
    # the kernel imports this checkout's package (a worktree's, not another checkout's install)
    monkeypatch.setenv("PYTHONPATH", str(NOTEBOOKS.parent))
    notebook = nbformat.read(NOTEBOOKS / name, as_version=4)
    client = NotebookClient(
        notebook,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        resources={"metadata": {"path": str(NOTEBOOKS)}},
    )
    try:
        client.execute()
    except CellExecutionError as err:
        pytest.fail(f"{name} failed:\n{err}", pytrace=False)
    nbformat.write(notebook, executed_notebooks / name)
