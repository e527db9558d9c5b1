"""Blender Line Art on an OBJ mesh, for comparison with kepler.

Not part of kepler's build; see bench/peers/README.md. Run as

    blender -b --factory-startup -t 1 --python lineart.py -- MESH.obj OUT.svg \
        [--hidden] [--all-edges] [--dir X,Y,Z] [--crease DEG]

The OBJ is imported without axis conversion (forward Y, up Z), so --dir and
up (0,1,0) are in the OBJ's own coordinates, as for kepler. An orthographic
camera looks along --dir at the mesh; a Grease Pencil object with a Line Art
modifier (source: scene; contour, crease at DEG between face normals, i.e.
Line Art's crease_threshold = 180 - DEG, material, edge marks,
intersections, loose edges: Line Art's defaults) is added, and the
dependency graph is evaluated. --hidden sets occlusion levels 0..128 so the
hidden lines come out too. --all-edges marks every mesh edge as a Freestyle
edge mark (before the timed step), so that Line Art's edge-mark lines are
every edge, like kepler's --edges all.

Printed to stdout: "lineart_step_s=... lineart_step_cpu_s=... strokes=N
points=N", where the step is depsgraph.update() and evaluated_get of the
Grease Pencil object, after the imported mesh itself was evaluated. The
strokes are written to OUT.svg (projected with the camera, outside the
timed step).
"""
import math
import sys
import time

import bpy
from mathutils import Matrix, Vector

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) < 2:
    print("usage: blender -b --factory-startup -t 1 --python lineart.py -- MESH.obj OUT.svg "
          "[--hidden] [--all-edges] [--dir X,Y,Z] [--crease DEG]", file=sys.stderr)
    sys.exit(2)
mesh_path, out_path = argv[0], argv[1]
hidden = "--hidden" in argv
all_edges = "--all-edges" in argv
view = Vector((-1.0, -2.0, -3.0))
crease_deg = 30.0
for i, a in enumerate(argv):
    if a == "--dir":
        view = Vector(tuple(float(x) for x in argv[i + 1].split(",")))
    if a == "--crease":
        crease_deg = float(argv[i + 1])
view.normalize()
up = Vector((0.0, 1.0, 0.0))

t_start = time.perf_counter()
scene = bpy.context.scene
# The factory startup scene holds a cube, a light and a camera: keep only
# the camera.
for ob in list(scene.objects):
    if ob.type != "CAMERA":
        bpy.data.objects.remove(ob, do_unlink=True)
cam = scene.camera

bpy.ops.wm.obj_import(filepath=mesh_path, forward_axis="Y", up_axis="Z")
meshes = [ob for ob in scene.objects if ob.type == "MESH"]
nfaces = sum(len(ob.data.polygons) for ob in meshes)
if all_edges:
    for ob in meshes:
        for e in ob.data.edges:  # foreach_set does not reach this flag
            e.use_freestyle_mark = True

# Fit: the bounding box's centre and circumsphere radius.
lo = Vector((math.inf,) * 3)
hi = Vector((-math.inf,) * 3)
for ob in meshes:
    mw = ob.matrix_world
    for v in ob.data.vertices:
        p = mw @ v.co
        lo = Vector(map(min, lo, p))
        hi = Vector(map(max, hi, p))
centre = (lo + hi) / 2
r = (hi - lo).length / 2 or 1.0

# Camera: local -Z along view, local Y = up (projected).
right = view.cross(up).normalized()
true_up = right.cross(view).normalized()
rot = Matrix((right, true_up, -view)).transposed()  # columns
cam.matrix_world = Matrix.Translation(centre - view * (4 * r)) @ rot.to_4x4()
cam.data.type = "ORTHO"
cam.data.ortho_scale = 2 * r
cam.data.clip_start = r * 1e-3
cam.data.clip_end = 10 * r
scene.render.resolution_x = 1024
scene.render.resolution_y = 1024

# Evaluate the imported mesh first, so that the timed step is Line Art's.
depsgraph = bpy.context.evaluated_depsgraph_get()
depsgraph.update()
t_setup = time.perf_counter()

gpd = bpy.data.grease_pencils.new("LineArt")
layer = gpd.layers.new("Lines")
layer.frames.new(scene.frame_current)
mat = bpy.data.materials.new("LineArt")
bpy.data.materials.create_gpencil_data(mat)
gpd.materials.append(mat)
gpo = bpy.data.objects.new("LineArt", gpd)
scene.collection.objects.link(gpo)
mod = gpo.grease_pencil_modifiers.new("LineArt", "GP_LINEART")
mod.source_type = "SCENE"
mod.target_layer = layer.info
mod.target_material = mat
mod.use_crease = True
mod.crease_threshold = math.radians(180.0 - crease_deg)
mod.use_edge_mark = True
if hidden:
    mod.use_multiple_levels = True
    mod.level_start = 0
    mod.level_end = 128

c0 = time.process_time()
t0 = time.perf_counter()
depsgraph.update()
ev = gpo.evaluated_get(depsgraph)
strokes = []
for lay in ev.data.layers:
    for fr in lay.frames:
        strokes.extend(fr.strokes)
t1 = time.perf_counter()
c1 = time.process_time()
npoints = sum(len(s.points) for s in strokes)

# SVG: project the stroke points with the camera (not timed).
inv = cam.matrix_world.inverted()
size = 1024.0
with open(out_path, "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" width="1024" height="1024">\n'
            '<g fill="none" stroke="black" stroke-width="1">\n')
    for s in strokes:
        pts = []
        for p in s.points:
            q = inv @ p.co
            pts.append("%.3f,%.3f" % (size / 2 + q.x / (2 * r) * size,
                                      size / 2 - q.y / (2 * r) * size))
        if len(pts) > 1:
            f.write('<polyline points="%s"/>\n' % " ".join(pts))
    f.write("</g></svg>\n")

print("lineart: faces=%d hidden=%s all_edges=%s setup_s=%.4f"
      % (nfaces, hidden, all_edges, t_setup - t_start))
print("lineart_step_s=%.6f lineart_step_cpu_s=%.6f strokes=%d points=%d"
      % (t1 - t0, c1 - c0, len(strokes), npoints))
sys.stdout.flush()
