"""kepler.compare and the pytest helper: a moved vertex is found, nothing else is."""

import pytest

import kepler
from kepler.testing import assert_matches_golden

CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
QUADS = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]


def two_cubes(path, lift=0.0):
    """Cube `a` at the origin (its top corner lifted by `lift`) and cube `b` far to its right."""
    lines = []
    for name, dx in (("a", 0.0), ("b", 3.0)):
        base = 8 if name == "b" else 0
        lines.append(f"o {name}")
        for i, (x, y, z) in enumerate(CUBE):
            up = lift if (name == "a" and i == 6) else 0.0
            lines.append(f"v {x + dx} {y + up} {z}")
        lines += ["f " + " ".join(str(base + i) for i in q) for q in QUADS]
    path.write_text("\n".join(lines) + "\n")
    return path


VIEW = {"dir": (-1, -2, -3)}


@pytest.fixture
def golden(tmp_path):
    return kepler.load(two_cubes(tmp_path / "g.obj")).render(**VIEW)


def test_the_same_render_is_the_same(golden, tmp_path):
    again = kepler.load(two_cubes(tmp_path / "again.obj")).render(**VIEW)
    c = kepler.compare(golden, again)
    assert c.same and not c.faces and c.compared > 0


def test_a_moved_vertex_changes_only_its_faces(golden, tmp_path):
    moved = kepler.load(two_cubes(tmp_path / "m.obj", lift=0.25)).render(**VIEW)
    c = kepler.compare(golden, moved, tol=1e-9)
    ids = {f.id for f in c.faces}
    # vertex 7 of cube a is used by its faces 1 (top), 3 and 4 (sides); cube b (6-11) is far
    assert ids and ids <= {0, 1, 2, 3, 4, 5}
    assert ids & {1, 3, 4}
    face = next(f for f in c.faces if f.id in {1, 3, 4})
    assert face.area_delta == pytest.approx(face.current_area - face.golden_area)
    assert face.xor_area >= abs(face.area_delta) - 1e-12
    assert c.changed + c.added + c.removed and not c.same
    # the tolerance judges every kind of change
    assert kepler.compare(golden, moved, tol=1e9).same


def test_golden_as_path_text_or_render(golden, tmp_path):
    path = tmp_path / "golden.json"
    path.write_text(golden.to_json())
    for g in (path, str(path), golden.to_json(), golden):
        assert kepler.compare(g, golden).same


def test_bad_golden_is_a_kepler_error(golden, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "kepler-visible/1",\n "faces": [oops]}')
    with pytest.raises(kepler.KeplerError, match="bad.json"):
        kepler.compare(bad, golden)
    with pytest.raises(kepler.KeplerError, match="missing.json"):
        kepler.compare(tmp_path / "missing.json", golden)


def test_report_json_is_the_commands_format(golden, tmp_path):
    import json

    moved = kepler.load(two_cubes(tmp_path / "m.obj", lift=0.25)).render(**VIEW)
    report = json.loads(kepler.compare(golden, moved).to_json())
    assert report["format"] == "kepler-diff/1" and report["changes"]
    assert set(report["changes"][0]) >= {"id", "kind", "area_delta", "xor_area"}


def test_assert_matches_golden(golden, tmp_path):
    path = tmp_path / "golden.json"
    assert_matches_golden(golden, path, update=True)
    assert_matches_golden(golden, path)
    moved = kepler.load(two_cubes(tmp_path / "m.obj", lift=0.25)).render(**VIEW)
    with pytest.raises(AssertionError, match=r"face [134] \(a\)"):
        assert_matches_golden(moved, path)
    with pytest.raises(AssertionError, match="KEPLER_UPDATE_GOLDENS"):
        assert_matches_golden(golden, tmp_path / "none.json")
