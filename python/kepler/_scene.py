"""Scenes loaded once and their renders: faces as numpy rings, and the command's outputs."""

import json as _json

from . import _kepler
from ._options import to_flags


def load(path, *, max_faces=None, hierarchy=None, include_root=None):
    """Loads and prepares a scene file or mesh, as ``kepler render`` does.

    ``max_faces`` is the command's ``--max-faces`` (default: what fits a render in 24 GiB);
    ``hierarchy`` its ``--hierarchy`` (``"simplify"`` or ``"median"``; answers are the same
    either way); ``include_root`` its ``--include-root`` (includes and meshes must lie under
    it). Raises :class:`KeplerError` naming the file and line of bad input.
    """
    return Scene(_kepler.load(str(path), load_flags(max_faces, hierarchy, include_root)))


def load_flags(max_faces=None, hierarchy=None, include_root=None):
    """The command's flags of loading, for :func:`load`'s arguments."""
    root = None if include_root is None else str(include_root)
    return to_flags({"max_faces": max_faces, "hierarchy": hierarchy, "include_root": root})


class Scene:
    """A scene loaded and prepared once (its INBOXes and object trees made)."""

    def __init__(self, native):
        self._native = native

    @property
    def path(self):
        """The file the scene was read from."""
        return self._native.path

    @property
    def face_count(self):
        """Faces once instances are placed: the JSON's ids run below it."""
        return self._native.face_count

    @property
    def warnings(self):
        """What the reader had to say about the file."""
        return list(self._native.warnings)

    def render(self, **options):
        """Renders one view: the visible region of every face.

        Keyword arguments are ``kepler render``'s flags by name: the camera (``dir``,
        ``eye``, ``target``, ``fov``, ``ortho``, ``up``), the lines (``edges``, ``crease``,
        ``hidden``) and the drawing (``page``, ``margin``, ``layers``, ``hatch``, ...). They
        stay with the result, which makes its SVG and PNG with them.
        """
        json_text, _, _, warnings = self._native.render(to_flags(options), json=True)
        return Render(self, options, json_text, warnings)

    def __repr__(self):
        return f"<kepler.Scene {self.path!s} ({self.face_count} faces)>"


class Face:
    """One face's visible region: ``polygons`` is a list of polygons, each a list of (N,2)
    float64 rings, the outer ring counter-clockwise first and its holes clockwise after."""

    __slots__ = ("id", "object", "area", "polygons", "section")

    def __init__(self, record, np):
        self.id = record["id"]
        self.object = record["object"]
        self.area = record["area"]
        self.section = record.get("section", False)
        self.polygons = [
            [np.asarray(ring, dtype=np.float64).reshape(-1, 2) for ring in polygon]
            for polygon in record["visible"]
        ]

    def __repr__(self):
        return f"<kepler.Face {self.id} of {self.object!r}, area {self.area}>"


class Render:
    """One view of a scene: its faces, its lines, and the command's outputs for it."""

    def __init__(self, scene, options, json_text, warnings):
        self.scene = scene
        self.options = dict(options)
        self.warnings = list(warnings)
        self._json = json_text
        self._parsed = None
        self._faces = None

    def _data(self):
        if self._parsed is None:
            self._parsed = _json.loads(self._json)
        return self._parsed

    @property
    def camera(self):
        """The JSON's camera: ``projection``, the world-to-screen ``matrix`` (and for a
        perspective camera ``eye`` and ``near``)."""
        return self._data()["camera"]

    @property
    def faces(self):
        """Every face with something visible, in global face order."""
        if self._faces is None:
            import numpy as np

            self._faces = [Face(f, np) for f in self._data()["faces"]]
        return self._faces

    @property
    def lines(self):
        """The drawing's polylines in screen space by kind (``visible``, ``hidden``, ...),
        each an (N,2) float64 array; empty unless ``edges`` or ``hidden`` was given."""
        import numpy as np

        lines = self._data().get("lines", {})
        return {
            kind: [np.asarray(p, dtype=np.float64).reshape(-1, 2) for p in polylines]
            for kind, polylines in lines.items()
        }

    def to_json(self):
        """The ``kepler-visible/1`` set: the bytes of ``kepler render ... --json``."""
        return self._json

    def to_svg(self, **options):
        """The drawing: the bytes of ``kepler render ... --svg``, with the render's options
        and these (``page="a4"``, ``hidden=True``, ``hatch=True``, ...) on top."""
        return self._output(options, svg=True)[1]

    def to_png(self, **options):
        """The picture: the bytes of ``kepler render ... --png``, options as :meth:`to_svg`."""
        return self._output(options, png=True)[2]

    def _output(self, options, **want):
        flags = to_flags({**self.options, **options})
        return self.scene._native.render(flags, **want)

    def __repr__(self):
        return f"<kepler.Render of {self.scene.path!s}: {len(self.faces)} faces visible>"
