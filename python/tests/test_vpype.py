"""`vpype kepler`: one layer a pen, the page asked for, and kepler's own lines."""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kepler

try:
    import vpype_cli
except ImportError:  # pragma: no cover - depends on the environment
    if os.environ.get("KEPLER_REQUIRE_VPYPE") == "1":
        raise
    pytest.skip("vpype is not installed (KEPLER_REQUIRE_VPYPE=1 makes this fail)",
                allow_module_level=True)

MM = 96 / 25.4  # vpype's unit is the CSS pixel
OPTIONS = "--dir -1,-2,-3 --hidden --page a4"


def svg_layers(svg):
    """{layer id: [(N,2) arrays in px]} from kepler's SVG: absolute M/L paths in mm."""
    layers = {}
    for group in re.finditer(r'<g [^>]*inkscape:label="(\d+) [^"]*"[^>]*>(.*?)</g>', svg, re.S):
        lines = layers.setdefault(int(group.group(1)), [])
        for d in re.findall(r' d="([^"]*)"', group.group(2)):
            for stroke in re.findall(r"M[^M]*", d):
                points = [tuple(map(float, p.split(","))) for p in re.split(r"[ML]", stroke) if p]
                lines.append(np.array(points) * MM)
    return layers


def doc_layers(document):
    return {lid: [np.column_stack([l.real, l.imag]) for l in layer]
            for lid, layer in document.layers.items()}


def without_specks(line, eps=1e-6):
    keep = [0] + [i for i in range(1, len(line)) if np.hypot(*(line[i] - line[i - 1])) > eps]
    return line[keep]


def canonical(lines):
    keyed = []
    for line in lines:
        fwd = tuple(map(tuple, np.round(line, 6)))
        keyed.append(min(fwd, fwd[::-1]))
    return sorted(keyed)


@pytest.fixture(scope="module")
def assembly(root):
    return root / "scenes/assembly.kdl"


def kepler_svg(path):
    scene = kepler.load(path)
    return scene.render(dir=(-1, -2, -3), hidden=True).to_svg(page="a4")


def test_stat_reports_one_layer_a_pen_and_the_page(assembly):
    vpype = Path(sys.executable).with_name("vpype")
    out = subprocess.run([str(vpype), "kepler", str(assembly), *OPTIONS.split(), "stat"],
                         check=True, capture_output=True, text=True).stdout
    reported = sorted(int(n) for n in re.findall(r"^Layer (\d+)$", out, re.M))
    assert reported == sorted(svg_layers(kepler_svg(assembly))) == [1, 2, 3, 4, 6]
    width, height = map(float, re.search(r"page size: \(([\d.]+), ([\d.]+)\)", out).groups())
    assert width == pytest.approx(210 * MM) and height == pytest.approx(297 * MM)


def test_the_drawing_is_keplers_svg_line_for_line(assembly):
    document = vpype_cli.execute(f"kepler '{assembly}' {OPTIONS}")
    ours, theirs = svg_layers(kepler_svg(assembly)), doc_layers(document)
    assert sorted(ours) == sorted(theirs)
    for lid in ours:
        assert len(ours[lid]) == len(theirs[lid]), f"layer {lid}"
        for a, b in zip(ours[lid], theirs[lid]):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-9)


def test_svgelements_reads_the_same_lines(assembly):
    """vpype's own reader (svgelements, an independent parser) agrees, up to its mm factor."""
    import io

    import vpype as vp

    svg = kepler_svg(assembly)
    ours = doc_layers(vpype_cli.execute(f"kepler '{assembly}' {OPTIONS}"))
    theirs = doc_layers(vp.read_multilayer_svg(io.StringIO(svg), 0.1, crop=False))
    assert sorted(ours) == sorted(theirs)
    for lid in ours:
        assert len(ours[lid]) == len(theirs[lid])
        for a, b in zip(ours[lid], theirs[lid]):
            # svgelements drops segments of a few nanometres (a dash ending just past a corner)
            np.testing.assert_allclose(without_specks(a), without_specks(b), rtol=1e-6)


def retracing_pairs(lines, tol):
    """Pairs of stroke ends closer than `tol` whose gap runs back along one of the two strokes'
    end segments: joining them would draw that bit twice, which kepler never does."""
    ends = [(line[0], line[1], i) for i, line in enumerate(lines)]
    ends += [(line[-1], line[-2], i) for i, line in enumerate(lines)]
    pairs = 0
    for a in range(len(ends)):
        for b in range(a + 1, len(ends)):
            (p, p_next, i), (q, q_next, j) = ends[a], ends[b]
            gap = q - p
            if i == j or not 0 < np.hypot(*gap) < tol:
                continue
            along = [(q_next - q, -gap), (p_next - p, gap)]
            if any(abs(d[0] * g[1] - d[1] * g[0]) < 1e-9 * np.hypot(*d) * np.hypot(*g) + 1e-12
                   and np.dot(d, g) > 0 for d, g in along):
                pairs += 1
    return pairs


def test_linemerge_and_linesort_change_no_line(assembly):
    """vpype joins stroke ends closer than 0.05 mm; kepler has joined every pair it may, and
    leaves only those whose gap would retrace a dash (a hidden line ending on another)."""
    before = doc_layers(vpype_cli.execute(f"kepler '{assembly}' {OPTIONS}"))
    after = doc_layers(vpype_cli.execute(f"kepler '{assembly}' {OPTIONS} linemerge linesort"))
    assert sorted(before) == sorted(after)
    for lid in before:
        if canonical(before[lid]) == canonical(after[lid]):
            continue
        retraces = retracing_pairs(before[lid], 0.05 * MM)
        assert lid == 6 and retraces, f"layer {lid}: linemerge joined lines kepler could have"
        assert len(before[lid]) - len(after[lid]) == retraces, f"layer {lid}"


def test_a_bad_scene_is_a_usage_error(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 x\n")
    with pytest.raises(Exception, match=r"bad\.obj:1"):
        vpype_cli.execute(f"kepler '{bad}'")
