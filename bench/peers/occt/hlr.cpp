// hlr-occt: Open CASCADE's polygonal hidden-line removal on an OBJ mesh,
// for comparison with kepler. Not part of kepler's build; see
// bench/peers/README.md.
//
//   hlr-occt MESH.obj X,Y,Z OUT.svg poly DEFLECTION [--build shared|separate]
//
// The mesh becomes one planar face per triangle: "shared" (default) makes
// one vertex per OBJ vertex and one edge per distinct vertex pair, used by
// both faces (no BRepBuilderAPI_Sewing, which did not finish the bunny in
// 240 s); "separate" makes every face its own closed polygon. The faces go
// into a compound, BRepMesh_IncrementalMesh meshes it with DEFLECTION, and
// HLRBRep_PolyAlgo + HLRBRep_PolyHLRToShape project it along X,Y,Z
// (orthographic). Every edge is a sharp edge, so the drawing is every
// triangle edge, visible (black) and hidden (dashed grey).
//
// stderr gets: faces, edges, and the seconds of each step (read, build,
// mesh, hlr = PolyAlgo Load+Update and PolyHLRToShape Update + the
// compounds, svg).
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <HLRAlgo_Projector.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <HLRBRep_PolyAlgo.hxx>
#include <HLRBRep_PolyHLRToShape.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using Clock = std::chrono::steady_clock;
static double secs(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

struct Obj {
  std::vector<gp_Pnt> v;
  std::vector<std::array<int, 3>> tri;
};

static bool readObj(const char *path, Obj &o) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 2) continue;
    if (line[0] == 'v' && line[1] == ' ') {
      double x, y, z;
      if (std::sscanf(line.c_str() + 2, "%lf %lf %lf", &x, &y, &z) == 3)
        o.v.emplace_back(x, y, z);
    } else if (line[0] == 'f' && line[1] == ' ') {
      std::istringstream ss(line.substr(2));
      std::string tok;
      std::vector<int> idx;
      while (ss >> tok) {
        int i = std::atoi(tok.c_str());  // stops at '/'
        if (i < 0) i += (int)o.v.size() + 1;
        idx.push_back(i - 1);
      }
      for (size_t k = 1; k + 1 < idx.size(); k++)
        o.tri.push_back({idx[0], idx[k], idx[k + 1]});
    }
  }
  return true;
}

static bool degenerate(const Obj &o, const std::array<int, 3> &t) {
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return true;
  gp_Vec a(o.v[t[0]], o.v[t[1]]), b(o.v[t[0]], o.v[t[2]]);
  return a.Crossed(b).Magnitude() <= 1e-300;
}

static const char *g_step = "start";
static Clock::time_point g_t0;
static void progress(const char *done) {
  std::fprintf(stderr, "hlr-occt: %s done at %.3f s\n", done, secs(g_t0, Clock::now()));
  std::fflush(stderr);
}
static int run(int argc, char **argv);
int main(int argc, char **argv) {
  try {
    return run(argc, argv);
  } catch (Standard_Failure &e) {
    std::fprintf(stderr, "hlr-occt: %s during %s: %s\n", e.DynamicType()->Name(), g_step,
                 e.GetMessageString());
    return 3;
  }
}

static int run(int argc, char **argv) {
  if (argc < 6 || std::strcmp(argv[4], "poly") != 0) {
    std::fprintf(stderr,
                 "usage: hlr-occt MESH.obj X,Y,Z OUT.svg poly DEFLECTION "
                 "[--build shared|separate]\n");
    return 2;
  }
  const char *meshPath = argv[1];
  double dx, dy, dz;
  if (std::sscanf(argv[2], "%lf,%lf,%lf", &dx, &dy, &dz) != 3) {
    std::fprintf(stderr, "bad direction %s\n", argv[2]);
    return 2;
  }
  const char *outPath = argv[3];
  double deflection = std::atof(argv[5]);
  std::string build = "shared";
  for (int i = 6; i < argc; i++) {
    if (!std::strcmp(argv[i], "--build") && i + 1 < argc) build = argv[++i];
  }
  if (build != "shared" && build != "separate") {
    std::fprintf(stderr, "--build shared|separate\n");
    return 2;
  }

  auto t0 = Clock::now();
  g_t0 = t0;
  Obj o;
  if (!readObj(meshPath, o)) {
    std::fprintf(stderr, "cannot read %s\n", meshPath);
    return 1;
  }
  auto t1 = Clock::now();

  g_step = "build";
  BRep_Builder bb;
  TopoDS_Compound comp;
  bb.MakeCompound(comp);
  size_t nFaces = 0, nEdges = 0, skipped = 0;
  // A triangle's face from its wire into the compound; counted as skipped where OCCT
  // refuses either.
  auto addFace = [&](bool wireDone, const std::function<TopoDS_Wire()> &wire) {
    if (!wireDone) {
      skipped++;
      return;
    }
    BRepBuilderAPI_MakeFace mf(wire(), Standard_True);
    if (!mf.IsDone()) {
      skipped++;
      return;
    }
    bb.Add(comp, mf.Face());
    nFaces++;
  };
  if (build == "shared") {
    std::vector<TopoDS_Vertex> verts(o.v.size());
    std::vector<bool> made(o.v.size(), false);
    auto vert = [&](int i) -> const TopoDS_Vertex & {
      if (!made[i]) {
        verts[i] = BRepBuilderAPI_MakeVertex(o.v[i]);
        made[i] = true;
      }
      return verts[i];
    };
    std::map<std::pair<int, int>, TopoDS_Edge> edges;
    for (const auto &t : o.tri) {
      if (degenerate(o, t)) {
        skipped++;
        continue;
      }
      BRepBuilderAPI_MakeWire mw;
      for (int k = 0; k < 3; k++) {
        int a = t[k], b = t[(k + 1) % 3];
        std::pair<int, int> key(std::min(a, b), std::max(a, b));
        auto it = edges.find(key);
        if (it == edges.end()) {
          TopoDS_Edge e = BRepBuilderAPI_MakeEdge(vert(key.first), vert(key.second));
          it = edges.emplace(key, e).first;
        }
        TopoDS_Edge e = it->second;
        if (a != key.first) e.Reverse();
        mw.Add(e);
      }
      addFace(mw.IsDone(), [&] { return mw.Wire(); });
    }
    nEdges = edges.size();
  } else {
    for (const auto &t : o.tri) {
      if (degenerate(o, t)) {
        skipped++;
        continue;
      }
      BRepBuilderAPI_MakePolygon poly(o.v[t[0]], o.v[t[1]], o.v[t[2]], Standard_True);
      addFace(poly.IsDone(), [&] { return poly.Wire(); });
      nEdges += 3;
    }
  }
  auto t2 = Clock::now();
  progress("build");

  g_step = "mesh";
  // BRepMesh refuses a deflection below Precision::Confusion() (1e-7) with
  // "invalid parameter value"; a planar triangle meshes to itself anyway.
  if (deflection < Precision::Confusion()) {
    std::fprintf(stderr, "hlr-occt: deflection %g raised to Precision::Confusion() = %g\n",
                 deflection, Precision::Confusion());
    deflection = Precision::Confusion();
  }
  BRepMesh_IncrementalMesh mesher(comp, deflection);
  auto t3 = Clock::now();
  progress("mesh");

  // Projector: the viewer looks along (dx,dy,dz); gp_Ax2's main direction
  // points at the viewer; x is right with y up (0,1,0).
  g_step = "hlr";
  gp_Dir view(dx, dy, dz);
  gp_Dir up(0, 1, 0);
  gp_Vec right = gp_Vec(view).Crossed(gp_Vec(up));
  if (right.Magnitude() < 1e-12) right = gp_Vec(1, 0, 0);
  gp_Ax2 ax(gp_Pnt(0, 0, 0), view.Reversed(), gp_Dir(right));
  HLRAlgo_Projector projector(ax);

  Handle(HLRBRep_PolyAlgo) algo = new HLRBRep_PolyAlgo();
  algo->Load(comp);
  algo->Projector(projector);
  algo->Update();
  progress("PolyAlgo::Update");
  HLRBRep_PolyHLRToShape toShape;
  toShape.Update(algo);
  progress("PolyHLRToShape::Update");
  // Each compound walks all of the algorithm's segments again.
  TopoDS_Shape vis[4], hid[4];
  vis[0] = toShape.VCompound();
  progress("VCompound");
  hid[0] = toShape.HCompound();
  progress("HCompound");
  vis[1] = toShape.Rg1LineVCompound();
  vis[2] = toShape.RgNLineVCompound();
  vis[3] = toShape.OutLineVCompound();
  hid[1] = toShape.Rg1LineHCompound();
  hid[2] = toShape.RgNLineHCompound();
  hid[3] = toShape.OutLineHCompound();
  progress("other compounds");
  auto t4 = Clock::now();

  // Projected edges are straight segments in the projector's plane.
  struct Seg { double x1, y1, x2, y2; };
  std::vector<Seg> segs[2];
  double minx = 1e300, miny = 1e300, maxx = -1e300, maxy = -1e300;
  for (int h = 0; h < 2; h++) {
    for (auto &s : (h ? hid : vis)) {
      if (s.IsNull()) continue;
      for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next()) {
        TopoDS_Vertex a, b;
        TopExp::Vertices(TopoDS::Edge(ex.Current()), a, b);
        if (a.IsNull() || b.IsNull()) continue;
        gp_Pnt p = BRep_Tool::Pnt(a), q = BRep_Tool::Pnt(b);
        segs[h].push_back({p.X(), p.Y(), q.X(), q.Y()});
        minx = std::min({minx, p.X(), q.X()});
        maxx = std::max({maxx, p.X(), q.X()});
        miny = std::min({miny, p.Y(), q.Y()});
        maxy = std::max({maxy, p.Y(), q.Y()});
      }
    }
  }
  g_step = "svg";
  const double size = 1024, margin = 16;
  double span = std::max(maxx - minx, maxy - miny);
  double sc = span > 0 ? (size - 2 * margin) / span : 1;
  FILE *f = std::fopen(outPath, "w");
  if (!f) {
    std::fprintf(stderr, "cannot write %s\n", outPath);
    return 1;
  }
  std::fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\">\n", size, size);
  const char *style[2] = {"id=\"visible\" stroke=\"black\" stroke-width=\"1\"",
                          "id=\"hidden\" stroke=\"#999\" stroke-width=\"0.6\" stroke-dasharray=\"3,3\""};
  for (int h = 1; h >= 0; h--) {
    std::fprintf(f, "<g fill=\"none\" %s>\n", style[h]);
    for (auto &s : segs[h])
      std::fprintf(f, "<polyline points=\"%.3f,%.3f %.3f,%.3f\"/>\n",
                   margin + (s.x1 - minx) * sc, size - margin - (s.y1 - miny) * sc,
                   margin + (s.x2 - minx) * sc, size - margin - (s.y2 - miny) * sc);
    std::fprintf(f, "</g>\n");
  }
  std::fprintf(f, "</svg>\n");
  std::fclose(f);
  auto t5 = Clock::now();

  std::fprintf(stderr,
               "hlr-occt: build=%s faces=%zu edges=%zu skipped=%zu visible=%zu hidden=%zu\n"
               "read_s=%.4f build_s=%.4f mesh_s=%.4f hlr_s=%.4f svg_s=%.4f\n",
               build.c_str(), nFaces, nEdges, skipped, segs[0].size(), segs[1].size(),
               secs(t0, t1), secs(t1, t2), secs(t2, t3), secs(t3, t4), secs(t4, t5));
  return 0;
}
