// ln-render: a small driver that renders an OBJ mesh with fogleman/ln
// (https://github.com/fogleman/ln) for comparison with kepler.
//
// It is not part of kepler's build; see bench/peers/README.md.
//
// Camera: ln's LookAt + Orthographic matrix, eye 1e6 away from the mesh's
// centre against -dir (ln's visibility rays go from each chop point to
// that eye, so they are all but parallel to dir). The mesh is fitted with
// ln's UnitCube; r is the radius of its bounding box's circumsphere, the
// picture spans 2r over -size pixels and -step 1 is one output pixel
// (world step 2r/size).
//
// -mode feature: border, silhouette and crease edges (angle between the
// adjacent faces' normals above -crease degrees; non-manifold edges too),
// with the mesh as the occluder and ln's own Scene.RenderWithMatrix.
// -mode all: every distinct triangle edge once.
// -hidden: also the parts that ln's ClipFilter test rejects (hidden), as a
// dashed grey group; the chop points are tested once and split into
// visible and hidden runs, mirroring RenderWithMatrix step by step.
package main

import (
	"flag"
	"fmt"
	"math"
	"os"
	"strconv"
	"strings"
	"time"

	"github.com/fogleman/ln/ln"
)

func parseVec(s string) ln.Vector {
	p := strings.Split(s, ",")
	if len(p) != 3 {
		fmt.Fprintf(os.Stderr, "bad vector %q (want x,y,z)\n", s)
		os.Exit(2)
	}
	var f [3]float64
	for i := range p {
		v, err := strconv.ParseFloat(strings.TrimSpace(p[i]), 64)
		if err != nil {
			fmt.Fprintf(os.Stderr, "bad vector %q: %v\n", s, err)
			os.Exit(2)
		}
		f[i] = v
	}
	return ln.Vector{X: f[0], Y: f[1], Z: f[2]}
}

// edgeMesh is the mesh as an occluder whose paths are a chosen edge set.
type edgeMesh struct {
	*ln.Mesh
	paths ln.Paths
}

func (m *edgeMesh) Paths() ln.Paths { return m.paths }

type edgeKey struct{ a, b ln.Vector }

func less(a, b ln.Vector) bool {
	if a.X != b.X {
		return a.X < b.X
	}
	if a.Y != b.Y {
		return a.Y < b.Y
	}
	return a.Z < b.Z
}

func key(a, b ln.Vector) edgeKey {
	if less(b, a) {
		a, b = b, a
	}
	return edgeKey{a, b}
}

// edges returns the chosen edges of the mesh as two-point paths. Triangles
// are matched on exact vertex positions (the loader keeps no indices; the
// fit transforms equal positions to equal positions).
func edges(m *ln.Mesh, dir ln.Vector, mode string, creaseDeg float64) ln.Paths {
	type adj struct {
		faces []int
	}
	order := []edgeKey{}
	adjs := map[edgeKey]*adj{}
	normals := make([]ln.Vector, len(m.Triangles))
	for i, t := range m.Triangles {
		n := t.V2.Sub(t.V1).Cross(t.V3.Sub(t.V1))
		if l := n.Length(); l > 0 {
			n = n.DivScalar(l)
		}
		normals[i] = n
		for _, e := range [][2]ln.Vector{{t.V1, t.V2}, {t.V2, t.V3}, {t.V3, t.V1}} {
			if e[0] == e[1] {
				continue
			}
			k := key(e[0], e[1])
			a := adjs[k]
			if a == nil {
				a = &adj{}
				adjs[k] = a
				order = append(order, k)
			}
			a.faces = append(a.faces, i)
		}
	}
	cosCrease := math.Cos(creaseDeg * math.Pi / 180)
	var paths ln.Paths
	for _, k := range order {
		a := adjs[k]
		keep := mode == "all"
		if !keep {
			switch len(a.faces) {
			case 2:
				n1, n2 := normals[a.faces[0]], normals[a.faces[1]]
				front1 := n1.Dot(dir) < 0
				front2 := n2.Dot(dir) < 0
				keep = front1 != front2 || n1.Dot(n2) < cosCrease
			default: // border (1 face) or non-manifold (3+)
				keep = true
			}
		}
		if keep {
			paths = append(paths, ln.Path{k.a, k.b})
		}
	}
	return paths
}

// render mirrors ln.Scene.RenderWithMatrix but keeps the rejected runs too.
func renderBoth(s *ln.Scene, matrix ln.Matrix, eye ln.Vector, width, height, step float64) (vis, hid ln.Paths) {
	s.Compile()
	paths := s.Paths()
	if step > 0 {
		paths = paths.Chop(step)
	}
	for _, p := range paths {
		var cur ln.Path
		curVis := false
		flush := func() {
			if len(cur) > 1 {
				if curVis {
					vis = append(vis, cur)
				} else {
					hid = append(hid, cur)
				}
			}
			cur = nil
		}
		for _, v := range p {
			w := matrix.MulPositionW(v)
			ok := s.Visible(eye, v) && ln.ClipBox.Contains(w)
			if ok != curVis {
				flush()
				curVis = ok
			}
			cur = append(cur, w)
		}
		flush()
	}
	if step > 0 {
		vis = vis.Simplify(1e-6)
		hid = hid.Simplify(1e-6)
	}
	screen := ln.Translate(ln.Vector{X: 1, Y: 1, Z: 0}).Scale(ln.Vector{X: width / 2, Y: height / 2, Z: 0})
	return vis.Transform(screen), hid.Transform(screen)
}

func svgGroup(b *strings.Builder, p ln.Paths, attrs string) {
	fmt.Fprintf(b, "<g %s>\n", attrs)
	for _, path := range p {
		b.WriteString("<polyline points=\"")
		for i, v := range path {
			if i > 0 {
				b.WriteByte(' ')
			}
			fmt.Fprintf(b, "%.3f,%.3f", v.X, v.Y)
		}
		b.WriteString("\"/>\n")
	}
	b.WriteString("</g>\n")
}

func main() {
	obj := flag.String("obj", "", "OBJ mesh")
	dirS := flag.String("dir", "-1,-2,-3", "view direction x,y,z")
	upS := flag.String("up", "0,1,0", "up vector x,y,z")
	mode := flag.String("mode", "feature", "feature|all")
	crease := flag.Float64("crease", 30, "crease threshold: angle between face normals, degrees")
	hidden := flag.Bool("hidden", false, "also write hidden parts (dashed grey)")
	out := flag.String("out", "out.svg", "output SVG")
	size := flag.Float64("size", 1024, "picture size in pixels")
	stepPx := flag.Float64("step", 1, "chop step in output pixels")
	flag.Parse()
	if *obj == "" || (*mode != "feature" && *mode != "all") {
		flag.Usage()
		os.Exit(2)
	}
	t0 := time.Now()
	mesh, err := ln.LoadOBJ(*obj)
	if err != nil {
		fmt.Fprintln(os.Stderr, err)
		os.Exit(1)
	}
	mesh.UnitCube()
	box := mesh.BoundingBox()
	center := box.Center()
	r := box.Size().Length() / 2
	dir := parseVec(*dirS).Normalize()
	up := parseVec(*upS)
	const dist = 1e6
	eye := center.Sub(dir.MulScalar(dist))

	paths := edges(mesh, dir, *mode, *crease)
	scene := ln.Scene{}
	scene.Add(&edgeMesh{mesh, paths})

	matrix := ln.LookAt(eye, center, up)
	matrix = matrix.Orthographic(-r, r, -r, r, dist-2*r, dist+2*r)
	step := *stepPx * 2 * r / *size
	t1 := time.Now()

	var vis, hid ln.Paths
	if *hidden {
		vis, hid = renderBoth(&scene, matrix, eye, *size, *size, step)
	} else {
		vis = scene.RenderWithMatrix(matrix, eye, *size, *size, step)
	}
	t2 := time.Now()

	var b strings.Builder
	fmt.Fprintf(&b, "<svg width=\"%g\" height=\"%g\" version=\"1.1\" xmlns=\"http://www.w3.org/2000/svg\">\n", *size, *size)
	fmt.Fprintf(&b, "<g transform=\"translate(0,%g) scale(1,-1)\" fill=\"none\">\n", *size)
	if *hidden {
		svgGroup(&b, hid, "id=\"hidden\" stroke=\"#999\" stroke-width=\"0.6\" stroke-dasharray=\"3,3\"")
	}
	svgGroup(&b, vis, "id=\"visible\" stroke=\"black\" stroke-width=\"1\"")
	b.WriteString("</g></svg>\n")
	if err := os.WriteFile(*out, []byte(b.String()), 0644); err != nil {
		fmt.Fprintln(os.Stderr, err)
		os.Exit(1)
	}
	fmt.Fprintf(os.Stderr, "ln-render: %d triangles, %d edges, %d visible paths, %d hidden paths; load+edges %.3fs, render %.3fs\n",
		len(mesh.Triangles), len(paths), len(vis), len(hid), t1.Sub(t0).Seconds(), t2.Sub(t1).Seconds())
}
