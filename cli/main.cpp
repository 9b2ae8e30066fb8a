// sweepvol: the command line of SPEC.md. Thin: parse, call, report.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "joints_cmd.hpp"
#include "args.hpp"
#include "section_cmd.hpp"
#include "stop_request.hpp"
#include "worker.hpp"
#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"

namespace {

const char* kUsage =
    "usage: sweepvol COMMAND [ARGS]\n"
    "\n"
    "commands:\n"
    "  run SPEC [-o OUT] [--report R.json] [--set PATH=VALUE]... [--verify] [--time-limit S]\n"
    "      [--no-direct-builds] [--general-motions]\n"
    "      compute the swept solid; OUT by extension: .step/.stp, .brep, .stl (binary), .off;\n"
    "      --time-limit stops the run after S seconds (default 600; status failed, exit 3)\n"
    "      --no-direct-builds builds balls under screws and graph extrusions by the general pipeline too\n"
    "      --general-motions builds other solids under paths from their candidate patches (in progress)\n"
    "  check SPEC [--set PATH=VALUE]...\n"
    "      validate the spec only\n"
    "  varieties SPEC [-o V.json] [--faces F.brep|F.step] [--svg F.svg] [--set PATH=VALUE]... [--time-limit S]\n"
    "      the boundary varieties of every stage: fixed and free parameters, the part on the final\n"
    "      boundary and its volume contribution; --faces writes the last stage's candidate faces,\n"
    "      --svg draws them (parallel projection, one colour per variety, legend)\n"
    "  section SPEC --z Z1,Z2,... [--svg F.svg] [-o S.json] [--set PATH=VALUE]... [--time-limit S]\n"
    "      cut the swept solid by the planes z = Z1, Z2, ...: area, loops and box of each section\n"
    "      (JSON, also written to S.json with -o); --svg draws them side by side\n"
    "  joints ASSEMBLY.json [--json] [--dot G.dot] [--motion-for PART [--range NAME=lo,hi]...]\n"
    "      kinematic joint recognition\n"
    "  --help, --version\n"
    "\n"
    "exit codes: 0 success, 2 invalid input, 3 computation failed or result not valid, 1 internal error;\n"
    "run, varieties and section compute in a worker process: --time-limit, Ctrl-C (SIGINT) or SIGTERM\n"
    "stops them as failed (exit 3) within a second, whatever step they are in, and no output file is left\n";

struct Args {
  std::string spec, out, report, faces, svg;
  std::vector<std::string> sets;
  bool verify = false;
  double time_limit = sweep::cli::kDefaultTimeLimit;  ///< seconds
  bool direct_builds = true;
  bool general_motions = false;
};

Args parse_args(int argc, char** argv, bool allow_output) {
  Args a;
  for (int i = 2; i < argc; ++i) {
    std::string s = argv[i];
    auto value = [&](const char* name) { return sweep::cli::option_value(argc, argv, i, name); };
    if (s == "--set") a.sets.push_back(value("--set"));
    else if (s.rfind("--set=", 0) == 0) a.sets.push_back(s.substr(6));
    else if (allow_output && s == "-o") a.out = value("-o");
    else if (allow_output && s == "--report") a.report = value("--report");
    else if (allow_output && s == "--verify") a.verify = true;
    else if (allow_output && s == "--faces") a.faces = value("--faces");
    else if (allow_output && s == "--svg") a.svg = value("--svg");
    else if (allow_output && s == "--no-direct-builds") a.direct_builds = false;
    else if (allow_output && s == "--general-motions") a.general_motions = true;
    else if (allow_output && s == "--time-limit") a.time_limit = sweep::cli::parse_time_limit(value("--time-limit"));
    else if (!s.empty() && s[0] == '-') throw sweep::InputError(s, "unknown option '" + s + "'");
    else if (a.spec.empty()) a.spec = s;
    else throw sweep::InputError(s, "unexpected argument '" + s + "'");
  }
  if (a.spec.empty()) throw sweep::InputError("SPEC", "missing spec file argument");
  return a;
}

bool write_text_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".partial";
  {
    std::ofstream o(tmp);
    o << text;
    if (!o) {
      std::remove(tmp.c_str());
      return false;
    }
  }
  return std::rename(tmp.c_str(), path.c_str()) == 0;
}

int cmd_check(int argc, char** argv) {
  Args a = parse_args(argc, argv, false);
  sweep::Spec s = sweep::load_spec(a.spec, a.sets);
  std::cout << "ok: " << a.spec << " (" << sweep::to_string(s.entity.kind) << ", "
            << sweep::to_string(s.motion.kind) << ", " << s.motion.motion.dof() << " joint"
            << (s.motion.motion.dof() == 1 ? "" : "s") << ")\n";
  return 0;
}

int cmd_run(int argc, char** argv) {
  Args a = parse_args(argc, argv, true);
  if (!a.svg.empty()) throw sweep::InputError("--svg", "--svg applies to varieties and section, not run");
  if (!a.out.empty() && !sweep::occt::supported_output(a.out))
    throw sweep::InputError("-o", "unsupported output extension in '" + a.out +
                                      "' (expected .step, .stp, .brep, .stl or .off)");
  sweep::Spec s = sweep::load_spec(a.spec, a.sets);
  sweep::occt::RunOptions opt;
  opt.verify = a.verify;
  opt.direct_builds = a.direct_builds;
  opt.settings.general_motions = a.general_motions;
  if (sweep::cli::stderr_is_terminal()) opt.progress = [](const std::string& line) { std::cerr << "sweepvol: " << line << "\n"; };
  opt.stop = sweep::cli::stop_request(a.time_limit);
  sweep::occt::RunResult r = sweep::occt::run_sweep(s, opt);
  if (r.report.ok() && !a.out.empty()) {
    try {
      double size = 0;
      for (int k = 0; k < 3; ++k) size = std::max(size, r.report.bbox_max[k] - r.report.bbox_min[k]);
      sweep::occt::write_shape(*r.shape, a.out, std::max(1e-4 * size, r.report.tol_requested));
    } catch (const sweep::ComputeError& e) {
      r.report.status = "failed";
      r.report.message = e.what();
    }
  }
  const std::string text = r.report.to_json().dump(2) + "\n";
  std::cout << text;
  if (!a.report.empty() && !write_text_atomic(a.report, text))
    throw sweep::ComputeError("cannot write report '" + a.report + "'");
  if (!r.report.ok()) {
    std::cerr << "sweepvol: failed: " << r.report.message << "\n";
    return 3;
  }
  return 0;
}

int cmd_varieties(int argc, char** argv) {
  Args a = parse_args(argc, argv, true);
  if (!a.faces.empty() && !sweep::occt::supported_output(a.faces))
    throw sweep::InputError("--faces", "unsupported extension in '" + a.faces + "' (expected .step, .stp or .brep)");
  if (!a.svg.empty()) sweep_check_svg_path(a.svg, "--svg");
  sweep::Spec s = sweep::load_spec(a.spec, a.sets);
  sweep::occt::RunOptions opt;
  std::vector<sweep::occt::Variety> vars;
  std::shared_ptr<const sweep::occt::Shape> faces;
  opt.varieties = &vars;
  opt.variety_faces = &faces;
  std::vector<int> face_ids;
  opt.variety_face_ids = &face_ids;
  if (sweep::cli::stderr_is_terminal()) opt.progress = [](const std::string& line) { std::cerr << "sweepvol: " << line << "\n"; };
  opt.stop = sweep::cli::stop_request(a.time_limit);
  sweep::occt::RunResult r = sweep::occt::run_sweep(s, opt);
  nlohmann::json out;
  out["sweep_varieties"] = 1;
  out["status"] = r.report.status;
  out["message"] = r.report.message;
  out["volume"] = r.report.to_json()["volume"];
  out["varieties"] = nlohmann::json::array();
  double sum = 0;
  for (const auto& v : vars) {
    out["varieties"].push_back(v.to_json());
    if (v.final_stage) sum += v.volume;
  }
  out["volume_from_varieties"] = sum;
  const std::string text = out.dump(2) + "\n";
  if (r.report.ok() && faces && !a.faces.empty()) sweep::occt::write_shape(*faces, a.faces, 1e-3);
  if (r.report.ok() && faces && !a.svg.empty()) sweep_write_varieties_svg(a.svg, s, *faces, face_ids, vars);
  if (!a.out.empty()) {
    if (!write_text_atomic(a.out, text)) throw sweep::ComputeError("cannot write '" + a.out + "'");
  } else {
    std::cout << text;
  }
  if (!r.report.ok()) {
    std::cerr << "sweepvol: failed: " << r.report.message << "\n";
    return 3;
  }
  return 0;
}

/// The --time-limit a supervised command gives (the default when none); false when it gives a bad
/// one (the command's own parser then reports it).
bool time_limit_of(int argc, char** argv, double& seconds) {
  seconds = sweep::cli::kDefaultTimeLimit;
  for (int i = 2; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--time-limit") {
      try {
        seconds = sweep::cli::parse_time_limit(argv[i + 1]);
      } catch (const sweep::InputError&) {
        return false;
      }
    }
  return true;
}

/// What run, varieties and section print when their worker had to be ended: their failed report
/// with the reason, also written to the report file of `run`.
int report_ended(const std::string& cmd, const std::string& reason, const std::vector<sweep::cli::Output>& outputs) {
  sweep::occt::Report report;
  report.status = "failed";
  report.message = reason;
  nlohmann::json out;
  if (cmd == "run") {
    out = report.to_json();
  } else {
    out[cmd == "section" ? "sweep_section" : "sweep_varieties"] = 1;
    out["status"] = report.status;
    out["message"] = reason;
    out["volume"] = report.to_json()["volume"];
    out[cmd == "section" ? "sections" : "varieties"] = nlohmann::json::array();
  }
  const std::string text = out.dump(2) + "\n";
  std::cout << text;
  for (const sweep::cli::Output& o : outputs)
    if (cmd == "run" && o.option == "--report") write_text_atomic(o.path, text);
  std::cerr << "sweepvol: failed: " << reason << "\n";
  return 3;
}

int dispatch(int argc, char** argv) {
  const std::string cmd = argv[1];
  try {
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      std::cout << kUsage;
      return 0;
    }
    if (cmd == "--version") {
      std::cout << "sweepvol " << SWEEP_VERSION << "\n";
      return 0;
    }
    if (cmd == "run") return cmd_run(argc, argv);
    if (cmd == "check") return cmd_check(argc, argv);
    if (cmd == "varieties") return cmd_varieties(argc, argv);
    if (cmd == "section") return sweep_section_main(argc - 1, argv + 1);
    if (cmd == "joints") return sweep_joints_main(argc - 1, argv + 1);
    std::cerr << "sweepvol: unknown command '" << cmd << "'\n" << kUsage;
    return 2;
  } catch (sweep::InputError& e) {
    std::string src = argc > 2 && argv[2][0] != '-' ? argv[2] : "";
    if (e.line() == 0 && !src.empty() && !e.pointer().empty() && e.pointer()[0] == '/') {
      // errors found after parsing (an unreadable file) still point into the spec text
      std::ifstream in(src);
      std::stringstream text;
      text << in.rdbuf();
      auto [line, col] = sweep::locate_pointer(text.str(), e.pointer());
      if (line > 0) e.set_position(line, col);
    }
    std::cerr << "sweepvol: error: " << e.describe(e.line() > 0 ? src : "") << "\n";
    return 2;
  } catch (const sweep::ComputeError& e) {
    std::cerr << "sweepvol: failed: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "sweepvol: internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string cmd = argv[1];
  sweep::cli::WorkerPlan plan;
  if (cmd == "run") plan.output_options = {"-o", "--report"};
  else if (cmd == "varieties") plan.output_options = {"-o", "--faces", "--svg"};
  else if (cmd == "section") plan.output_options = {"-o", "--svg"};
  else return dispatch(argc, argv);
  if (!time_limit_of(argc, argv, plan.time_limit)) return dispatch(argc, argv);
  plan.on_ended = [&cmd](const std::string& reason, const std::vector<sweep::cli::Output>& outputs) {
    return report_ended(cmd, reason, outputs);
  };
  return sweep::cli::run_in_worker(argc, argv, plan, dispatch);
}
