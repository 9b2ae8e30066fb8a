/// @file kinematics_report.cpp
/// JSON, Graphviz DOT and text reports of a joint analysis, and the `axes` motion object.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "sweep/kinematics.hpp"

namespace sweep {
namespace kinematics {

using ojson = nlohmann::ordered_json;

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

ojson vec_json(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson basis_json(const ScrewBasis& b) {
  ojson out = ojson::array();
  for (Eigen::Index j = 0; j < b.cols(); ++j) {
    ojson t = ojson::array();
    for (int i = 0; i < 6; ++i) t.push_back(b(i, j));
    out.push_back(t);
  }
  return out;
}

std::string num(double x) {
  if (std::abs(x) < 5e-13) x = 0.0;
  std::ostringstream os;
  os << std::setprecision(6) << x;
  return os.str();
}

std::string vec_text(const Vec3& v) { return "(" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + ")"; }

/// Text for inside a DOT string: quotes and backslashes escaped.
std::string dot_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string dot_quote(const std::string& s) { return "\"" + dot_escape(s) + "\""; }

const std::string& part_name(const Assembly& a, int i) { return a.parts[static_cast<std::size_t>(i)]; }

/// Axis, centre or normal of a joint, in words.
std::string geometry_text(const Joint& j) {
  switch (j.kind) {
    case JointKind::Revolute:
    case JointKind::Cylindrical:
      return "axis through " + vec_text(j.point) + " along " + vec_text(j.direction);
    case JointKind::Helical:
      return "axis through " + vec_text(j.point) + " along " + vec_text(j.direction) + ", pitch " +
             num(j.pitch * kTwoPi) + " per turn";
    case JointKind::Prismatic:
      return "along " + vec_text(j.direction);
    case JointKind::Spherical:
      return "centre " + vec_text(j.point);
    case JointKind::Planar:
      return "normal " + vec_text(j.direction);
    default:
      return "";
  }
}

}  // namespace

ojson report_json(const Assembly& a, const Analysis& an) {
  ojson out;
  ojson joints = ojson::array();
  for (const auto& pj : an.joints) {
    const Joint& j = pj.joint;
    ojson e;
    e["parts"] = {part_name(a, pj.parts[0]), part_name(a, pj.parts[1])};
    e["type"] = to_string(j.kind);
    e["dof"] = j.dof;
    e["twists"] = basis_json(j.twists);
    e["redundant"] = j.redundant;
    e["rank"] = j.rank;
    e["constraints"] = pj.constraints;
    switch (j.kind) {
      case JointKind::Revolute:
      case JointKind::Helical:
      case JointKind::Cylindrical:
        e["axis"] = {{"point", vec_json(j.point)}, {"direction", vec_json(j.direction)}};
        if (j.kind == JointKind::Helical) e["pitch"] = j.pitch * kTwoPi;
        break;
      case JointKind::Prismatic:
        e["direction"] = vec_json(j.direction);
        break;
      case JointKind::Spherical:
        e["center"] = vec_json(j.point);
        break;
      case JointKind::Planar:
        e["normal"] = vec_json(j.direction);
        break;
      default:
        break;
    }
    joints.push_back(e);
  }
  out["joints"] = joints;
  ojson parts = ojson::array();
  for (std::size_t p = 0; p < a.parts.size(); ++p) {
    if (static_cast<int>(p) == a.ground) continue;
    parts.push_back({{"name", a.parts[p]}, {"dof", an.part_dof[p]}});
  }
  out["parts"] = parts;
  out["ground"] = part_name(a, a.ground);
  out["mobility"] = an.mobility;
  out["loop_redundant"] = an.loop_redundant;
  ojson over = ojson::array();
  for (int j : an.over_constrained()) {
    const auto& pj = an.joints[static_cast<std::size_t>(j)];
    over.push_back({{"parts", {part_name(a, pj.parts[0]), part_name(a, pj.parts[1])}},
                    {"redundant", pj.joint.redundant}});
  }
  out["over_constrained"] = over;
  return out;
}

std::string report_dot(const Assembly& a, const Analysis& an) {
  std::ostringstream os;
  os << "graph " << dot_quote(a.name.empty() ? "joints" : a.name) << " {\n";
  os << "  node [shape=ellipse];\n";
  for (std::size_t p = 0; p < a.parts.size(); ++p) {
    const bool g = static_cast<int>(p) == a.ground;
    const std::string second = g ? "" : "\\ndof " + std::to_string(an.part_dof[p]);
    os << "  " << dot_quote(a.parts[p]) << " [label=\"" << dot_escape(a.parts[p]) << second << "\""
       << (g ? ", shape=box, style=bold" : "") << "];\n";
  }
  for (const auto& pj : an.joints) {
    const Joint& j = pj.joint;
    std::string label = to_string(j.kind);
    if (j.kind == JointKind::Helical) label += " (pitch " + num(j.pitch * kTwoPi) + ")";
    if (j.kind == JointKind::Unrecognized) label += " (dof " + std::to_string(j.dof) + ")";
    if (j.redundant > 0) label += "\\n" + std::to_string(j.redundant) + " redundant";
    os << "  " << dot_quote(part_name(a, pj.parts[0])) << " -- " << dot_quote(part_name(a, pj.parts[1]))
       << " [label=\"" << label << "\"];\n";
  }
  os << "}\n";
  return os.str();
}

std::string report_table(const Assembly& a, const Analysis& an) {
  std::vector<std::array<std::string, 5>> rows;
  rows.push_back({"joint", "type", "dof", "redundant", "geometry"});
  for (const auto& pj : an.joints)
    rows.push_back({part_name(a, pj.parts[0]) + " - " + part_name(a, pj.parts[1]), to_string(pj.joint.kind),
                    std::to_string(pj.joint.dof), std::to_string(pj.joint.redundant),
                    geometry_text(pj.joint)});
  std::array<std::size_t, 5> w{};
  for (const auto& r : rows)
    for (std::size_t c = 0; c < 5; ++c) w[c] = std::max(w[c], r[c].size());
  std::ostringstream os;
  if (!a.name.empty()) os << a.name << "\n";
  os << a.parts.size() << " parts, " << a.constraints.size() << " constraints, ground "
     << part_name(a, a.ground) << "\n\n";
  for (const auto& r : rows) {
    std::string line = r[0] + std::string(w[0] - r[0].size() + 2, ' ') + r[1] +
                       std::string(w[1] - r[1].size() + 2, ' ') + std::string(w[2] - r[2].size(), ' ') +
                       r[2] + "  " + std::string(w[3] - r[3].size(), ' ') + r[3] + "  " + r[4];
    while (!line.empty() && line.back() == ' ') line.pop_back();
    os << line << "\n";
  }
  std::size_t pw = 4;
  for (const auto& p : a.parts) pw = std::max(pw, p.size());
  os << "\n"
     << "part" << std::string(pw - 4 + 2, ' ') << "dof\n";
  for (std::size_t p = 0; p < a.parts.size(); ++p) {
    if (static_cast<int>(p) == a.ground) continue;
    os << a.parts[p] << std::string(pw - a.parts[p].size() + 2, ' ') << std::setw(3) << an.part_dof[p]
       << "\n";
  }
  const auto over = an.over_constrained();
  int red = 0;
  for (int j : over) red += an.joints[static_cast<std::size_t>(j)].joint.redundant;
  os << "\nmobility " << an.mobility << "; over-constrained pairs " << over.size() << " (" << red
     << " redundant components); redundant in loops " << an.loop_redundant << "\n";
  return os.str();
}

ojson motion_json(const Motion& m) {
  ojson joints = ojson::array();
  for (const auto& j : m.joints) {
    ojson e;
    e["type"] = sweep::to_string(j.type);
    e["point"] = vec_json(j.point);
    e["direction"] = vec_json(j.direction);
    if (j.type == JointType::Helical) e["pitch"] = j.pitch * kTwoPi;
    e["range"] = {j.lo, j.hi};
    joints.push_back(e);
  }
  ojson out;
  out["kind"] = "axes";
  out["joints"] = joints;
  return out;
}

namespace {

void format_into(const ojson& j, int level, std::string& out) {
  const std::string pad(static_cast<std::size_t>(2 * level), ' ');
  const std::string inner(static_cast<std::size_t>(2 * level + 2), ' ');
  if (j.is_array()) {
    const bool flat = std::all_of(j.begin(), j.end(), [](const ojson& e) { return e.is_primitive(); });
    if (flat || j.empty()) {
      out += "[";
      for (std::size_t i = 0; i < j.size(); ++i) {
        if (i) out += ", ";
        format_into(j[i], level + 1, out);
      }
      out += "]";
      return;
    }
    out += "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out += inner;
      format_into(j[i], level + 1, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += pad + "]";
  } else if (j.is_object()) {
    if (j.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    std::size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      out += inner + ojson(it.key()).dump() + ": ";
      format_into(it.value(), level + 1, out);
      out += i + 1 < j.size() ? ",\n" : "\n";
    }
    out += pad + "}";
  } else if (j.is_number_float()) {
    // 12 significant digits: drops the last bits of rounding noise of the linear algebra.
    const double x = j.get<double>();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", x == 0.0 ? 0.0 : x);
    out += buf;
  } else {
    out += j.dump();
  }
}

}  // namespace

std::string format_json(const ojson& j) {
  std::string out;
  format_into(j, 0, out);
  return out + "\n";
}

}  // namespace kinematics
}  // namespace sweep
