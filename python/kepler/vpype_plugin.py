"""``vpype kepler SCENE [options]``: an exact hidden-line drawing of a 3D scene or mesh as vpype
layers, one a pen (outline, edges, intersections, marks, hatching, hidden dashes).

The drawing is kepler's own plotter SVG read into the document (every line is the SVG's,
coordinates converted from mm to vpype's CSS pixels by the exact factor 96/25.4; vpype's
``read`` would use svgelements' rounded one), with the page size set, so a pipeline
such as ``vpype kepler bunny.obj --hidden linemerge linesort write out.svg`` draws what
``kepler render bunny.obj --hidden --svg out.svg`` draws. Options are the command's, by the
same names; values are passed to it as written (``--dir -1,-2,-3``).
"""

import click
import vpype as vp
import vpype_cli

from ._scene import load
from ._svg import read

# (flag, takes a value, help): kepler render's camera, line and drawing options.
OPTIONS = [
    ("dir", True, "Orthographic view along X,Y,Z."),
    ("eye", True, "Perspective eye X,Y,Z (with --target)."),
    ("target", True, "Point looked at X,Y,Z."),
    ("fov", True, "Perspective field of view in degrees."),
    ("ortho", False, "Orthographic from --eye towards --target."),
    ("up", True, "Up vector X,Y,Z, or auto (the base the mesh stands on)."),
    ("view", True, "Named view: front, back, left, right, top, bottom or iso."),
    ("edges", True, "Which edges: feature or all."),
    ("crease", True, "Crease threshold in degrees."),
    ("hidden", False, "Draw hidden lines too, as dashes on their own layer."),
    ("page", True, "Page: a4, a3, letter or WxHmm (default: the drawing's own size)."),
    ("landscape", False, "Turn the page to landscape."),
    ("margin", True, "Margin in mm."),
    ("pen", True, "Pen width in mm."),
    ("layers", True, "Layers by pen, object or none."),
    ("dash", True, "Hidden-line dash and gap in mm (MM,MM)."),
    ("join", True, "Join strokes whose ends are this close, in mm."),
    ("simplify", True, "Simplify lines to this tolerance in mm."),
    ("hatch", False, "Hatch visible faces by their shade."),
    ("hatch-spacing", True, "Hatch spacing in mm."),
    ("hatch-angle", True, "Hatch angle in degrees."),
    ("hatch-outline", False, "Outline every hatched face."),
    ("light", True, "Light direction X,Y,Z for the hatching."),
    ("lod", True, "Draw objects smaller than this many pixels as tribox substitutes."),
    ("no-inbox", False, "Render without INBOXes."),
]


def _with_options(command):
    for flag, takes_value, help_text in reversed(OPTIONS):
        if takes_value:
            command = click.option(f"--{flag}", type=str, default=None, help=help_text)(command)
        else:
            command = click.option(f"--{flag}", is_flag=True, default=False, help=help_text)(
                command
            )
    return command


def drawing(scene_path, options, hierarchy=None):
    """The vpype Document of kepler's SVG for ``options`` (command flag names, ``_`` or ``-``)."""
    options = {k.replace("-", "_"): v for k, v in options.items()}
    camera_keys = {"dir", "eye", "target", "fov", "ortho", "up", "view", "edges", "crease",
                   "hidden"}
    scene = load(scene_path, hierarchy=hierarchy)
    render = scene.render(**{k: v for k, v in options.items() if k in camera_keys})
    svg = render.to_svg(**{k: v for k, v in options.items() if k not in camera_keys})
    return document_of(svg)


def document_of(svg):
    """The vpype Document of a kepler SVG: its layers at their ids, each with its name, colour
    and pen width, its lines exactly the SVG's (times the mm-to-pixel factor), and its page."""
    width, height, layers = read(svg)
    document = vp.Document(page_size=(width, height))
    for layer in layers:
        if not layer.lines:
            continue
        document.add(vp.LineCollection(layer.lines), layer.id)
        lc = document.layers[layer.id]
        lc.set_property(vp.METADATA_FIELD_NAME, layer.label)
        lc.set_property(vp.METADATA_FIELD_COLOR, vp.Color(layer.color))
        lc.set_property(vp.METADATA_FIELD_PEN_WIDTH, layer.width)
    return document


class _OptionsAfterScene(click.Command):
    """Takes this command's options after SCENE too (``vpype kepler bunny.obj --hidden``).

    vpype chains commands, so click stops a command at its first positional argument; the
    options that follow SCENE and are this command's are moved before it, and the first
    token that is not one of them starts the next command.
    """

    def parse_args(self, ctx, args):
        takes_value = {}
        for param in self.params:
            if isinstance(param, click.Option):
                for name in param.opts:
                    takes_value[name] = not param.is_flag
        before, rest = [], list(args)
        while rest and rest[0].startswith("-") and rest[0] != "-":
            before.extend(_take_option(rest, takes_value))
        if rest:
            scene = rest.pop(0)
            while rest and rest[0].split("=", 1)[0] in takes_value:
                before.extend(_take_option(rest, takes_value))
            rest.insert(0, scene)
        return super().parse_args(ctx, before + rest)


def _take_option(rest, takes_value):
    """Pops one option (and its value when it takes one and is not written NAME=VALUE)."""
    token = rest.pop(0)
    if takes_value.get(token, False) and rest:
        return [token, rest.pop(0)]
    return [token]


@click.command(cls=_OptionsAfterScene)
@click.argument("scene", type=click.Path(exists=True, dir_okay=False))
@click.option("--hierarchy", type=click.Choice(["simplify", "median"]), default=None,
              help="Object tree for flat meshes (answers are the same).")
@_with_options
@vpype_cli.global_processor
def kepler(document, scene, hierarchy, **options):
    """Exact hidden-line drawing of a 3D scene file (.kdl), mesh (.obj, .stl, .ply) or glTF/3MF scene.

    Adds one layer a pen (1 outline, 2 edges, 3 intersections, 4 marks, 5 hatching,
    6 hidden) at the layer ids of kepler's SVG, and sets the page size.
    """
    from ._kepler import KeplerError

    try:
        drawn = drawing(scene, options, hierarchy)
    except KeplerError as e:
        raise click.BadParameter(str(e), param_hint="SCENE") from e
    document.extend(drawn)
    document.page_size = drawn.page_size
    return document


kepler.help_group = "Plugins"
