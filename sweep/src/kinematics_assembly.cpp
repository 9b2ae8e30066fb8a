/// @file kinematics_assembly.cpp
/// Assembly files (SPEC.md "Assembly file v1"), the joint graph and part mobilities, and the
/// motion of a part along a path of the graph.
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "kinematics_internal.hpp"
#include "sweep/error.hpp"
#include "sweep/kinematics.hpp"

namespace sweep {
namespace kinematics {

using nlohmann::json;

namespace {

std::string escape_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::string in_quotes(const std::string& s) { return "\"" + s + "\""; }

const char* type_name(const json& v) { return v.type_name(); }

double number(const json& v, const std::string& ptr) {
  if (!v.is_number()) throw InputError(ptr, std::string("expected a number, got ") + type_name(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(ptr, "expected a finite number");
  return x;
}

Vec3 vec3(const json& v, const std::string& ptr) {
  if (!v.is_array() || v.size() != 3) throw InputError(ptr, "expected an array of 3 numbers");
  Vec3 out;
  for (int i = 0; i < 3; ++i) out[i] = number(v[static_cast<std::size_t>(i)], ptr + "/" + std::to_string(i));
  return out;
}

bool is_comment(const std::string& key) { return !key.empty() && key[0] == '_'; }

void check_fields(const json& obj, const std::string& ptr, const std::set<std::string>& allowed,
                  const std::string& what) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (is_comment(it.key()) || allowed.count(it.key())) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InputError(ptr + "/" + escape_token(it.key()),
                     "unknown field " + in_quotes(it.key()) + " in " + what + " (expected " + list + ")");
  }
}

const json& field(const json& obj, const std::string& key, const std::string& ptr) {
  auto it = obj.find(key);
  if (it == obj.end()) throw InputError(ptr + "/" + key, "missing field " + in_quotes(key));
  return *it;
}

Vec3 direction(const json& v, const std::string& ptr, const char* what) {
  const Vec3 d = vec3(v, ptr);
  if (!(d.norm() > 1e-12))
    throw InputError(ptr, std::string(what) + " must not be zero (got [" + std::to_string(d.x()) + ", " +
                              std::to_string(d.y()) + ", " + std::to_string(d.z()) + "])");
  return d;
}

Axis axis(const json& obj, const std::string& ptr) {
  if (!obj.is_object())
    throw InputError(ptr, "expected an axis object {\"point\": [x, y, z], \"direction\": [x, y, z]}");
  check_fields(obj, ptr, {"point", "direction"}, "an axis");
  Axis a;
  a.point = vec3(field(obj, "point", ptr), ptr + "/point");
  a.direction = direction(field(obj, "direction", ptr), ptr + "/direction", "degenerate axis: the direction");
  return a;
}

Plane plane(const json& obj, const std::string& ptr) {
  if (!obj.is_object())
    throw InputError(ptr, "expected a plane object {\"point\": [x, y, z], \"normal\": [x, y, z]}");
  check_fields(obj, ptr, {"point", "normal"}, "a plane");
  Plane p;
  p.point = vec3(field(obj, "point", ptr), ptr + "/point");
  p.normal = direction(field(obj, "normal", ptr), ptr + "/normal", "degenerate plane: the normal");
  return p;
}

std::array<double, 2> range_pair(const json& v, const std::string& ptr) {
  if (!v.is_array() || v.size() != 2) throw InputError(ptr, "expected a range [lo, hi]");
  const double lo = number(v[0], ptr + "/0"), hi = number(v[1], ptr + "/1");
  if (lo > hi)
    throw InputError(
        ptr, "range [lo, hi] needs lo <= hi (got [" + std::to_string(lo) + ", " + std::to_string(hi) + "])");
  return {lo, hi};
}

std::pair<int, int> line_column(const std::string& text, std::size_t byte) {
  int line = 1, col = 1;
  for (std::size_t i = 0; i < text.size() && i < byte; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

double angle_between_lines(const Vec3& a, const Vec3& b) {
  return std::asin(std::min(1.0, a.normalized().cross(b.normalized()).norm()));
}

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

/// Checks that constraint `c` holds at the given position.
void check_consistency(const GeometryConstraint& c, const std::string& ptr, const NumericFrame& f) {
  const double lt = f.length_tolerance(), at = f.tolerance;
  auto parallel = [&](const Vec3& a, const Vec3& b, const std::string& p, const char* what) {
    const double ang = angle_between_lines(a, b);
    if (ang > at)
      throw InputError(p, std::string(what) + " (angle " + fmt(ang) + " rad, tolerance " + fmt(at) + ")");
  };
  auto near = [&](double d, const std::string& p, const char* what) {
    if (d > lt)
      throw InputError(p, std::string(what) + " (off by " + fmt(d) + ", tolerance " + fmt(lt) + ")");
  };
  auto line_distance = [](const Vec3& x, const Axis& a) {
    return (x - a.point).cross(a.direction.normalized()).norm();
  };
  switch (c.type) {
    case ConstraintType::Coaxial:
      parallel(c.axis1.direction, c.axis2.direction, ptr + "/axis2/direction",
               "axis2 is not parallel to axis1");
      near(line_distance(c.axis2.point, c.axis1), ptr + "/axis2/point", "axis2 is not on the line of axis1");
      break;
    case ConstraintType::Coplanar:
      parallel(c.plane1.normal, c.plane2.normal, ptr + "/plane2/normal", "plane2 is not parallel to plane1");
      near(std::abs((c.plane2.point - c.plane1.point).dot(c.plane1.normal.normalized())),
           ptr + "/plane2/point", "plane2 is not in plane1");
      break;
    case ConstraintType::Spherical:
      near((c.point2 - c.point1).norm(), ptr + "/point2", "point2 does not coincide with point1");
      break;
    case ConstraintType::Align:
      parallel(c.plane1.normal, c.plane2.normal, ptr + "/plane2/normal", "plane2 is not parallel to plane1");
      break;
    case ConstraintType::LineSurfaceDistance: {
      const Vec3 n = c.plane2.normal.normalized();
      const double s = std::abs(c.axis1.direction.normalized().dot(n));
      if (std::asin(std::min(1.0, s)) > at)
        throw InputError(ptr + "/axis1/direction", "axis1 is not parallel to plane2 (angle " +
                                                       fmt(std::asin(std::min(1.0, s))) + " rad)");
      near(std::abs(std::abs((c.axis1.point - c.plane2.point).dot(n)) - c.distance), ptr + "/distance",
           "the distance between axis1 and plane2 differs from \"distance\"");
      break;
    }
    case ConstraintType::PointOnLine:
      near(line_distance(c.point1, c.axis2), ptr + "/point1", "point1 is not on axis2");
      break;
  }
}

std::vector<Vec3> constraint_points(const GeometryConstraint& c) {
  switch (c.type) {
    case ConstraintType::Coaxial:
      return {c.axis1.point, c.axis2.point};
    case ConstraintType::Coplanar:
    case ConstraintType::Align:
      return {c.plane1.point, c.plane2.point};
    case ConstraintType::Spherical:
      return {c.point1, c.point2};
    case ConstraintType::LineSurfaceDistance:
      return {c.axis1.point, c.plane2.point};
    case ConstraintType::PointOnLine:
      return {c.point1, c.axis2.point};
  }
  return {};
}

struct TypeInfo {
  ConstraintType type;
  std::vector<std::string> fields;
};

const std::map<std::string, TypeInfo>& constraint_types() {
  static const std::map<std::string, TypeInfo> types = {
      {"coaxial", {ConstraintType::Coaxial, {"axis1", "axis2"}}},
      {"coplanar", {ConstraintType::Coplanar, {"plane1", "plane2"}}},
      {"spherical", {ConstraintType::Spherical, {"point1", "point2"}}},
      {"align", {ConstraintType::Align, {"plane1", "plane2"}}},
      {"line_surface_distance", {ConstraintType::LineSurfaceDistance, {"axis1", "plane2", "distance"}}},
      {"point_on_line", {ConstraintType::PointOnLine, {"point1", "axis2"}}},
  };
  return types;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Parsing

int Assembly::part_index(const std::string& n) const {
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (parts[i] == n) return static_cast<int>(i);
  return -1;
}

std::string Assembly::joint_name(int a, int b) const {
  if (a > b) std::swap(a, b);
  return parts[static_cast<std::size_t>(a)] + "-" + parts[static_cast<std::size_t>(b)];
}

NumericFrame assembly_frame(const Assembly& a, const Settings& settings) {
  NumericFrame f;
  f.rank_factor = settings.rank_factor;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const auto& c : a.constraints)
    for (const Vec3& p : constraint_points(c)) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (a.constraints.empty()) {
    lo.setZero();
    hi.setZero();
  }
  f.center = 0.5 * (lo + hi);
  const double diag = (hi - lo).norm();
  f.scale = diag > 0.0 ? diag : 1.0;
  f.tolerance = a.tolerance > 0.0 ? a.tolerance / f.scale : settings.relative_tolerance;
  return f;
}

RangeSpec resolve_range_key(const Assembly& a, const std::string& key, const std::string& pointer) {
  std::set<std::pair<int, int>> pairs;
  for (const auto& c : a.constraints)
    pairs.insert({std::min(c.parts[0], c.parts[1]), std::max(c.parts[0], c.parts[1])});
  std::vector<RangeSpec> matches;
  for (const auto& [x, y] : pairs) {
    const std::string& nx = a.parts[static_cast<std::size_t>(x)];
    const std::string& ny = a.parts[static_cast<std::size_t>(y)];
    if (key == nx + "-" + ny || key == ny + "-" + nx) {
      RangeSpec r;
      r.joint = {x, y};
      matches.push_back(r);
    }
  }
  const int p = a.part_index(key);
  if (p >= 0) {
    if (p == a.ground)
      throw InputError(pointer, in_quotes(key) + " is the ground, which has no joint to give a range to");
    RangeSpec r;
    r.part = p;
    matches.push_back(r);
  }
  if (matches.empty())
    throw InputError(pointer, in_quotes(key) +
                                  " names neither a part nor a joint (a joint is \"partA-partB\" for two "
                                  "constrained parts)");
  if (matches.size() > 1)
    throw InputError(pointer, in_quotes(key) + " is ambiguous: it names several joints or parts");
  matches[0].source = pointer;
  return matches[0];
}

Assembly parse_assembly(const std::string& text, const Settings& settings) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    const auto [line, col] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string msg = e.what();
    const auto pos = msg.find("] ");
    if (pos != std::string::npos) msg = msg.substr(pos + 2);
    const auto at = msg.find("parse error at line ");
    const auto colon = msg.find(": ", at == std::string::npos ? 0 : at);
    if (at == 0 && colon != std::string::npos) msg = msg.substr(colon + 2);
    throw InputError("", "invalid JSON: " + msg, line, col);
  }
  if (!doc.is_object()) throw InputError("", "an assembly file is a JSON object");
  check_fields(doc, "", {"assembly", "name", "parts", "ground", "constraints", "ranges", "tolerance"},
               "an assembly");

  Assembly a;
  const json& version = field(doc, "assembly", "");
  if (!version.is_number_integer() || version.get<long long>() != 1)
    throw InputError("/assembly", "unsupported assembly version (expected 1)");
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) throw InputError("/name", "expected a string");
    a.name = doc["name"].get<std::string>();
  }
  if (doc.contains("tolerance")) {
    a.tolerance = number(doc["tolerance"], "/tolerance");
    if (!(a.tolerance > 0.0))
      throw InputError("/tolerance", "must be positive (got " + fmt(a.tolerance) + ")");
  }

  const json& parts = field(doc, "parts", "");
  if (!parts.is_array() || parts.empty())
    throw InputError("/parts", "expected a non-empty array of part names");
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string ptr = "/parts/" + std::to_string(i);
    if (!parts[i].is_string() || parts[i].get<std::string>().empty())
      throw InputError(ptr, "expected a non-empty part name");
    const std::string n = parts[i].get<std::string>();
    if (a.part_index(n) >= 0) throw InputError(ptr, "duplicate part name " + in_quotes(n));
    a.parts.push_back(n);
  }

  const json& ground = field(doc, "ground", "");
  if (!ground.is_string()) throw InputError("/ground", "expected a part name");
  a.ground = a.part_index(ground.get<std::string>());
  if (a.ground < 0)
    throw InputError("/ground",
                     "the ground " + in_quotes(ground.get<std::string>()) + " is not among the parts");

  const json& cons = field(doc, "constraints", "");
  if (!cons.is_array()) throw InputError("/constraints", "expected an array of constraints");
  std::vector<std::string> pointers;
  std::vector<std::pair<std::array<double, 2>, std::string>> local_ranges;
  for (std::size_t i = 0; i < cons.size(); ++i) {
    const std::string ptr = "/constraints/" + std::to_string(i);
    const json& c = cons[i];
    if (!c.is_object()) throw InputError(ptr, "expected a constraint object");
    const json& type = field(c, "type", ptr);
    std::string known;
    for (const auto& [n, info] : constraint_types()) known += (known.empty() ? "" : ", ") + n;
    if (!type.is_string()) throw InputError(ptr + "/type", "expected one of " + known);
    const auto it = constraint_types().find(type.get<std::string>());
    if (it == constraint_types().end())
      throw InputError(ptr + "/type", "unknown constraint type " + in_quotes(type.get<std::string>()) +
                                          " (expected one of " + known + ")");
    const TypeInfo& info = it->second;
    std::set<std::string> allowed(info.fields.begin(), info.fields.end());
    allowed.insert({"type", "parts", "range", "name"});
    check_fields(c, ptr, allowed, std::string("a ") + it->first + " constraint");

    GeometryConstraint g;
    g.type = info.type;
    const json& ps = field(c, "parts", ptr);
    if (!ps.is_array() || ps.size() != 2) throw InputError(ptr + "/parts", "expected two part names");
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string pp = ptr + "/parts/" + std::to_string(k);
      if (!ps[k].is_string()) throw InputError(pp, "expected a part name");
      const int idx = a.part_index(ps[k].get<std::string>());
      if (idx < 0) throw InputError(pp, "unknown part " + in_quotes(ps[k].get<std::string>()));
      g.parts[k] = idx;
    }
    if (g.parts[0] == g.parts[1])
      throw InputError(ptr + "/parts", "a part cannot be constrained with itself (" +
                                           in_quotes(a.parts[static_cast<std::size_t>(g.parts[0])]) +
                                           " twice)");
    for (const auto& f : info.fields) {
      const json& v = field(c, f, ptr);
      const std::string fp = ptr + "/" + f;
      if (f == "axis1")
        g.axis1 = axis(v, fp);
      else if (f == "axis2")
        g.axis2 = axis(v, fp);
      else if (f == "plane1")
        g.plane1 = plane(v, fp);
      else if (f == "plane2")
        g.plane2 = plane(v, fp);
      else if (f == "point1")
        g.point1 = vec3(v, fp);
      else if (f == "point2")
        g.point2 = vec3(v, fp);
      else if (f == "distance") {
        g.distance = number(v, fp);
        if (g.distance < 0.0) throw InputError(fp, "must be >= 0 (got " + fmt(g.distance) + ")");
      }
    }
    if (c.contains("name") && !c["name"].is_string()) throw InputError(ptr + "/name", "expected a string");
    if (c.contains("range")) {
      RangeSpec r;
      const auto lh = range_pair(c["range"], ptr + "/range");
      r.joint = {std::min(g.parts[0], g.parts[1]), std::max(g.parts[0], g.parts[1])};
      r.lo = lh[0];
      r.hi = lh[1];
      r.source = ptr + "/range";
      a.ranges.push_back(r);
    }
    a.constraints.push_back(g);
    pointers.push_back(ptr);
  }

  if (doc.contains("ranges")) {
    const json& rs = doc["ranges"];
    if (!rs.is_object())
      throw InputError("/ranges", "expected an object {\"partA-partB\": [lo, hi], \"part\": [lo, hi]}");
    for (auto it = rs.begin(); it != rs.end(); ++it) {
      if (is_comment(it.key())) continue;
      const std::string ptr = "/ranges/" + escape_token(it.key());
      RangeSpec r = resolve_range_key(a, it.key(), ptr);
      const auto lh = range_pair(it.value(), ptr);
      r.lo = lh[0];
      r.hi = lh[1];
      a.ranges.push_back(r);
    }
  }
  // Two ranges for one target must agree.
  for (std::size_t i = 0; i < a.ranges.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const RangeSpec &x = a.ranges[i], &y = a.ranges[j];
      if (x.joint == y.joint && x.part == y.part && (x.lo != y.lo || x.hi != y.hi))
        throw InputError(x.source, "conflicts with the range given at " + y.source);
    }

  const NumericFrame frame = assembly_frame(a, settings);
  for (std::size_t i = 0; i < a.constraints.size(); ++i)
    check_consistency(a.constraints[i], pointers[i], frame);
  return a;
}

Assembly load_assembly(const std::string& path, const Settings& settings) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("", "cannot read assembly file " + in_quotes(path));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_assembly(ss.str(), settings);
}

// ---------------------------------------------------------------------------------------------
// Analysis

int Analysis::find_joint(int a, int b) const {
  if (a > b) std::swap(a, b);
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].parts[0] == a && joints[i].parts[1] == b) return static_cast<int>(i);
  return -1;
}

std::vector<int> Analysis::over_constrained() const {
  std::vector<int> out;
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].joint.redundant > 0) out.push_back(static_cast<int>(i));
  return out;
}

Analysis analyze(const Assembly& a, const Settings& settings) {
  Analysis an;
  an.frame = assembly_frame(a, settings);
  const NumericFrame& f = an.frame;

  // Group the constraints by pair of parts.
  std::map<std::pair<int, int>, std::vector<int>> groups;
  for (std::size_t i = 0; i < a.constraints.size(); ++i) {
    const auto& p = a.constraints[i].parts;
    groups[{std::min(p[0], p[1]), std::max(p[0], p[1])}].push_back(static_cast<int>(i));
  }

  // Algorithm 1 for each pair; keep the local wrench span for the global system.
  std::vector<Eigen::MatrixXd> wrench_spans;
  for (const auto& [pair, idx] : groups) {
    PairJoint pj;
    pj.parts = {pair.first, pair.second};
    pj.constraints = idx;
    std::vector<Wrench> ws;
    for (int i : idx) {
      const auto w = constraint_wrenches(a.constraints[static_cast<std::size_t>(i)]);
      ws.insert(ws.end(), w.begin(), w.end());
    }
    pj.joint = recognize_joint(ws, f);
    Eigen::MatrixXd local(6, static_cast<Eigen::Index>(ws.size()));
    for (std::size_t j = 0; j < ws.size(); ++j)
      local.col(static_cast<Eigen::Index>(j)) = f.wrench_to_local(ws[j]);
    wrench_spans.push_back(detail::span_basis(local, f));
    an.joints.push_back(pj);
  }

  // Unknowns: the local twist of every part but the ground.
  const int n = static_cast<int>(a.parts.size());
  std::vector<int> col(static_cast<std::size_t>(n), -1);
  int unknowns = 0;
  for (int p = 0; p < n; ++p)
    if (p != a.ground) col[static_cast<std::size_t>(p)] = 6 * unknowns++;
  int rows = 0;
  for (const auto& s : wrench_spans) rows += static_cast<int>(s.cols());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, 6 * unknowns);
  int r = 0;
  for (std::size_t j = 0; j < an.joints.size(); ++j) {
    const auto& s = wrench_spans[j];
    const int pa = an.joints[j].parts[0], pb = an.joints[j].parts[1];
    for (Eigen::Index k = 0; k < s.cols(); ++k, ++r) {
      // reciprocal product of the wrench with t_b - t_a
      const Eigen::Matrix<double, 1, 6> w = swap_triplets(s.col(k)).transpose();
      if (col[static_cast<std::size_t>(pb)] >= 0) A.block<1, 6>(r, col[static_cast<std::size_t>(pb)]) += w;
      if (col[static_cast<std::size_t>(pa)] >= 0) A.block<1, 6>(r, col[static_cast<std::size_t>(pa)]) -= w;
    }
  }
  int rank = 0;
  const Eigen::MatrixXd N = detail::null_space(A, f, &rank);
  an.mobility = static_cast<int>(N.cols());
  an.loop_redundant = rows - rank;

  an.part_dof.assign(static_cast<std::size_t>(n), 0);
  an.part_twists.assign(static_cast<std::size_t>(n), ScrewBasis(6, 0));
  for (int p = 0; p < n; ++p) {
    if (p == a.ground) continue;
    const Eigen::MatrixXd block = N.middleRows(col[static_cast<std::size_t>(p)], 6);
    // Not normalized column by column: columns of rounding-noise size must stay negligible.
    ScrewBasis local = detail::span_basis(block, f, false);
    an.part_dof[static_cast<std::size_t>(p)] = static_cast<int>(local.cols());
    ScrewBasis world = detail::to_world(local, f);
    detail::clean(world, f.center.norm() + f.scale);
    an.part_twists[static_cast<std::size_t>(p)] = world;
  }
  return an;
}

// ---------------------------------------------------------------------------------------------
// Paths and motions

std::vector<int> joint_path(const Assembly& a, const Analysis& an, int part) {
  const int n = static_cast<int>(a.parts.size());
  if (part < 0 || part >= n || part == a.ground) return {};
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> via(static_cast<std::size_t>(n), -1);  // joint index that reached the part
    std::vector<bool> seen(static_cast<std::size_t>(n), false);
    std::deque<int> queue{a.ground};
    seen[static_cast<std::size_t>(a.ground)] = true;
    while (!queue.empty()) {
      const int p = queue.front();
      queue.pop_front();
      for (std::size_t j = 0; j < an.joints.size(); ++j) {
        const auto& pj = an.joints[j];
        if (pass == 0 && (!pj.joint.is_screw() || pj.joint.dof != 1)) continue;
        int q = -1;
        if (pj.parts[0] == p)
          q = pj.parts[1];
        else if (pj.parts[1] == p)
          q = pj.parts[0];
        if (q < 0 || seen[static_cast<std::size_t>(q)]) continue;
        seen[static_cast<std::size_t>(q)] = true;
        via[static_cast<std::size_t>(q)] = static_cast<int>(j);
        queue.push_back(q);
      }
    }
    if (!seen[static_cast<std::size_t>(part)]) continue;
    std::vector<int> path;
    for (int p = part; p != a.ground;) {
      const int j = via[static_cast<std::size_t>(p)];
      path.push_back(j);
      const auto& pj = an.joints[static_cast<std::size_t>(j)];
      p = pj.parts[0] == p ? pj.parts[1] : pj.parts[0];
    }
    std::reverse(path.begin(), path.end());
    return path;
  }
  return {};
}

Motion motion_for(const Assembly& a, const Analysis& an, int part, const std::vector<RangeSpec>& overrides) {
  if (part < 0 || part >= static_cast<int>(a.parts.size())) throw InputError("/parts", "unknown part");
  const std::string& name = a.parts[static_cast<std::size_t>(part)];
  if (part == a.ground) throw InputError("/ground", in_quotes(name) + " is the ground: it does not move");
  const std::vector<int> path = joint_path(a, an, part);
  if (path.empty())
    throw InputError("/constraints",
                     "no chain of constraints connects " + in_quotes(name) + " to the ground");

  Motion m;
  int parent = a.ground;
  for (int j : path) {
    const PairJoint& pj = an.joints[static_cast<std::size_t>(j)];
    const int child = pj.parts[0] == parent ? pj.parts[1] : pj.parts[0];
    const std::string jn = a.joint_name(pj.parts[0], pj.parts[1]);
    const std::string first = "/constraints/" + std::to_string(pj.constraints.front());
    if (!pj.joint.is_screw())
      throw InputError(first, "joint " + jn + " on the path to " + in_quotes(name) + " is " +
                                  to_string(pj.joint.kind) + " with " + std::to_string(pj.joint.dof) +
                                  " dof; a motion needs 1-dof revolute, prismatic or helical joints");
    const RangeSpec* found = nullptr;
    for (const auto* list : {&overrides, &a.ranges}) {
      for (const auto& r : *list)
        if (r.part < 0 && r.joint == pj.parts) found = &r;
      if (!found)
        for (const auto& r : *list)
          if (r.part == child) found = &r;
      if (found) break;
    }
    if (!found)
      throw InputError("/ranges", "joint " + jn + " on the path to " + in_quotes(name) +
                                      " has no range (give \"ranges\": {\"" + jn +
                                      "\": [lo, hi]} or --range " + jn + "=lo,hi)");
    ScrewJoint sj;
    sj.type = pj.joint.kind == JointKind::Revolute    ? JointType::Revolute
              : pj.joint.kind == JointKind::Prismatic ? JointType::Prismatic
                                                      : JointType::Helical;
    sj.direction = pj.joint.direction;
    sj.point = pj.joint.point;
    if (sj.type == JointType::Prismatic) {
      // Any point will do; take the centre of the constraint geometry of the pair.
      Vec3 c = Vec3::Zero();
      int cnt = 0;
      for (int ci : pj.constraints)
        for (const Vec3& p : constraint_points(a.constraints[static_cast<std::size_t>(ci)])) {
          c += p;
          ++cnt;
        }
      sj.point = c / std::max(cnt, 1);
    }
    sj.pitch = pj.joint.pitch;
    sj.lo = found->lo;
    sj.hi = found->hi;
    m.joints.push_back(sj);
    parent = child;
  }
  return m;
}

}  // namespace kinematics
}  // namespace sweep
