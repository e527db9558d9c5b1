"""Many views: Dask workers, the command's shards and the whole run write the same files."""

import subprocess
import time

import pytest

import kepler
from kepler.views import render_views

FRAMES = 24


def files(folder):
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def command(kepler_bin, scene, out, *flags):
    subprocess.run([kepler_bin, "render", str(scene), "--turntable", str(FRAMES),
                    "--json", str(out / "f.json"), "--svg", str(out / "f.svg"), "-q", *flags],
                   check=True)


@pytest.fixture(scope="module")
def bunny_whole(kepler_bin, tmp_path_factory, models):
    path = models / "stanford-bunny.obj"
    if not path.is_file():
        pytest.skip(f"no model {path}")
    out = tmp_path_factory.mktemp("whole")
    command(kepler_bin, path, out)
    return path, files(out)


def test_dask_workers_write_the_whole_runs_files(bunny_whole, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    path, whole = bunny_whole
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            start = time.perf_counter()
            written = render_views(path, FRAMES, tmp_path, name="f", outputs=("json", "svg"),
                                   client=client)
            seconds = time.perf_counter() - start
    print(f"render_views on 2 Dask workers: {FRAMES / seconds:.2f} frames/s")
    assert len(written) == 2 * FRAMES
    assert files(tmp_path) == whole


def test_shards_of_the_command_write_the_whole_runs_files(bunny_whole, kepler_bin, tmp_path):
    path, whole = bunny_whole
    for i in range(1, 4):
        command(kepler_bin, path, tmp_path, "--shard", f"{i}/3")
    assert files(tmp_path) == whole


def test_in_process_views_match_the_command(root, kepler_bin, tmp_path):
    scene = root / "scenes/polyhedra.kdl"
    out = tmp_path / "cli"
    out.mkdir()
    command(kepler_bin, scene, out)
    render_views(scene, FRAMES, tmp_path / "py", name="f", outputs=("json", "svg"))
    assert files(tmp_path / "py") == files(out)


def test_a_list_of_cameras_renders_each_as_render_would(root, tmp_path):
    scene_path = root / "scenes/assembly.kdl"
    cameras = [{"dir": (1, 0, 0)}, {"dir": (0, -1, 0), "up": (0, 0, 1)}, {"eye": (5, 4, 3)}]
    written = render_views(scene_path, cameras, tmp_path, name="v", hidden=True)
    assert [p.rsplit("/", 1)[1] for p in written] == ["v-001.json", "v-002.json", "v-003.json"]
    scene = kepler.load(scene_path)
    for camera, path in zip(cameras, written):
        assert open(path).read() == scene.render(hidden=True, **camera).to_json()


def test_bad_outputs_and_cameras_are_refused(root, tmp_path):
    with pytest.raises(ValueError, match="pdf"):
        render_views(root / "scenes/assembly.kdl", 2, tmp_path, outputs=("pdf",))
    with pytest.raises(kepler.KeplerError):
        render_views(root / "scenes/assembly.kdl", 0, tmp_path)
