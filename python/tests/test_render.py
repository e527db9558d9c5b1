"""The Python package against the command: the same bytes for the same options."""

import subprocess

import numpy as np
import pytest

import kepler


def cli(kepler_bin, tmp_path, scene, flags, ext):
    out = tmp_path / f"out.{ext}"
    subprocess.run([kepler_bin, "render", str(scene), *flags, f"--{ext}", str(out), "-q"], check=True)
    return out.read_bytes()


def test_the_readme_example(root):
    scene = kepler.load(root / "scenes/assembly.kdl")
    r = scene.render(dir=(-1, -2, -3), up=(0, 1, 0), edges="all", hidden=True)
    assert r.faces, "the assembly has visible faces"
    face = r.faces[0]
    assert isinstance(face.id, int) and face.object and face.area > 0
    ring = face.polygons[0][0]
    assert ring.dtype == np.float64 and ring.ndim == 2 and ring.shape[1] == 2
    assert set(r.lines) >= {"visible", "hidden"} and r.lines["hidden"]
    assert r.to_json().startswith('{"format":"kepler-visible/1"')
    svg = r.to_svg(page="a4", hidden=True)
    assert svg.startswith("<svg") and 'width="210mm"' in svg and 'height="297mm"' in svg


def shoelace(ring):
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def test_areas_are_the_rings_areas(root):
    r = kepler.load(root / "scenes/polyhedra.kdl").render()
    for face in r.faces:
        area = sum(shoelace(ring) for polygon in face.polygons for ring in polygon)
        assert area == pytest.approx(face.area, rel=1e-9, abs=1e-12)
        for polygon in face.polygons:
            assert shoelace(polygon[0]) > 0, "outer rings turn counter-clockwise"
            assert all(shoelace(hole) < 0 for hole in polygon[1:]), "holes turn clockwise"


CASES = [
    ("scenes/assembly.kdl", {}),
    ("scenes/polyhedra.kdl", {"edges": "all", "hidden": True}),
    ("scenes/town.kdl", {"dir": (-1, -2, -3), "up": (0, 1, 0)}),
    # glTF (with its camera) and 3MF scenes load through the library as through the command.
    ("tests/fixtures/scenes/cube_nodes.glb", {}),
    ("tests/fixtures/scenes/cube_parts.3mf", {"dir": (-1, -2, -3), "up": (0, 1, 0)}),
]


def flags_of(options):
    return kepler._options.to_flags(options)


@pytest.mark.parametrize("path,options", CASES)
def test_json_and_svg_are_the_commands_bytes(root, kepler_bin, tmp_path, path, options):
    r = kepler.load(root / path).render(**options)
    assert r.to_json().encode() == cli(kepler_bin, tmp_path, root / path, flags_of(options), "json")
    page = {"page": "a4", "hatch": True}
    svg = r.to_svg(**page).encode()
    assert svg == cli(kepler_bin, tmp_path, root / path, flags_of({**options, **page}), "svg")


@pytest.mark.parametrize("name", ["cow.obj", "stanford-bunny.obj"])
def test_shared_meshes_are_the_commands_bytes(model, kepler_bin, tmp_path, name):
    path = model(name)
    options = {"eye": (1.5, 1.0, 2.5), "target": (0, 0, 0), "fov": 35} if name == "cow.obj" else {}
    r = kepler.load(path).render(**options)
    assert r.to_json().encode() == cli(kepler_bin, tmp_path, path, flags_of(options), "json")
    svg = r.to_svg(page="a4", hidden=True).encode()
    assert svg == cli(kepler_bin, tmp_path, path, flags_of({**options, "page": "a4", "hidden": True}), "svg")


def test_png_is_a_png(root):
    png = kepler.load(root / "scenes/assembly.kdl").render().to_png(size=64)
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_scene_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 x\nf 1 2 3\n")
    with pytest.raises(kepler.KeplerError, match=r"bad\.obj:3"):
        kepler.load(bad)


def test_missing_file_is_an_error(tmp_path):
    with pytest.raises(kepler.KeplerError, match="nope.obj"):
        kepler.load(tmp_path / "nope.obj")


def test_unknown_option_is_named(root):
    scene = kepler.load(root / "scenes/assembly.kdl")
    with pytest.raises(kepler.KeplerError, match="--colour"):
        scene.render(colour="red")
    with pytest.raises(kepler.KeplerError, match="svg"):
        scene.render(svg="x.svg")
    with pytest.raises(kepler.KeplerError, match="load"):
        scene.render(hierarchy="median")
    with pytest.raises(TypeError, match="dir"):
        scene.render(dir=("a", 1, 2))


def test_bad_camera_is_an_error_not_a_crash(root):
    scene = kepler.load(root / "scenes/assembly.kdl")
    with pytest.raises(kepler.KeplerError):
        scene.render(dir=(0, 0, 0))


def test_hierarchies_agree(root):
    path = root / "scenes/polyhedra.kdl"
    a = kepler.load(path, hierarchy="median").render()
    b = kepler.load(path, hierarchy="simplify").render()
    assert a.to_json() == b.to_json()


def test_threads_are_released(root):
    """Two renders on two Python threads run at once (the lock is released) and agree."""
    import threading

    scene = kepler.load(root / "scenes/town.kdl")
    results = [None, None]

    def work(i):
        results[i] = scene.render(dir=(-1, -2, -3)).to_json()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results[0] is not None and results[0] == results[1]


def test_a_section_is_flagged_and_matches_the_command(kepler_bin, tmp_path):
    # The issue's unit cube, cut at x = 0.5 and seen along -x: the cut is all that shows.
    cube = tmp_path / "cube.obj"
    cube.write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
    )
    options = dict(dir=(-1, 0, 0), section=[(0.5, 0, 0, 1, 0, 0)])
    r = kepler.load(cube).render(**options)
    assert [f.section for f in r.faces] == [True]
    assert r.faces[0].area == pytest.approx(1.0, rel=1e-12)
    flags = ["--dir", "-1,0,0", "--section", "0.5,0,0,1,0,0"]
    assert r.to_json().encode() == cli(kepler_bin, tmp_path, cube, flags, "json")
