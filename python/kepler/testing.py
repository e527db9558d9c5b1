"""pytest helpers: assert that a render matches a golden visible-polygon set."""

import os
from pathlib import Path

from ._compare import compare


def assert_matches_golden(result, golden, tol=1e-9, update=None):
    """Fails, listing every changed face with its area change, unless ``result`` (a Render)
    matches the ``kepler-visible/1`` file ``golden`` within ``tol``.

    With ``update`` true (default: the environment's ``KEPLER_UPDATE_GOLDENS=1``), writes the
    render to ``golden`` instead; a missing golden fails with that hint.
    """
    golden = Path(golden)
    if update is None:
        update = os.environ.get("KEPLER_UPDATE_GOLDENS") == "1"
    if update:
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text(result.to_json(), encoding="utf-8")
        return
    if not golden.is_file():
        raise AssertionError(f"no golden {golden}: run with KEPLER_UPDATE_GOLDENS=1 to write it")
    comparison = compare(golden, result, tol=tol)
    if not comparison.same:
        raise AssertionError(f"{golden}: {comparison}")
