// Drawings: planar cross-sections of a solid and the boundary variety faces, as SVG.
#include "occt_bridge/drawing.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <GProp_GProps.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "base/internal.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {
namespace {

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}
/// A pixel coordinate: two decimals are plenty and keep files small.
std::string px(double x) { return fmt("%.2f", x); }
/// A model value for labels.
std::string num(double x) { return fmt("%.6g", std::abs(x) < 1e-12 ? 0.0 : x); }

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

/// Text safe inside an XML comment (no "--").
std::string comment_safe(std::string s) {
  for (std::size_t p; (p = s.find("--")) != std::string::npos;) s.replace(p, 2, "- -");
  return s;
}

/// Points of an edge at chordal deflection `defl`, in the edge's own orientation.
std::vector<gp_Pnt> edge_points(const TopoDS_Edge& e, double defl) {
  std::vector<gp_Pnt> pts;
  if (BRep_Tool::Degenerated(e)) return pts;
  BRepAdaptor_Curve c(e);
  GCPnts_QuasiUniformDeflection d(c, defl);
  if (d.IsDone() && d.NbPoints() >= 2) {
    for (int i = 1; i <= d.NbPoints(); ++i) pts.push_back(d.Value(i));
  } else {
    const int n = 32;
    for (int i = 0; i <= n; ++i)
      pts.push_back(c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * i / n));
  }
  if (e.Orientation() == TopAbs_REVERSED) std::reverse(pts.begin(), pts.end());
  return pts;
}

/// Ticks at multiples of a 1-2-5 step within [lo, hi], about `want` of them.
std::vector<double> ticks(double lo, double hi, int want) {
  std::vector<double> t;
  const double span = hi - lo;
  if (!(span > 0)) return t;
  const double raw = span / want, mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * span; v += step) t.push_back(v);
  return t;
}

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
                          "#17becf", "#bcbd22", "#0b3d91", "#a50f15", "#006d2c", "#b35806", "#54278f",
                          "#e7298a", "#66a61e", "#e6ab02", "#1b9e77", "#7570b3", "#a6761d"};
const char* kGrey = "#9a9a9a";
const char* palette(int slot) { return kPalette[slot % int(sizeof kPalette / sizeof kPalette[0])]; }

}  // namespace

nlohmann::json Section::to_json() const {
  return {{"z", z},
          {"area", area},
          {"loops", loops},
          {"bbox", {{bbox_min[0], bbox_min[1]}, {bbox_max[0], bbox_max[1]}}}};
}

std::vector<Section> sections(const Shape& solid, const std::vector<double>& heights, const SectionOptions& options) {
  SWEEP_ASSERT(options.relative_deflection > 0, "relative_deflection must be positive");
  const TopoDS_Shape& s = solid.shape;
  Bnd_Box box;
  BRepBndLib::AddOptimal(s, box, false, false);
  std::vector<Section> out;
  double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
  if (!box.IsVoid()) box.Get(x0, y0, z0, x1, y1, z1);
  const double size = std::max({x1 - x0, y1 - y0, z1 - z0, 1e-300});
  const double margin = 0.1 * size + 1.0;
  for (double z : heights) {
    SWEEP_ASSERT(std::isfinite(z), "section height must be finite");
    Section sec;
    sec.z = z;
    if (box.IsVoid() || z < z0 - 1e-7 * size || z > z1 + 1e-7 * size) {
      out.push_back(sec);
      continue;
    }
    TopoDS_Shape result;
    try {
      TopoDS_Face plane =
          BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp::DZ()), x0 - margin, x1 + margin, y0 - margin, y1 + margin)
              .Face();
      BRepAlgoAPI_Common op;
      TopTools_ListOfShape args, tools;
      args.Append(s);
      tools.Append(plane);
      op.SetArguments(args);
      op.SetTools(tools);
      op.SetRunParallel(false);
      op.Build();
      if (!op.IsDone() || op.HasErrors()) throw ComputeError("the section at z = " + num(z) + " failed (OCCT boolean)");
      result = op.Shape();
    } catch (const Standard_Failure& f) {
      throw ComputeError("the section at z = " + num(z) + " failed: " +
                         (f.GetMessageString() ? f.GetMessageString() : "OCCT error"));
    }
    GProp_GProps g;
    BRepGProp::SurfaceProperties(result, g);
    sec.area = std::abs(g.Mass());
    Bnd_Box sb;
    BRepBndLib::AddOptimal(result, sb, false, false);
    if (sb.IsVoid()) {
      out.push_back(sec);
      continue;
    }
    double a0, b0, c0, a1, b1, c1;
    sb.Get(a0, b0, c0, a1, b1, c1);
    sec.bbox_min = {a0, b0};
    sec.bbox_max = {a1, b1};
    const double defl = options.relative_deflection * std::max({a1 - a0, b1 - b0, 1e-12 * size});
    for (TopExp_Explorer fx(result, TopAbs_FACE); fx.More(); fx.Next()) {
      const TopoDS_Face& face = TopoDS::Face(fx.Current());
      for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) {
        ++sec.loops;
        std::vector<std::array<double, 2>> line;
        for (BRepTools_WireExplorer ex(TopoDS::Wire(wx.Current()), face); ex.More(); ex.Next()) {
          std::vector<gp_Pnt> pts = edge_points(ex.Current(), defl);
          for (std::size_t i = line.empty() ? 0 : 1; i < pts.size(); ++i) line.push_back({pts[i].X(), pts[i].Y()});
        }
        if (!line.empty()) sec.polylines.push_back(std::move(line));
      }
    }
    if (sec.loops == 0) sec.area = 0;  // edges or vertices only: the plane touches the solid
    out.push_back(sec);
  }
  return out;
}

std::string sections_svg(const std::vector<Section>& secs, const std::string& title) {
  // A common frame: the union of the sections' boxes, padded.
  double ux0 = 0, uy0 = 0, ux1 = 0, uy1 = 0;
  bool any = false;
  for (const auto& s : secs) {
    if (s.empty()) continue;
    if (!any) {
      ux0 = s.bbox_min[0], uy0 = s.bbox_min[1], ux1 = s.bbox_max[0], uy1 = s.bbox_max[1];
      any = true;
    } else {
      ux0 = std::min(ux0, s.bbox_min[0]), uy0 = std::min(uy0, s.bbox_min[1]);
      ux1 = std::max(ux1, s.bbox_max[0]), uy1 = std::max(uy1, s.bbox_max[1]);
    }
  }
  if (!any) ux0 = uy0 = -1, ux1 = uy1 = 1;
  {
    const double pad = 0.05 * std::max({ux1 - ux0, uy1 - uy0, 1e-9});
    ux0 -= pad, uy0 -= pad, ux1 += pad, uy1 += pad;
  }
  // Equal scale in x and y, the same in every panel.
  const double scale = std::min(300.0 / (ux1 - ux0), 360.0 / (uy1 - uy0));
  const double dw = (ux1 - ux0) * scale, dh = (uy1 - uy0) * scale;
  const double left = 70, top = 50, right = 25, bottom = 75;
  const double pw = left + dw + right, ph = top + dh + bottom;
  const double W = std::max(pw * std::max<std::size_t>(secs.size(), 1), 360.0), H = ph + 30;

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px(W) << "\" height=\"" << px(H)
    << "\" viewBox=\"0 0 " << px(W) << " " << px(H) << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<!-- sweepvol section: cross-sections z = const of the swept solid, x to the right, y up, equal scale "
    << num(scale) << " px per unit -->\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"10\" y=\"20\" font-size=\"14\">" << xml_escape(title) << "</text>\n";
  const auto xt = ticks(ux0, ux1, 5), yt = ticks(uy0, uy1, 5);
  for (std::size_t k = 0; k < secs.size(); ++k) {
    const Section& s = secs[k];
    const double ox = k * pw + left, oy = 30 + top;
    auto X = [&](double x) { return ox + (x - ux0) * scale; };
    auto Y = [&](double y) { return oy + (uy1 - y) * scale; };
    o << "<g class=\"panel\" id=\"section-" << k + 1 << "\">\n"
      << "<text class=\"title\" x=\"" << px(ox + dw / 2) << "\" y=\"" << px(oy - 14)
      << "\" text-anchor=\"middle\" font-size=\"14\">z = " << num(s.z) << "</text>\n"
      << "<rect x=\"" << px(ox) << "\" y=\"" << px(oy) << "\" width=\"" << px(dw) << "\" height=\"" << px(dh)
      << "\" fill=\"none\" stroke=\"#888\" stroke-width=\"0.8\"/>\n";
    // axis ticks with their values
    o << "<g class=\"ticks\" stroke=\"#888\" stroke-width=\"0.8\">";
    for (double t : xt) o << "<line x1=\"" << px(X(t)) << "\" y1=\"" << px(oy + dh) << "\" x2=\"" << px(X(t)) << "\" y2=\"" << px(oy + dh + 5) << "\"/>";
    for (double t : yt) o << "<line x1=\"" << px(ox - 5) << "\" y1=\"" << px(Y(t)) << "\" x2=\"" << px(ox) << "\" y2=\"" << px(Y(t)) << "\"/>";
    o << "</g>\n<g class=\"tick-labels\" font-size=\"10\" fill=\"#444\">";
    for (double t : xt) o << "<text x=\"" << px(X(t)) << "\" y=\"" << px(oy + dh + 16) << "\" text-anchor=\"middle\">" << num(t) << "</text>";
    for (double t : yt) o << "<text x=\"" << px(ox - 7) << "\" y=\"" << px(Y(t) + 3) << "\" text-anchor=\"end\">" << num(t) << "</text>";
    o << "<text x=\"" << px(ox + dw) << "\" y=\"" << px(oy + dh + 28) << "\" text-anchor=\"end\">x</text>"
      << "<text x=\"" << px(ox - 7) << "\" y=\"" << px(oy - 2) << "\" text-anchor=\"end\">y</text></g>\n";
    if (s.empty()) {
      o << "<text x=\"" << px(ox + dw / 2) << "\" y=\"" << px(oy + dh / 2) << "\" text-anchor=\"middle\" fill=\"#888\">"
        << "empty</text>\n";
    } else {
      o << "<path class=\"section\" fill=\"#7fa7d9\" fill-opacity=\"0.6\" fill-rule=\"evenodd\" stroke=\"#1a3d6d\" "
           "stroke-width=\"1.2\" stroke-linejoin=\"round\" d=\"";
      for (const auto& line : s.polylines) {
        for (std::size_t i = 0; i < line.size(); ++i)
          o << (i == 0 ? "M" : "L") << px(X(line[i][0])) << " " << px(Y(line[i][1])) << " ";
        o << "Z ";
      }
      o << "\"/>\n";
    }
    o << "<text class=\"area\" x=\"" << px(ox + dw / 2) << "\" y=\"" << px(oy + dh + 48)
      << "\" text-anchor=\"middle\">area = " << num(s.area) << " (" << s.loops << " loop" << (s.loops == 1 ? "" : "s")
      << ")</text>\n</g>\n";
  }
  o << "</svg>\n";
  return o.str();
}

namespace {

/// The triangulation of a copy of the faces for a drawing, coarser until it has at most
/// options.max_triangles triangles: the copy and its deflection.
std::pair<TopoDS_Shape, double> meshed_for_drawing(const Shape& faces, const VarietyDrawingOptions& options) {
  // (a copy: the caller's faces keep no triangulation of ours)
  TopoDS_Shape shape = BRepBuilderAPI_Copy(faces.shape, true, false).Shape();
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  double size = 1;
  if (!box.IsVoid()) size = std::sqrt(box.SquareExtent());
  double defl = options.relative_deflection * size;
  for (int attempt = 0; attempt < 12; ++attempt) {
    BRepTools::Clean(shape);
    BRepMesh_IncrementalMesh mesh(shape, defl, false, 0.5, false);
    long tris = 0;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      TopLoc_Location loc;
      Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(TopoDS::Face(ex.Current()), loc);
      if (!t.IsNull()) tris += t->NbTriangles();
    }
    if (tris <= options.max_triangles) break;
    defl *= 2;
  }
  return {shape, defl};
}

/// A parallel projection looking along -d (from d towards the origin), z up, and the box of what
/// it projected.
struct Projection {
  Eigen::Vector3d d, right, up;
  double sx0 = 1e300, sy0 = 1e300, sx1 = -1e300, sy1 = -1e300;
  explicit Projection(const Eigen::Vector3d& dir)
      : d(dir), right(Eigen::Vector3d::UnitZ().cross(dir).normalized()), up(dir.cross(right)) {}
  Eigen::Vector2d operator()(const gp_Pnt& p) {
    const Eigen::Vector3d x = to_eigen(p);
    const Eigen::Vector2d s(x.dot(right), -x.dot(up));
    sx0 = std::min(sx0, s.x()), sx1 = std::max(sx1, s.x()), sy0 = std::min(sy0, s.y()), sy1 = std::max(sy1, s.y());
    return s;
  }
};

/// One face as drawn: its variety (-1 unknown), mean depth, mesh edges and outline, projected.
struct DrawnFace {
  int variety;
  double depth;
  std::vector<std::array<Eigen::Vector2d, 2>> mesh, outline;
};

/// The faces of the meshed shape projected, far faces first (near outlines are drawn over far ones).
std::vector<DrawnFace> drawn_faces(const TopoDS_Shape& shape, const std::vector<int>& face_variety, int varieties,
                                   double defl, Projection& project) {
  std::vector<DrawnFace> drawn;
  std::size_t k = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next(), ++k) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    DrawnFace dr;
    dr.variety = k < face_variety.size() && face_variety[k] >= 0 && face_variety[k] < varieties ? face_variety[k] : -1;
    TopLoc_Location loc;
    Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(f, loc);
    double depth = 0;
    int nd = 0;
    if (!t.IsNull()) {
      std::vector<Eigen::Vector2d> nodes(t->NbNodes() + 1);
      for (int i = 1; i <= t->NbNodes(); ++i) {
        const gp_Pnt p = t->Node(i).Transformed(loc.Transformation());
        nodes[i] = project(p);
        depth += to_eigen(p).dot(project.d), ++nd;
      }
      std::set<std::pair<int, int>> seen;
      for (int i = 1; i <= t->NbTriangles(); ++i) {
        int n[3];
        t->Triangle(i).Get(n[0], n[1], n[2]);
        for (int e = 0; e < 3; ++e) {
          const int a = std::min(n[e], n[(e + 1) % 3]), b = std::max(n[e], n[(e + 1) % 3]);
          if (seen.insert({a, b}).second) dr.mesh.push_back({nodes[a], nodes[b]});
        }
      }
    }
    dr.depth = nd ? depth / nd : 0;
    for (TopExp_Explorer ee(f, TopAbs_EDGE); ee.More(); ee.Next()) {
      const std::vector<gp_Pnt> pts = edge_points(TopoDS::Edge(ee.Current()), defl);
      for (std::size_t i = 1; i < pts.size(); ++i) dr.outline.push_back({project(pts[i - 1]), project(pts[i])});
    }
    drawn.push_back(std::move(dr));
  }
  std::stable_sort(drawn.begin(), drawn.end(), [](const DrawnFace& a, const DrawnFace& b) { return a.depth < b.depth; });
  return drawn;
}

/// The legend: one entry per variety (id, type, stage, fixed parameters, what it is), and one for
/// faces of unknown variety when there are any.
void write_legend(std::ostream& o, const std::vector<Variety>& vars, const std::function<const char*(int)>& colour,
                  double legend_x, double top, double row, bool any_unknown) {
  o << "<g class=\"legend\">\n<text x=\"" << px(legend_x) << "\" y=\"" << px(top) << "\" font-size=\"13\">"
    << "varieties (id, type, fixed parameters)</text>\n";
  double y = top + 20;
  auto fixed_text = [](const nlohmann::json& fixed) {
    std::string s;
    for (const auto& [key, val] : fixed.items())
      s += (s.empty() ? "" : ", ") + key + " = " + (val.is_number() ? num(val.get<double>()) : val.dump());
    return s.empty() ? std::string("none") : s;
  };
  for (std::size_t i = 0; i < vars.size(); ++i, y += row) {
    const Variety& v = vars[i];
    o << "<g class=\"legend-entry\" id=\"legend-v" << i + 1 << "\" data-variety=\"" << i + 1 << "\">"
      << "<rect x=\"" << px(legend_x) << "\" y=\"" << px(y - 10) << "\" width=\"14\" height=\"14\" fill=\""
      << colour(int(i)) << "\"" << (v.final_stage ? "" : " fill-opacity=\"0.3\"") << "/>"
      << "<text x=\"" << px(legend_x + 20) << "\" y=\"" << px(y + 1) << "\">" << i + 1 << "  " << xml_escape(v.type)
      << "  stage " << v.stage << ", fixed: " << xml_escape(fixed_text(v.fixed)) << (v.final_stage ? "" : " (not drawn)")
      << "</text><text x=\"" << px(legend_x + 20) << "\" y=\"" << px(y + 13) << "\" font-size=\"10\" fill=\"#555\">"
      << xml_escape(v.what) << "</text></g>\n";
  }
  if (any_unknown)
    o << "<g class=\"legend-entry\" id=\"legend-unknown\"><rect x=\"" << px(legend_x) << "\" y=\"" << px(y - 10)
      << "\" width=\"14\" height=\"14\" fill=\"" << kGrey << "\"/><text x=\"" << px(legend_x + 20) << "\" y=\""
      << px(y + 1) << "\">variety unknown</text></g>\n";
  o << "</g>\n";
}

}  // namespace

std::string varieties_svg(const Shape& faces, const std::vector<int>& face_variety, const std::vector<Variety>& vars,
                          const std::string& title, const VarietyDrawingOptions& options) {
  // Projection: looking from `view_from` towards the origin, z up.
  Eigen::Vector3d d(options.view_from[0], options.view_from[1], options.view_from[2]);
  SWEEP_ASSERT(d.norm() > 0 && d.normalized().cross(Eigen::Vector3d::UnitZ()).norm() > 1e-6,
               "view direction must be non-zero and not along z");
  d.normalize();
  // Colours: the drawn (last stage) varieties with faces take the first palette entries.
  std::vector<int> slot(vars.size(), -1);
  {
    int next = 0;
    for (int pass = 0; pass < 2; ++pass)
      for (std::size_t i = 0; i < vars.size(); ++i)
        if (slot[i] < 0 && (pass == 1 || (vars[i].final_stage && vars[i].faces > 0))) slot[i] = next++;
  }
  const std::function<const char*(int)> colour = [&](int id) { return id < 0 ? kGrey : palette(slot[std::size_t(id)]); };

  const auto [shape, defl] = meshed_for_drawing(faces, options);
  Projection project(d);
  const std::vector<DrawnFace> drawn = drawn_faces(shape, face_variety, int(vars.size()), defl, project);
  double sx0 = project.sx0, sy0 = project.sy0, sx1 = project.sx1, sy1 = project.sy1;
  if (sx0 > sx1) sx0 = sy0 = -1, sx1 = sy1 = 1;

  const double area_w = 640, pad = 30, top = 60;
  const double scale = std::min(area_w / std::max(sx1 - sx0, 1e-12), 640.0 / std::max(sy1 - sy0, 1e-12));
  const double dw = (sx1 - sx0) * scale, dh = (sy1 - sy0) * scale;
  const double legend_x = pad + dw + 30, row = 30;
  bool any_unknown = false;
  for (const auto& dr : drawn) any_unknown = any_unknown || dr.variety < 0;
  const double legend_h = 40 + row * (vars.size() + (any_unknown ? 1 : 0));
  const double W = legend_x + 560, H = std::max(top + dh + pad + 40, top + legend_h);
  auto X = [&](double x) { return pad + (x - sx0) * scale; };
  auto Y = [&](double y) { return top + (y - sy0) * scale; };

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px(W) << "\" height=\"" << px(H) << "\" viewBox=\"0 0 "
    << px(W) << " " << px(H) << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<!-- sweepvol varieties: candidate faces of the last stage in a parallel projection, viewed from direction ("
    << num(d.x()) << ", " << num(d.y()) << ", " << num(d.z()) << ") towards the origin, z up; thin lines are mesh "
    << "edges (deflection " << num(defl) << "), thick lines face boundaries -->\n"
    << "<!-- " << comment_safe(title) << " -->\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << px(pad) << "\" y=\"24\" font-size=\"14\">" << xml_escape(title) << "</text>\n"
    << "<text class=\"caption\" x=\"" << px(pad) << "\" y=\"42\" font-size=\"11\" fill=\"#444\">parallel projection "
    << "viewed from (" << num(d.x()) << ", " << num(d.y()) << ", " << num(d.z()) << "), z up</text>\n"
    << "<g class=\"faces\" fill=\"none\" stroke-linecap=\"round\">\n";
  for (const auto& dr : drawn) {
    const char* c = colour(dr.variety);
    o << "<g class=\"face\" data-variety=\"" << (dr.variety < 0 ? std::string("unknown") : std::to_string(dr.variety + 1))
      << "\" stroke=\"" << c << "\">";
    if (!dr.mesh.empty()) {
      o << "<path stroke-width=\"0.35\" stroke-opacity=\"0.45\" d=\"";
      for (const auto& e : dr.mesh)
        o << "M" << px(X(e[0].x())) << " " << px(Y(e[0].y())) << "L" << px(X(e[1].x())) << " " << px(Y(e[1].y()));
      o << "\"/>";
    }
    if (!dr.outline.empty()) {
      o << "<path stroke-width=\"1.4\" d=\"";
      for (std::size_t i = 0; i < dr.outline.size(); ++i) {
        const auto& e = dr.outline[i];
        if (i == 0 || (dr.outline[i - 1][1] - e[0]).norm() > 1e-12)
          o << "M" << px(X(e[0].x())) << " " << px(Y(e[0].y()));
        o << "L" << px(X(e[1].x())) << " " << px(Y(e[1].y()));
      }
      o << "\"/>";
    }
    o << "</g>\n";
  }
  o << "</g>\n";
  write_legend(o, vars, colour, legend_x, top, row, any_unknown);
  o << "</svg>\n";
  return o.str();
}

void write_text_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".partial";
  {
    std::ofstream o(tmp, std::ios::binary);
    o << text;
    o.close();
    if (!o) {
      std::remove(tmp.c_str());
      throw ComputeError("cannot write '" + path + "'");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw ComputeError("cannot write '" + path + "'");
  }
}

}  // namespace sweep::occt
