"""kepler: exact hidden-surface removal for polyhedral scenes.

Load a scene file (.kdl), a mesh (.obj, .stl, .ply) or a glTF/3MF scene (.gltf, .glb, .3mf)
once, render it in as many views as you like, and get for every face its exact visible
region: numpy rings in screen space, the command's canonical JSON, its plotter SVG or its
PNG. Every keyword argument of :meth:`Scene.render` is a flag of ``kepler render`` by the
same name (``edges="all"`` is ``--edges all``, ``hatch_spacing=2`` is ``--hatch-spacing
2``), so the outputs are the command's bytes for the same options.
"""

from ._kepler import KeplerError, __version__
from ._compare import Comparison, FaceChange, compare
from ._scene import Face, Render, Scene, load

__all__ = ["Comparison", "Face", "FaceChange", "KeplerError", "Render", "Scene", "compare",
           "load", "__version__"]
