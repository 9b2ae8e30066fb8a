// sweepvol section: cross-sections z = const of the swept solid, as JSON and as an SVG drawing;
// and the SVG drawing of `sweepvol varieties --svg`.
#include "section_cmd.hpp"
#include "stop_request.hpp"
#include "worker.hpp"
#include "args.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include "occt_bridge/drawing.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"

namespace {

struct SectionArgs {
  std::string spec, svg, out;
  std::vector<std::string> sets;
  bool has_z = false;
  std::string z;
  double time_limit = sweep::cli::kDefaultTimeLimit;  ///< seconds
};

/// "1,5,10": finite numbers separated by commas.
std::vector<double> parse_heights(const std::string& text) {
  std::vector<double> z;
  if (text.find_first_not_of(" \t") == std::string::npos)
    throw sweep::InputError("--z", "--z needs at least one height (e.g. --z 0.5,1)");
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    char* end = nullptr;
    const double x = item.empty() ? 0.0 : std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
      throw sweep::InputError("--z", "--z: '" + item + "' is not a finite number (expected heights like 0.5,1,2)");
    z.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return z;
}

SectionArgs parse_section_args(int argc, char** argv) {
  SectionArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* name) { return sweep::cli::option_value(argc, argv, i, name); };
    if (s == "--set") a.sets.push_back(value("--set"));
    else if (s.rfind("--set=", 0) == 0) a.sets.push_back(s.substr(6));
    else if (s == "--z") a.z = value("--z"), a.has_z = true;
    else if (s.rfind("--z=", 0) == 0) a.z = s.substr(4), a.has_z = true;
    else if (s == "--svg") a.svg = value("--svg");
    else if (s.rfind("--svg=", 0) == 0) a.svg = s.substr(6);
    else if (s == "-o") a.out = value("-o");
    else if (s == "--time-limit") a.time_limit = sweep::cli::parse_time_limit(value("--time-limit"));
    else if (!s.empty() && s[0] == '-') throw sweep::InputError(s, "unknown option '" + s + "'");
    else if (a.spec.empty()) a.spec = s;
    else throw sweep::InputError(s, "unexpected argument '" + s + "'");
  }
  if (a.spec.empty()) throw sweep::InputError("SPEC", "missing spec file argument");
  if (!a.has_z) throw sweep::InputError("--z", "missing --z Z1,Z2,... (the heights of the cutting planes)");
  return a;
}

}  // namespace

void sweep_check_svg_path(const std::string& path, const char* option) {
  const std::string base = path.substr(path.find_last_of('/') + 1);  // npos + 1 == 0
  std::string ext = base.size() > 4 ? base.substr(base.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".svg")
    throw sweep::InputError(option, std::string(option) + ": the drawing must be an .svg file (got '" + path + "')");
}

void sweep_write_varieties_svg(const std::string& path, const sweep::Spec& spec, const sweep::occt::Shape& faces,
                               const std::vector<int>& ids, const std::vector<sweep::occt::Variety>& varieties) {
  const std::string title = (spec.name.empty() ? std::string("sweep") : spec.name) + ": boundary varieties";
  sweep::occt::write_text_file(path, sweep::occt::varieties_svg(faces, ids, varieties, title));
}

int sweep_section_main(int argc, char** argv) {
  const SectionArgs a = parse_section_args(argc, argv);
  const std::vector<double> heights = parse_heights(a.z);
  if (!a.svg.empty()) sweep_check_svg_path(a.svg, "--svg");
  if (!a.out.empty() && a.out == a.svg) throw sweep::InputError("-o", "-o and --svg name the same file");
  const sweep::Spec spec = sweep::load_spec(a.spec, a.sets);
  sweep::occt::RunOptions opt;
  if (sweep::cli::stderr_is_terminal()) opt.progress = [](const std::string& line) { std::cerr << "sweepvol: " << line << "\n"; };
  opt.stop = sweep::cli::stop_request(a.time_limit);
  sweep::occt::RunResult r = sweep::occt::run_sweep(spec, opt);

  nlohmann::json out;
  out["sweep_section"] = 1;
  out["sections"] = nlohmann::json::array();
  std::vector<sweep::occt::Section> secs;
  if (r.report.ok() && r.report.dimension != 3) {
    r.report.status = "failed";
    r.report.message = "sections need a solid; the swept set has dimension " + std::to_string(r.report.dimension);
  }
  if (r.report.ok()) {
    try {
      secs = sweep::occt::sections(*r.shape, heights);
    } catch (const sweep::ComputeError& e) {
      r.report.status = "failed";
      r.report.message = e.what();
    }
  }
  for (const auto& s : secs) out["sections"].push_back(s.to_json());
  const nlohmann::json report = r.report.to_json();
  out["volume"] = report["volume"];
  out["status"] = r.report.status;
  if (!r.report.message.empty()) out["message"] = r.report.message;
  const std::string text = out.dump(2) + "\n";
  if (r.report.ok()) {
    if (!a.svg.empty()) {
      const std::string title = (spec.name.empty() ? a.spec : spec.name) + ": sections z = const";
      sweep::occt::write_text_file(a.svg, sweep::occt::sections_svg(secs, title));
    }
    if (!a.out.empty()) sweep::occt::write_text_file(a.out, text);
  }
  std::cout << text;
  if (!r.report.ok()) {
    std::cerr << "sweepvol: failed: " << r.report.message << "\n";
    return 3;
  }
  return 0;
}
