"""kepler's own plotter SVG read back as layers of polylines in CSS pixels (vpype's unit).

Only what kepler writes is read: an ``<svg>`` with ``width``/``height`` (mm or px) and a
``viewBox``, Inkscape layer groups, and paths of absolute ``M``/``L`` commands (``Z`` closes).
The user units are scaled to pixels by the exact ratio of ``width`` to the viewBox, so every
point is kepler's, times one factor.
"""

import re
from dataclasses import dataclass, field

import numpy as np

PX_PER = {"mm": 96 / 25.4, "cm": 96 / 2.54, "in": 96.0, "px": 1.0, "": 1.0}

_LENGTH = re.compile(r"^\s*([0-9.eE+-]+)\s*([a-z]*)\s*$")
_ATTR = re.compile(r'([\w:-]+)="([^"]*)"')
_TAG = re.compile(r"<(/?)(svg|g|path)\b([^>]*?)/?>", re.S)
_COMMAND = re.compile(r"([MLZ])([^MLZ]*)")


@dataclass
class Layer:
    """One Inkscape layer: its id (the first number of its label), label, stroke colour,
    pen width in pixels and polylines as complex arrays (x + iy, pixels)."""

    id: int
    label: str
    color: str
    width: float
    lines: list = field(default_factory=list)


def _length(text):
    m = _LENGTH.match(text or "")
    if not m or m.group(2) not in PX_PER:
        raise ValueError(f"not a length kepler writes: {text!r}")
    return float(m.group(1)) * PX_PER[m.group(2)]


def _polylines(d, scale):
    lines, current = [], []
    for command, numbers in _COMMAND.findall(d):
        if command == "M":
            if len(current) > 1:
                lines.append(current)
            current = []
        if command == "Z":
            if current:
                current.append(current[0])
            continue
        x, y = (float(v) for v in numbers.split(","))
        current.append(complex(x * scale, y * scale))
    if len(current) > 1:
        lines.append(current)
    return [np.array(line, dtype=np.complex128) for line in lines]


def read(svg):
    """``(page width px, page height px, [Layer, ...])`` of a kepler SVG, layers in order."""
    width = height = scale = None
    layers, current = [], None
    for closing, tag, attrs in _TAG.findall(svg):
        a = dict(_ATTR.findall(attrs))
        if tag == "svg" and not closing:
            width, height = _length(a.get("width")), _length(a.get("height"))
            box = [float(v) for v in a.get("viewBox", f"0 0 {width} {height}").split()]
            scale = width / box[2]
        elif tag == "g" and not closing and a.get("inkscape:groupmode") == "layer":
            label = a.get("inkscape:label", "")
            number = re.search(r"\d+", label) or re.search(r"\d+", a.get("id", ""))
            layer_id = max(1, int(number.group())) if number else len(layers) + 1
            current = Layer(layer_id, label, a.get("stroke", "#000000"),
                            _length(a.get("stroke-width", "0")) * scale)
            layers.append(current)
        elif tag == "g" and closing:
            current = None
        elif tag == "path" and current is not None and a.get("fill", "none") == "none":
            current.lines.extend(_polylines(a.get("d", ""), scale))
    if width is None:
        raise ValueError("no <svg> element")
    return width, height, layers
