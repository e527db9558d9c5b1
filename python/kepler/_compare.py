"""Regression diffs of visible-polygon sets: which faces changed, and by how much."""

import json as _json
import os
from dataclasses import dataclass

from . import _kepler


@dataclass(frozen=True)
class FaceChange:
    """One face that differs by more than the tolerance."""

    id: int
    object: str
    kind: str  # "changed", "added" (newly visible) or "removed" (no longer visible)
    golden_area: float
    current_area: float
    area_delta: float
    xor_area: float  # the area of the symmetric difference of the two regions
    relative: float  # xor_area relative to the face's size: what the tolerance bounds


class Comparison:
    """What :func:`compare` found: ``kepler diff``'s report (``kepler-diff/1``)."""

    def __init__(self, report_json):
        self._json = report_json
        data = _json.loads(report_json)
        self.tol = data["tol"]
        self.compared = data["compared"]
        self.camera_differs = data["camera_differs"]
        self.faces = [FaceChange(**c) for c in data["changes"]]

    def _ids(self, kind):
        return [f.id for f in self.faces if f.kind == kind]

    @property
    def changed(self):
        """Ids of faces visible in both whose regions differ."""
        return self._ids("changed")

    @property
    def added(self):
        """Ids of faces visible now and not in the golden set."""
        return self._ids("added")

    @property
    def removed(self):
        """Ids of faces visible in the golden set and not now."""
        return self._ids("removed")

    @property
    def same(self):
        """Whether no face differs by more than the tolerance."""
        return not self.faces

    def __bool__(self):
        return self.same

    def to_json(self):
        """The ``kepler-diff/1`` report: the bytes of ``kepler diff --report json``."""
        return self._json

    def __str__(self):
        if self.same:
            return f"same: {self.compared} faces compared (tolerance {self.tol:g})"
        lines = [f"{len(self.faces)} face{'s' if len(self.faces) != 1 else ''} changed "
                 f"(of {self.compared} compared, tolerance {self.tol:g})"]
        for f in self.faces:
            lines.append(f"  face {f.id} ({f.object}): {f.kind}, area {f.golden_area:.6e} -> "
                         f"{f.current_area:.6e} ({f.area_delta:+.3e}), symmetric difference "
                         f"{f.xor_area:.3e} ({f.relative:.3e} of its size)")
        return "\n".join(lines)

    def __repr__(self):
        return f"<kepler.Comparison: {len(self.faces)} faces differ>"


def _text_and_name(value, role):
    """A set given as a Render, a path, or JSON text -> (JSON text, the name errors use)."""
    if hasattr(value, "to_json"):
        return value.to_json(), f"<{role} render>"
    if isinstance(value, os.PathLike) or (isinstance(value, str) and not value.lstrip().startswith("{")):
        path = os.fspath(value)
        try:
            with open(path, encoding="utf-8") as f:
                return f.read(), path
        except OSError as e:
            raise _kepler.KeplerError(f"{path}: {e.strerror}") from e
    if isinstance(value, (bytes, bytearray)):
        value = value.decode("utf-8")
    if isinstance(value, str):
        return value, f"<{role} JSON>"
    raise TypeError(f"{role}: a Render, a path or kepler-visible/1 JSON text, not {value!r}")


def compare(golden, current, tol=1e-9):
    """Compares two visible-polygon sets face by face, as ``kepler diff`` does.

    ``golden`` and ``current`` are each a :class:`Render`, a path to a ``kepler-visible/1``
    file, or its JSON text. A face differs when the symmetric difference of its two visible
    regions, relative to its size, exceeds ``tol``; faces that appear or vanish are judged
    the same way. Returns a :class:`Comparison` (``.changed``, ``.added``, ``.removed``,
    ``.faces`` with area deltas, ``.same``).
    """
    golden_text, golden_name = _text_and_name(golden, "golden")
    current_text, current_name = _text_and_name(current, "current")
    return Comparison(_kepler.diff(golden_text, golden_name, current_text, current_name, float(tol)))
