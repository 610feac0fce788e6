"""The notebook gallery: ``notebooks/*.ipynb`` copied into ``docs/gallery/`` for myst-nb to render.

``SCREWKIT_EXECUTED_NOTEBOOKS`` names a folder holding an executed copy of every notebook (the test
suite's own runs, ``tests/test_notebooks.py``): those copies are rendered as they are and nothing
is executed again. Without it, the committed notebooks (without outputs) are copied and myst-nb
executes them during the build.
"""

import os
import shutil
from pathlib import Path

ENVIRONMENT_VARIABLE = "SCREWKIT_EXECUTED_NOTEBOOKS"


def prepare(docs: Path) -> str:
    """Fill ``docs/gallery`` and return myst-nb's execution mode for it (``"off"`` or ``"force"``)."""
    notebooks = sorted((docs.parent / "notebooks").glob("*.ipynb"))
    executed = os.environ.get(ENVIRONMENT_VARIABLE)
    copies = [Path(executed) / n.name for n in notebooks] if executed else []
    missing = [c for c in copies if not c.is_file()]
    if missing:
        raise FileNotFoundError(f"{ENVIRONMENT_VARIABLE}={executed} lacks {', '.join(c.name for c in missing)}")
    folder = docs / "gallery"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir()
    for source, copy in zip(notebooks, copies or notebooks, strict=True):
        shutil.copy2(copy, folder / source.name)
    return "off" if copies else "force"
