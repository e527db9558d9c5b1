"""Many views of one scene on a Dask cluster: each worker loads and prepares the scene once
and renders its share of the frames, into the files the command's whole run would write.

Dask rather than Ray: its wheels are pure Python (a few MB against Ray's hundreds), a
``LocalCluster`` starts in a second on a laptop or a CI machine, and the same code runs on
a cluster of many machines (``dask.distributed.Client("scheduler:8786")``).
"""

import os
from pathlib import Path

from . import _kepler
from ._options import to_flags
from ._scene import load_flags

OUTPUTS = ("json", "svg", "png")


def render_views(scene_path, cameras, out_dir, *, name="frame", outputs=("json",), client=None,
                 shards=None, max_faces=None, hierarchy=None, **options):
    """Renders many views of ``scene_path`` into ``out_dir``; returns the files written.

    ``cameras`` is a number N (a turntable of N views, as ``--turntable N``), a views file
    (as ``--views FILE``: one line of camera flags per view), or a list of dicts of camera
    options (``{"dir": (1, 0, 0)}``, ...), each over ``options``. Files are named as the
    command names them: ``out_dir/NAME-01.json`` and so on, for each of ``outputs``
    (``"json"``, ``"svg"``, ``"png"``), byte for byte the command's.

    With a Dask ``client`` the frames are split into ``shards`` parts (default: one a
    worker), frame k going to shard k mod shards, as ``--shard I/K`` splits them; each part
    is one task that loads the scene once. Without one, they render here.
    """
    for kind in outputs:
        if kind not in OUTPUTS:
            raise ValueError(f"outputs: {kind!r} is not one of {OUTPUTS}")
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    base = {str(kind): str(out_dir / f"{name}.{kind}") for kind in outputs}
    jobs = _jobs(str(scene_path), cameras, options, max_faces, hierarchy)
    for flags in jobs.per_view or [jobs.flags]:
        _kepler.check_flags(jobs.scene_path, flags, jobs.per_view is not None)
    if client is None:
        return _run(jobs, base, range(jobs.count()))
    if shards is None:
        shards = max(1, len(client.scheduler_info()["workers"]))
    parts = [list(range(i, jobs.count(), shards)) for i in range(shards)]
    futures = [client.submit(_run, jobs, base, part, pure=False) for part in parts if part]
    written = [path for done in client.gather(futures) for path in done]
    return sorted(written)


class _Jobs:
    """What every worker needs to render any frame: picklable, the scene loaded lazily."""

    def __init__(self, scene_path, flags, per_view, max_faces, hierarchy, count=None):
        self.scene_path = scene_path
        self.flags = flags
        self.per_view = per_view
        self.max_faces = max_faces
        self.hierarchy = hierarchy
        self._count = len(per_view) if per_view is not None else count

    def count(self):
        """The number of views (a views file's are counted by the command's own reader)."""
        if self._count is None:
            self._count = self.load().frame_count(self.flags)
        return self._count

    def load(self):
        return _kepler.load(self.scene_path, load_flags(self.max_faces, self.hierarchy))


def _jobs(scene_path, cameras, options, max_faces, hierarchy):
    if isinstance(cameras, bool):
        raise TypeError("cameras: a number of turntable views, a views file or a list of dicts")
    if isinstance(cameras, int):
        return _Jobs(scene_path, to_flags({**options, "turntable": cameras}), None, max_faces,
                     hierarchy, count=cameras)
    if isinstance(cameras, (str, os.PathLike)):
        return _Jobs(scene_path, to_flags({**options, "views": str(cameras)}), None, max_faces,
                     hierarchy)
    per_view = [to_flags({**options, **dict(camera)}) for camera in cameras]
    return _Jobs(scene_path, to_flags(options), per_view, max_faces, hierarchy)


def _run(jobs, base, frames):
    """Renders `frames` of `jobs` with one load of the scene; returns the files written."""
    frames = list(frames)
    if not frames:
        return []
    scene = jobs.load()
    want = {kind: True for kind in base}
    total = jobs.count()
    written = []
    for k in frames:
        if jobs.per_view is None:
            (made,) = scene.render_frames(jobs.flags, [k], **want)
        else:
            made = scene.render(jobs.per_view[k], **want)
        for kind, value in zip(OUTPUTS, made[:3]):
            if kind in base:
                path = Path(_kepler.frame_path(base[kind], k, total))
                _write(path, value.encode() if isinstance(value, str) else value)
                written.append(str(path))
    return written


def _write(path, data):
    """Writes `data` to `path` through a temporary beside it, so no reader sees half a file."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(data)
    os.replace(tmp, path)
