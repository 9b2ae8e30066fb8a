// sweepvol joints: kinematic joint recognition of an assembly file (SPEC.md "Assembly file v1").
#include "joints_cmd.hpp"
#include "args.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "sweep/error.hpp"
#include "sweep/kinematics.hpp"
#include "sweep/spec.hpp"

namespace {

namespace kin = sweep::kinematics;

const char* kJointsUsage =
    "usage: sweepvol joints ASSEMBLY.json [--json] [--dot G.dot] [--motion-for PART [--range "
    "NAME=lo,hi]...]\n"
    "\n"
    "  (default)          table of the joints between constrained parts and of each part's mobility\n"
    "  --json             the same as JSON (SPEC.md)\n"
    "  --dot G.dot        also write the joint graph as Graphviz DOT\n"
    "  --motion-for PART  print the sweep-spec motion (kind \"axes\") that moves PART relative to the\n"
    "                     ground along a path of 1-dof joints, outermost first\n"
    "  --range NAME=lo,hi range of a joint on that path; NAME is \"partA-partB\" or the part the joint\n"
    "                     moves; overrides the assembly's \"ranges\"\n";

struct JointsArgs {
  std::string assembly, dot, motion_for;
  bool json = false, help = false;
  std::vector<std::string> ranges;
};

JointsArgs parse_joints_args(int argc, char** argv) {
  JointsArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* name) { return sweep::cli::option_value(argc, argv, i, name); };
    if (s == "--help" || s == "-h")
      a.help = true;
    else if (s == "--json")
      a.json = true;
    else if (s == "--dot")
      a.dot = value("--dot");
    else if (s.rfind("--dot=", 0) == 0)
      a.dot = s.substr(6);
    else if (s == "--motion-for")
      a.motion_for = value("--motion-for");
    else if (s.rfind("--motion-for=", 0) == 0)
      a.motion_for = s.substr(13);
    else if (s == "--range")
      a.ranges.push_back(value("--range"));
    else if (s.rfind("--range=", 0) == 0)
      a.ranges.push_back(s.substr(8));
    else if (!s.empty() && s[0] == '-')
      throw sweep::InputError(s, "unknown option '" + s + "'");
    else if (a.assembly.empty())
      a.assembly = s;
    else
      throw sweep::InputError(s, "unexpected argument '" + s + "'");
  }
  if (a.help) return a;
  if (a.assembly.empty()) throw sweep::InputError("ASSEMBLY", "missing assembly file argument");
  if (!a.ranges.empty() && a.motion_for.empty())
    throw sweep::InputError("--range", "--range applies to --motion-for only");
  if (!a.dot.empty() && a.dot == a.assembly)
    throw sweep::InputError("--dot", "refusing to overwrite the assembly file with the DOT graph");
  return a;
}

bool parse_number(const std::string& s, double* x) {
  if (s.empty()) return false;
  char* end = nullptr;
  *x = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(*x);
}

/// "NAME=lo,hi" (the range may be bracketed: NAME=[lo,hi]).
kin::RangeSpec parse_range_arg(const kin::Assembly& a, const std::string& arg) {
  const std::string where = "--range " + arg;
  const auto eq = arg.rfind('=');
  if (eq == std::string::npos || eq == 0) throw sweep::InputError(where, "expected NAME=lo,hi");
  std::string value = arg.substr(eq + 1);
  if (value.size() >= 2 && value.front() == '[' && value.back() == ']')
    value = value.substr(1, value.size() - 2);
  const auto comma = value.find(',');
  double lo = 0, hi = 0;
  if (comma == std::string::npos || !parse_number(value.substr(0, comma), &lo) ||
      !parse_number(value.substr(comma + 1), &hi))
    throw sweep::InputError(where, "expected NAME=lo,hi with two numbers");
  if (lo > hi) throw sweep::InputError(where, "the range needs lo <= hi");
  kin::RangeSpec r = kin::resolve_range_key(a, arg.substr(0, eq), where);
  r.lo = lo;
  r.hi = hi;
  return r;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw sweep::InputError("", "cannot read assembly file '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int run(const JointsArgs& args, std::string* text) {
  *text = read_file(args.assembly);
  const kin::Assembly a = kin::parse_assembly(*text);
  const kin::Analysis an = kin::analyze(a);

  if (!args.dot.empty()) {
    std::ofstream o(args.dot);
    if (!(o << kin::report_dot(a, an))) throw sweep::InputError("--dot", "cannot write '" + args.dot + "'");
  }

  if (!args.motion_for.empty()) {
    const int part = a.part_index(args.motion_for);
    if (part < 0) throw sweep::InputError("--motion-for", "unknown part '" + args.motion_for + "'");
    std::vector<kin::RangeSpec> overrides;
    for (const auto& r : args.ranges) overrides.push_back(parse_range_arg(a, r));
    const sweep::Motion m = kin::motion_for(a, an, part, overrides);
    const std::size_t path_dof = m.joints.size();
    if (an.part_dof[static_cast<std::size_t>(part)] < static_cast<int>(path_dof))
      std::cerr << "sweepvol: note: " << args.motion_for << " has "
                << an.part_dof[static_cast<std::size_t>(part)]
                << " dof through the whole assembly; the motion moves it through " << path_dof
                << " joints as an open chain (closed loops are not enforced)\n";
    std::cout << kin::format_json(kin::motion_json(m));
    return 0;
  }
  if (args.json)
    std::cout << kin::format_json(kin::report_json(a, an));
  else
    std::cout << kin::report_table(a, an);
  return 0;
}

}  // namespace

int sweep_joints_main(int argc, char** argv) {
  std::string text;
  try {
    const JointsArgs args = parse_joints_args(argc, argv);
    if (args.help) {
      std::cout << kJointsUsage;
      return 0;
    }
    return run(args, &text);
  } catch (const sweep::InputError& e) {
    std::cerr << "sweepvol: error: " << (e.pointer().empty() ? std::string("/") : e.pointer()) << ": "
              << e.what();
    int line = e.line(), col = e.column();
    if (line <= 0 && !text.empty() && !e.pointer().empty() && e.pointer()[0] == '/') {
      const auto lc = sweep::locate_pointer(text, e.pointer());
      line = lc.first;
      col = lc.second;
    }
    if (line > 0) std::cerr << " (line " << line << ", column " << col << ")";
    std::cerr << "\n";
    return 2;
  } catch (const sweep::ComputeError& e) {
    std::cerr << "sweepvol: failed: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "sweepvol: internal error: " << e.what() << "\n";
    return 1;
  }
}
