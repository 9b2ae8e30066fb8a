// The verdict on a computed solid against a membership test that does not use it.
#include "verdict/verdict.hpp"
#include "verdict/solid_rays.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <BRepTools.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Edge.hxx>
#include <ShapeUpgrade_ShapeDivideClosed.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <cmath>
#include <mutex>
#include <random>

#include "sweep/point_text.hpp"

namespace sweep::occt {

namespace {

/// One face's triangles with their parameters, for probes on the exact surface.
struct FaceMesh {
  TopoDS_Face face;
  std::vector<Triangle> xyz;
  std::vector<std::array<gp_Pnt2d, 3>> uv;
  std::vector<double> cumulative;  ///< cumulative triangle areas
  double area = 0;
};

std::vector<FaceMesh> face_meshes(const TopoDS_Shape& shape) {
  std::vector<FaceMesh> out;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    FaceMesh fm;
    fm.face = TopoDS::Face(ex.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(fm.face, loc);
    if (tri.IsNull()) continue;
    const gp_Trsf T = loc.Transformation();
    const bool reversed = fm.face.Orientation() == TopAbs_REVERSED;
    for (int k = 1; k <= tri->NbTriangles(); ++k) {
      int n1, n2, n3;
      tri->Triangle(k).Get(n1, n2, n3);
      if (reversed) std::swap(n2, n3);
      Triangle t{to_eigen(tri->Node(n1).Transformed(T)), to_eigen(tri->Node(n2).Transformed(T)),
                 to_eigen(tri->Node(n3).Transformed(T))};
      fm.area += 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
      fm.cumulative.push_back(fm.area);
      fm.xyz.push_back(t);
      if (tri->HasUVNodes()) fm.uv.push_back({tri->UVNode(n1), tri->UVNode(n2), tri->UVNode(n3)});
    }
    out.push_back(std::move(fm));
  }
  return out;
}

/// Polylines of the shape's edges, for the distance of a probe to the nearest edge.
struct EdgeSegments {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  std::vector<Eigen::AlignedBox3d> edge_boxes;
  std::vector<std::pair<std::size_t, std::size_t>> ranges;  ///< each edge's segments

  EdgeSegments(const TopoDS_Shape& shape, double deflection) {
    TopTools_IndexedMapOfShape edges;
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    for (int k = 1; k <= edges.Extent(); ++k) {
      const TopoDS_Edge& e = TopoDS::Edge(edges(k));
      if (BRep_Tool::Degenerated(e)) continue;
      BRepAdaptor_Curve c(e);
      GCPnts_QuasiUniformDeflection pts(c, deflection);
      std::vector<Eigen::Vector3d> p;
      if (pts.IsDone() && pts.NbPoints() >= 2) {
        for (int i = 1; i <= pts.NbPoints(); ++i) p.push_back(to_eigen(pts.Value(i)));
      } else {
        const int n = Settings::edge_polyline_segments;
        for (int i = 0; i <= n; ++i)
          p.push_back(to_eigen(c.Value(c.FirstParameter() + (c.LastParameter() - c.FirstParameter()) * i / n)));
      }
      const std::size_t first = segments.size();
      Eigen::AlignedBox3d box;
      for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        segments.push_back({p[i], p[i + 1]});
        box.extend(p[i]);
        box.extend(p[i + 1]);
      }
      ranges.push_back({first, segments.size()});
      edge_boxes.push_back(box);
    }
  }
  /// Whether some edge passes within r of x.
  bool near(const Eigen::Vector3d& x, double r) const {
    for (std::size_t e = 0; e < ranges.size(); ++e) {
      const Eigen::Vector3d d = (edge_boxes[e].min() - x).cwiseMax(x - edge_boxes[e].max()).cwiseMax(0.0);
      if (d.norm() > r) continue;
      for (std::size_t s = ranges[e].first; s < ranges[e].second; ++s) {
        const Eigen::Vector3d a = segments[s].first, ab = segments[s].second - a;
        const double t = std::clamp((x - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
        if ((a + t * ab - x).norm() <= r) return true;
      }
    }
    return false;
  }
};

}  // namespace

std::vector<Triangle> triangulate(const TopoDS_Shape& shape, double deflection, std::string* problem,
                                  std::vector<std::pair<TopoDS_Face, std::string>>* uncovered) {
  BRepMesh_IncrementalMesh mesh(shape, deflection, false, 0.5, true);
  std::vector<Triangle> out;
  const std::vector<FaceMesh> faces = face_meshes(shape);
  // the most area of a face the triangles may miss and still hold every point of it within two
  // deflections (below)
  const double sliver_area = M_PI * deflection * deflection;
  if (problem) {
    // a face without triangles is a hole in the mesh, unless it has no area, or so little that no
    // point of it is a deflection from its edges (below: the mesh must then still be closed)
    problem->clear();
    double total = 0;
    for (const auto& fm : faces) total += fm.area;
    int missing = 0;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face& f = TopoDS::Face(ex.Current());
      TopLoc_Location loc;
      missing += BRep_Tool::Triangulation(f, loc).IsNull() &&
                 std::abs(face_area(f)) > std::max(Settings::mesh_missing_area * total, sliver_area);
    }
    if (missing > 0) *problem = std::to_string(missing) + " faces have no triangulation";
  }
  Bnd_Box b;
  for (const auto& fm : faces) {
    out.insert(out.end(), fm.xyz.begin(), fm.xyz.end());
    if (!problem || !problem->empty()) continue;
    // the triangles must cover the face: their area against the face's, within what the chords of
    // a deflection-bounded triangulation can lose. On a small face (a sliver where faces meet) the
    // chords may lose more; a part of area A that the triangles miss has no point farther than
    // sqrt(A / pi) from its rim, which the triangles or the face's edges hold to within a
    // deflection, so a loss up to pi deflection^2 keeps every point of the face within two
    // deflections of the triangles, inside the band the samples leave out.
    const double exact = face_area(fm.face), loss = std::abs(fm.area - exact);
    if (loss > Settings::mesh_area_loss * std::abs(exact) + Settings::mesh_area_loss_floor && loss > sliver_area) {
      const std::string what =
          "the triangulation of a face covers " + std::to_string(fm.area) + " of its area " + std::to_string(exact);
      if (uncovered)
        uncovered->push_back({fm.face, what});
      else
        *problem = what;
    }
  }
  if (problem && problem->empty()) {
    // closed: every triangle side is shared by another triangle
    Eigen::AlignedBox3d box;
    for (const auto& t : out) box.extend(t.a), box.extend(t.b), box.extend(t.c);
    const double q = Settings::mesh_side_resolution * std::max(box.sizes().maxCoeff(), 1e-300);
    auto key = [&](const Eigen::Vector3d& p) {
      return std::array<long long, 3>{std::llround(p.x() / q), std::llround(p.y() / q), std::llround(p.z() / q)};
    };
    std::map<std::pair<std::array<long long, 3>, std::array<long long, 3>>, int> sides;
    for (const auto& t : out) {
      const Eigen::Vector3d v[3] = {t.a, t.b, t.c};
      for (int k = 0; k < 3; ++k) {
        auto a = key(v[k]), c = key(v[(k + 1) % 3]);
        if (c < a) std::swap(a, c);
        if (a != c) sides[{a, c}] += 1;
      }
    }
    std::size_t open = 0;
    for (const auto& [side, count] : sides) open += count % 2;
    if (open > 0) *problem = "the triangulation has " + std::to_string(open) + " open sides";
  }
  return out;
}

double proportion_upper_bound(std::size_t k, std::size_t n, double confidence) {
  if (n == 0) return 1.0;
  // one-sided normal quantile by bisection on the error function
  double lo = 0, hi = 10;
  for (int it = 0; it < 100; ++it) {
    const double m = 0.5 * (lo + hi);
    (0.5 * std::erfc(-m / std::sqrt(2.0)) < confidence ? lo : hi) = m;
  }
  const double z = 0.5 * (lo + hi), N = double(n), p = double(k) / N;
  const double centre = p + z * z / (2 * N), spread = z * std::sqrt(p * (1 - p) / N + z * z / (4 * N * N));
  return std::min(1.0, (centre + spread) / (1 + z * z / N));
}

namespace {

/// Serialises the first disagreement's description across threads.
class FirstMismatch {
 public:
  explicit FirstMismatch(std::string& out) : out_(out) {}
  void note(const std::string& what) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (out_.empty()) out_ = what;
  }

 private:
  std::string& out_;
  std::mutex mutex_;
};

/// Boxes that hold a face and its triangles with `margin` around them: the face's surface over its
/// parameter box on 8 x 8 cells, each sampled at 5 x 5 points and widened by the longest step
/// between neighbouring points (far more than the surface strays between them), and the triangles
/// in groups of Settings::region_triangle_group.
std::vector<Eigen::AlignedBox3d> region_of(const TopoDS_Face& face, const std::vector<Triangle>& tris, double margin) {
  std::vector<Eigen::AlignedBox3d> out;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const BRepAdaptor_Surface S(face);
  constexpr int cells = 8, n = 4;
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b) {
      Eigen::AlignedBox3d box;
      double step = 0;
      Eigen::Vector3d grid[n + 1][n + 1];
      for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k) {
          const double u = u0 + (u1 - u0) * (a + double(i) / n) / cells, v = v0 + (v1 - v0) * (b + double(k) / n) / cells;
          grid[i][k] = to_eigen(S.Value(u, v));
          box.extend(grid[i][k]);
          if (i > 0) step = std::max(step, (grid[i][k] - grid[i - 1][k]).norm());
          if (k > 0) step = std::max(step, (grid[i][k] - grid[i][k - 1]).norm());
        }
      out.push_back(Eigen::AlignedBox3d(box.min().array() - (margin + step), box.max().array() + (margin + step)));
    }
  const int group = Settings::region_triangle_group;
  for (std::size_t first = 0; first < tris.size(); first += group) {
    Eigen::AlignedBox3d box;
    for (std::size_t k = first; k < std::min(tris.size(), first + group); ++k)
      box.extend(tris[k].a), box.extend(tris[k].b), box.extend(tris[k].c);
    out.push_back(Eigen::AlignedBox3d(box.min().array() - margin, box.max().array() + margin));
  }
  return out;
}

/// Uniform samples in the box, each classified against the triangulated solid (or, when `mesh` is
/// null, by OCCT's classifier) and by the membership; samples within `band` of the triangulated
/// boundary are left out. Where the two disagree, rays against the exact faces give the solid's
/// side; a disagreement stands when they agree with the triangles or give no clear answer. Rays
/// against the triangles miss the boxes of `avoid` (faces whose triangles do not cover them); a
/// sample no such ray decides is classified by OCCT's classifier (*exact counts them).
void judge_samples(const TopoDS_Shape& solid, const MeshIndex* mesh, const std::vector<Eigen::AlignedBox3d>& avoid,
                   const Eigen::AlignedBox3d& box, const MemberTestMaker& member, double tol, double band,
                   const Settings& settings, FirstMismatch& first, VerdictResult& r, std::size_t* exact) {
  const std::size_t n = settings.verdict_samples;
  std::vector<Eigen::Vector3d> pts(n);
  std::mt19937_64 rng(settings.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (auto& p : pts) p = box.min() + Eigen::Vector3d(uni(rng), uni(rng), uni(rng)).cwiseProduct(box.sizes());
  std::atomic<std::size_t> near{0}, mismatches{0}, undecided{0}, by_classifier{0};
  parallel_for(n, [&]() -> std::function<void(std::size_t)> {
    const MemberTest in_set = member();
    auto cls = std::make_shared<BRepClass3d_SolidClassifier>();
    auto loaded = std::make_shared<bool>(false);
    auto rays = std::make_shared<std::vector<FaceHit>>();  // (set up at this thread's first disagreement)
    return [&, in_set, cls, loaded, rays](std::size_t i) {
      const Eigen::Vector3d& p = pts[i];
      bool a = false;
      int by_mesh = -1;
      if (mesh) {
        if (mesh->distance_below(p, band) < band) {
          ++near;
          return;
        }
        by_mesh = avoid.empty() ? int(mesh->inside(p)) : mesh->inside_avoiding(p, avoid);
      }
      if (by_mesh >= 0) {
        a = by_mesh == 1;
      } else {
        if (!*loaded) cls->Load(solid), *loaded = true;
        ++by_classifier;
        cls->Perform(to_pnt(p), tol);
        if (cls->State() == TopAbs_ON) {
          ++near;
          return;
        }
        a = cls->State() == TopAbs_IN;
      }
      const int m = in_set(p);
      if (m < 0) {
        ++undecided;
        return;
      }
      const bool b = m == 1;
      if (a != b) {
        // a second opinion on the solid's side, from rays against its exact faces (a triangle
        // or OCCT's classifier can be wrong where a ray meets an edge or a sliver)
        if (rays->empty()) *rays = face_hits(solid, tol);
        const int exact = ray_inside(*rays, p, tol);
        if (exact >= 0 && (exact == 1) == b) return;
        ++mismatches;
        first.note(std::string("the point ") + point_text(p, 9) +
                   (b ? " of the swept set lies outside the solid" : " lies in the solid but not in the swept set"));
      }
    };
  });
  r.samples = n;
  r.near_boundary = near;
  r.mismatches = mismatches;
  r.undecided = undecided;
  if (exact) *exact = by_classifier;
}

struct Probe {
  Eigen::Vector3d p, n;  ///< a point of a face and the outward normal there
};

/// Points on the exact faces, chosen by area, at least `clearance` from every edge.
std::vector<Probe> pick_probes(const TopoDS_Shape& solid, const std::vector<FaceMesh>& faces, double deflection,
                               double clearance, const Settings& settings) {
  std::vector<Probe> probes;
  double total_area = 0;
  for (const auto& f : faces) total_area += f.area;
  if (total_area <= 0) return probes;
  const EdgeSegments edges(solid, deflection);
  std::mt19937_64 rng(settings.seed + 1);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const std::size_t wanted = settings.verdict_probes;
  for (std::size_t attempt = 0; attempt < 8 * wanted && probes.size() < wanted; ++attempt) {
    // a face by area, a triangle of it by area, a point of it, carried to the exact surface
    double pick = uni(rng) * total_area;
    std::size_t fi = 0;
    while (fi + 1 < faces.size() && pick > faces[fi].area) pick -= faces[fi++].area;
    const FaceMesh& fm = faces[fi];
    if (fm.uv.empty() || fm.cumulative.empty()) continue;
    const std::size_t ti = std::min<std::size_t>(
        std::lower_bound(fm.cumulative.begin(), fm.cumulative.end(), uni(rng) * fm.area) - fm.cumulative.begin(),
        fm.uv.size() - 1);
    double s = uni(rng), t = uni(rng);
    if (s + t > 1) s = 1 - s, t = 1 - t;
    const auto& uv = fm.uv[ti];
    const gp_Pnt2d q(uv[0].X() + s * (uv[1].X() - uv[0].X()) + t * (uv[2].X() - uv[0].X()),
                     uv[0].Y() + s * (uv[1].Y() - uv[0].Y()) + t * (uv[2].Y() - uv[0].Y()));
    BRepAdaptor_Surface S(fm.face);
    BRepLProp_SLProps props(S, q.X(), q.Y(), 1, Settings::normal_resolution);
    if (!props.IsNormalDefined()) continue;
    Eigen::Vector3d nn = to_eigen(gp_Vec(props.Normal()));
    if (fm.face.Orientation() == TopAbs_REVERSED) nn = -nn;
    const Eigen::Vector3d p = to_eigen(props.Value());
    if (edges.near(p, clearance)) continue;
    probes.push_back({p, nn});
  }
  return probes;
}

/// Each probe tested by the membership at `delta` outside and inside its face (where the
/// membership cannot decide that close, farther off, up to `deflection`). At `delta` the points
/// are taken as outside and inside the solid; farther off, where the solid may be thinner than the
/// offset (a sliver along a fold), the exact solid's classifier says which side each point is on.
/// In batches: when the membership leaves almost every probe of the first batch undecided (a
/// search over joint parameters this close to the boundary), the rest are not tried.
void judge_probes(const TopoDS_Shape& solid, double tol, const std::vector<Probe>& probes, const MemberTestMaker& member,
                  double delta, double deflection, FirstMismatch& first, VerdictResult& r) {
  std::atomic<std::size_t> bad{0}, undecided{0};
  std::mutex offset_mutex;
  r.probe_offset_max = delta;
  const std::size_t batch = Settings::probe_batch;
  std::size_t tried = 0;
  while (tried < probes.size()) {
    const std::size_t start = tried, count = std::min(batch, probes.size() - start);
    const std::size_t undecided_before = undecided;
    parallel_for(count, [&]() -> std::function<void(std::size_t)> {
      const MemberTest in_set = member();
      auto cls = std::make_shared<std::unique_ptr<BRepClass3d_SolidClassifier>>();  // made when first needed
      return [&, in_set, start, cls](std::size_t k) {
        const Probe& pr = probes[start + k];
        int mo = -1, mi = -1;
        double off = delta;
        for (; off <= std::max(delta, deflection) * (1 + Settings::probe_offset_rounding); off *= 4) {
          mo = in_set(pr.p + off * pr.n);
          mi = mo < 0 ? -1 : in_set(pr.p - off * pr.n);
          if (mo >= 0 && mi >= 0) break;
        }
        if (mo < 0 || mi < 0) {
          ++undecided;
          return;
        }
        bool out_in_solid = false, in_in_solid = true;
        if (off > delta) {
          {
            std::lock_guard<std::mutex> lock(offset_mutex);
            r.probe_offset_max = std::max(r.probe_offset_max, off);
          }
          if (!*cls) *cls = std::make_unique<BRepClass3d_SolidClassifier>(solid);
          (*cls)->Perform(to_pnt(pr.p + off * pr.n), tol);
          const TopAbs_State so = (*cls)->State();
          (*cls)->Perform(to_pnt(pr.p - off * pr.n), tol);
          const TopAbs_State si = (*cls)->State();
          if (so == TopAbs_ON || si == TopAbs_ON) {
            ++undecided;
            return;
          }
          out_in_solid = so == TopAbs_IN;
          in_in_solid = si == TopAbs_IN;
        }
        const bool out_in_set = mo == 1, in_in_set = mi == 1;
        if (out_in_set != out_in_solid || in_in_set != in_in_solid) {
          ++bad;
          first.note(std::string("the boundary of the solid at ") + point_text(pr.p, 9) + " is not that of the swept set (" +
                     (out_in_set != out_in_solid ? (out_in_set ? "a point just outside it is swept"
                                                               : "a point outside it, in the solid, is not swept")
                                                 : (in_in_set ? "a point inside it, outside the solid, is swept"
                                                              : "a point just inside it is not swept")) +
                     ")");
        }
      };
    });
    tried += count;
    if (start == 0 && undecided - undecided_before >= count * 9 / 10) break;
  }
  r.probes = tried;
  r.probe_mismatches = bad;
  r.probe_undecided = undecided;
}

}  // namespace

VerdictResult judge_solid(const TopoDS_Shape& solid, const Eigen::AlignedBox3d& box, const MemberTestMaker& member,
                          double tol, double size, const Settings& settings) {
  VerdictResult r;
  r.undecided_fraction = settings.undecided_fraction;
  const double deflection = settings.verdict_deflection * size;
  // OCCT's mesher can leave a face closed on itself (a tube with a seam) without interior nodes
  // across its closed direction, so that whole strips collapse onto the seam; a copy with such
  // faces cut in two (the same geometry; the result itself is not changed) meshes right.
  // The solid is meshed as it is, then (when that mesh fails its checks) as such a copy, then both
  // finer; when every mesh fails (or OCCT throws), samples are classified by OCCT's classifier.
  // (Meshing the copy first costs the overlapping springs a third more: cutting their trimmed
  // faces can throw.)
  TopoDS_Shape meshed;
  std::string problem, first_problem;
  std::vector<Triangle> tris;
  // the first mesh whose only fault is faces its triangles do not cover: kept, with the regions
  // of those faces, in case no mesh is right
  const double band = tol + 3 * deflection;
  std::vector<Triangle> partial_tris;
  std::vector<Eigen::AlignedBox3d> partial_avoid;
  std::string partial_what;
  // (the finer meshes are not made when one with uncovered faces is at hand: they cost more than
  // the classifier's share near those faces)
  for (int attempt = 0; attempt < 4 && (attempt == 0 || !problem.empty()) && (attempt < 2 || partial_tris.empty());
       ++attempt) {
    const bool divide = attempt % 2 == 1;
    r.classifier = std::string(attempt < 2 ? "the triangulation" : "a finer triangulation") +
                   (divide ? " (closed faces divided)" : "");
    if (!meshed.IsNull()) BRepTools::Clean(meshed);
    meshed = solid;
    std::vector<std::pair<TopoDS_Face, std::string>> uncovered;
    try {
      OCC_CATCH_SIGNALS
      if (divide) {
        ShapeUpgrade_ShapeDivideClosed divider(solid);
        divider.SetNbSplitPoints(1);
        divider.Perform();
        if (!divider.Result().IsNull()) meshed = divider.Result();
      }
      tris = triangulate(meshed, (attempt < 2 ? 1.0 : Settings::verdict_finer_deflection) * deflection, &problem,
                         &uncovered);
      if (problem.empty() && !uncovered.empty()) {
        problem = uncovered.front().second;
        if (partial_tris.empty()) {
          partial_what = std::to_string(uncovered.size()) + " faces whose triangles do not cover them (" + problem + ")";
          for (const FaceMesh& fm : face_meshes(meshed))
            for (const auto& [face, what] : uncovered)
              if (fm.face.IsSame(face))
                for (const auto& b : region_of(face, fm.xyz, band)) partial_avoid.push_back(b);
          partial_tris = tris;
        }
      }
    } catch (const Standard_Failure& f) {
      problem = std::string("OCCT failed to mesh it: ") + (f.GetMessageString() ? f.GetMessageString() : "");
      meshed = solid;
      tris.clear();
    }
    if (attempt == 0) first_problem = problem;
  }
  const bool partial = !problem.empty() && !partial_tris.empty();
  if (partial) {
    tris = std::move(partial_tris);
    r.classifier = "the triangulation, rays kept off " + partial_what;
  } else if (!problem.empty()) {
    r.classifier = "OCCT's solid classifier (" + first_problem + "; " + problem + ")";
    partial_avoid.clear();
  }
  const bool by_mesh = problem.empty() || partial;
  const MeshIndex mesh(by_mesh ? std::move(tris) : std::vector<Triangle>());
  const std::vector<FaceMesh> faces = face_meshes(meshed);
  r.box_volume = box.volume();
  FirstMismatch first(r.first_mismatch);
  std::size_t exact = 0;
  judge_samples(solid, by_mesh ? &mesh : nullptr, partial_avoid, box, member, tol, band, settings, first, r, &exact);
  if (partial) r.classifier += ", and OCCT's solid classifier for the " + std::to_string(exact) + " samples no such ray decides";
  const double delta = settings.probe_offset * tol;
  judge_probes(solid, tol,
               pick_probes(meshed, faces, deflection, Settings::probe_edge_clearance * delta + deflection, settings),
               member, delta, deflection, first, r);
  // The symmetric difference: where samples disagree, the band that was not tested and the
  // samples the membership did not decide.
  r.difference_bound =
      r.box_volume * proportion_upper_bound(r.mismatches + r.near_boundary + r.undecided, r.samples, settings.confidence);
  // the triangulation was the verdict's: the result goes out without it (the divided copy shares
  // the faces that were not cut)
  BRepTools::Clean(meshed);
  BRepTools::Clean(solid);
  return r;
}

double measured_geometric_error(const TopoDS_Shape& shape) {
  double worst = 0;
  ShapeAnalysis_Edge sae;
  for (TopExp_Explorer fx(shape, TopAbs_FACE); fx.More(); fx.Next()) {
    const TopoDS_Face& face = TopoDS::Face(fx.Current());
    TopLoc_Location sl;
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face, sl);
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e)) continue;
      double dev = 0;
      if (sae.CheckSameParameter(e, face, dev, Settings::pcurve_gap_samples)) worst = std::max(worst, dev);
      double f, l;
      const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
      const BRepAdaptor_Curve curve(e);
      for (TopExp_Explorer vx(e, TopAbs_VERTEX); vx.More(); vx.Next()) {
        const TopoDS_Vertex& v = TopoDS::Vertex(vx.Current());
        const gp_Pnt p = BRep_Tool::Pnt(v);
        const double t = BRep_Tool::Parameter(v, e);
        worst = std::max(worst, curve.Value(t).Distance(p));
        if (!pc.IsNull() && !surface.IsNull()) {
          const gp_Pnt2d uv = pc->Value(BRep_Tool::Parameter(v, e, face));
          worst = std::max(worst, surface->Value(uv.X(), uv.Y()).Transformed(sl.Transformation()).Distance(p));
        }
      }
    }
  }
  return worst;
}

}  // namespace sweep::occt
