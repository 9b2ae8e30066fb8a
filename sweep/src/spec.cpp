#include "sweep/spec.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include "sweep/error.hpp"

namespace sweep {

namespace {

constexpr double kPi = 3.14159265358979323846;
using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// JSON pointers

std::string escape_token(const std::string& t) {
  std::string r;
  for (char ch : t) {
    if (ch == '~') r += "~0";
    else if (ch == '/') r += "~1";
    else r += ch;
  }
  return r;
}

std::string child(const std::string& ptr, const std::string& key) { return ptr + "/" + escape_token(key); }
std::string child(const std::string& ptr, std::size_t index) { return ptr + "/" + std::to_string(index); }

/// Splits an RFC 6901 pointer into unescaped tokens; false when the syntax is invalid.
bool split_pointer(const std::string& p, std::vector<std::string>& tokens) {
  tokens.clear();
  if (p.empty()) return true;
  if (p[0] != '/') return false;
  std::string cur;
  for (std::size_t i = 1; i <= p.size(); ++i) {
    if (i == p.size() || p[i] == '/') {
      tokens.push_back(cur);
      cur.clear();
    } else if (p[i] == '~') {
      if (i + 1 >= p.size() || (p[i + 1] != '0' && p[i + 1] != '1')) return false;
      cur += p[i + 1] == '0' ? '~' : '/';
      ++i;
    } else {
      cur += p[i];
    }
  }
  return true;
}

std::string join_pointer(const std::vector<std::string>& tokens, std::size_t n) {
  std::string r;
  for (std::size_t i = 0; i < n && i < tokens.size(); ++i) r = child(r, tokens[i]);
  return r;
}

/// A canonical array index: "0" or digits without a leading zero.
bool parse_index(const std::string& t, std::size_t& index) {
  if (t.empty() || t.size() > 18) return false;
  if (t.size() > 1 && t[0] == '0') return false;
  for (char ch : t)
    if (ch < '0' || ch > '9') return false;
  index = static_cast<std::size_t>(std::stoull(t));
  return true;
}

// ---------------------------------------------------------------------------------------------
// Positions in the raw text

/// 1-based line and column (in characters) of byte `offset` of `text`.
std::pair<int, int> line_col(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  int line = 1, col = 1;
  const std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? std::min<std::size_t>(3, offset) : 0;
  for (std::size_t i = start; i < offset; ++i) {
    const unsigned char ch = static_cast<unsigned char>(text[i]);
    if (ch == '\n') {
      ++line;
      col = 1;
    } else if ((ch & 0xC0) != 0x80) {
      ++col;
    }
  }
  return {line, col};
}

void append_utf8(std::string& out, unsigned long cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

/// A tolerant walk over raw JSON text that reports every value with its pointer and byte span
/// (after the value has been read). The visitor returns true to stop the walk.
class Scanner {
 public:
  using Visit = std::function<bool(const std::string& ptr, std::size_t begin, std::size_t end)>;
  Scanner(const std::string& s, Visit visit) : s_(s), visit_(std::move(visit)) {}
  void run() {
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;  // byte order mark
    skip_ws();
    value("", 0);
  }

 private:
  static constexpr int kMaxDepth = 2000;

  void skip_ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }

  bool hex4(unsigned long& v) {
    if (i_ + 4 > s_.size()) return false;
    v = 0;
    for (int k = 0; k < 4; ++k) {
      const char ch = s_[i_ + k];
      v <<= 4;
      if (ch >= '0' && ch <= '9') v |= static_cast<unsigned long>(ch - '0');
      else if (ch >= 'a' && ch <= 'f') v |= static_cast<unsigned long>(ch - 'a' + 10);
      else if (ch >= 'A' && ch <= 'F') v |= static_cast<unsigned long>(ch - 'A' + 10);
      else return false;
    }
    i_ += 4;
    return true;
  }

  /// Reads a string starting at the opening quote, decoding escapes.
  bool read_string(std::string& out) {
    out.clear();
    if (i_ >= s_.size() || s_[i_] != '"') return false;
    ++i_;
    while (i_ < s_.size()) {
      const char ch = s_[i_++];
      if (ch == '"') return true;
      if (ch != '\\') {
        out += ch;
        continue;
      }
      if (i_ >= s_.size()) return false;
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned long cp = 0;
          if (!hex4(cp)) return false;
          if (cp >= 0xD800 && cp < 0xDC00 && i_ + 1 < s_.size() && s_[i_] == '\\' && s_[i_ + 1] == 'u') {
            const std::size_t save = i_;
            i_ += 2;
            unsigned long lo = 0;
            if (hex4(lo) && lo >= 0xDC00 && lo < 0xE000) cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            else i_ = save;
          }
          append_utf8(out, cp);
          break;
        }
        default: return false;
      }
    }
    return false;
  }

  /// Returns false when the walk must end (stopped or malformed).
  bool value(const std::string& ptr, int depth) {
    if (depth > kMaxDepth || i_ >= s_.size()) return false;
    const std::size_t begin = i_;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      skip_ws();
      if (i_ < s_.size() && s_[i_] == '}') {
        ++i_;
      } else {
        for (;;) {
          skip_ws();
          std::string key;
          if (!read_string(key)) return false;
          skip_ws();
          if (i_ >= s_.size() || s_[i_] != ':') return false;
          ++i_;
          skip_ws();
          if (!value(child(ptr, key), depth + 1)) return false;
          skip_ws();
          if (i_ < s_.size() && s_[i_] == ',') {
            ++i_;
            continue;
          }
          if (i_ < s_.size() && s_[i_] == '}') {
            ++i_;
            break;
          }
          return false;
        }
      }
    } else if (c == '[') {
      ++i_;
      skip_ws();
      if (i_ < s_.size() && s_[i_] == ']') {
        ++i_;
      } else {
        for (std::size_t index = 0;; ++index) {
          skip_ws();
          if (!value(child(ptr, index), depth + 1)) return false;
          skip_ws();
          if (i_ < s_.size() && s_[i_] == ',') {
            ++i_;
            continue;
          }
          if (i_ < s_.size() && s_[i_] == ']') {
            ++i_;
            break;
          }
          return false;
        }
      }
    } else if (c == '"') {
      std::string str;
      if (!read_string(str)) return false;
    } else {
      while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '-' ||
                                s_[i_] == '+' || s_[i_] == '.'))
        ++i_;
      if (i_ == begin) return false;
    }
    return !visit_(ptr, begin, i_);
  }

  const std::string& s_;
  Visit visit_;
  std::size_t i_ = 0;
};

/// Pointer and byte offset of the first number in `text` too large for a double, if any.
bool find_overflowing_number(const std::string& text, std::string& ptr, std::size_t& offset,
                             std::string& token) {
  bool found = false;
  Scanner scan(text, [&](const std::string& p, std::size_t b, std::size_t e) {
    const char c = text[b];
    if (c != '-' && !(c >= '0' && c <= '9')) return false;
    const std::string t = text.substr(b, e - b);
    const double v = std::strtod(t.c_str(), nullptr);
    if (std::isfinite(v)) return false;
    ptr = p;
    offset = b;
    token = t;
    found = true;
    return true;
  });
  scan.run();
  return found;
}

// ---------------------------------------------------------------------------------------------
// Formatting for messages

std::string fmt_num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os.precision(15);
  os << v;
  return os.str();
}

std::string describe(const ojson& j) {
  if (j.is_number_float()) return fmt_num(j.get<double>());
  std::string s = j.dump();
  if (s.size() > 80) s = s.substr(0, 77) + "...";
  return s;
}

std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string r;
  for (std::size_t i = 0; i < items.size(); ++i) r += (i ? sep : "") + items[i];
  return r;
}

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

// ---------------------------------------------------------------------------------------------
// Validation context and field helpers

struct Ctx {
  const std::string& text;
  std::string base_dir;
  bool degrees = false;
  std::vector<std::vector<std::string>> overridden;  ///< token lists of --set pointers

  std::pair<int, int> position(const std::string& ptr) const {
    std::vector<std::string> tokens;
    if (!split_pointer(ptr, tokens)) return {0, 0};
    for (const auto& o : overridden)
      if (o.size() <= tokens.size() && std::equal(o.begin(), o.end(), tokens.begin())) return {0, 0};
    for (std::size_t n = tokens.size() + 1; n-- > 0;) {
      const auto loc = locate_pointer(text, join_pointer(tokens, n));
      if (loc.first > 0) return loc;
    }
    return {0, 0};
  }

  [[noreturn]] void fail(const std::string& ptr, const std::string& message) const {
    const auto loc = position(ptr);
    throw InputError(ptr, message, loc.first, loc.second);
  }

  double angle_scale() const { return degrees ? kPi / 180.0 : 1.0; }
};

bool is_comment(const std::string& key) { return !key.empty() && key[0] == '_'; }

const ojson& object(const Ctx& c, const ojson& j, const std::string& ptr) {
  if (!j.is_object()) c.fail(ptr, "must be an object (got " + describe(j) + ")");
  return j;
}

const ojson* optional_field(const ojson& obj, const char* key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const ojson& field(const Ctx& c, const ojson& obj, const std::string& ptr, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) c.fail(child(ptr, key), std::string("missing required field '") + key + "'");
  return *it;
}

void check_fields(const Ctx& c, const ojson& obj, const std::string& ptr, const std::vector<std::string>& allowed,
                  const std::string& owner) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (is_comment(it.key())) continue;
    if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
    c.fail(child(ptr, it.key()), "unknown field '" + it.key() + "'" + (owner.empty() ? "" : " for " + owner) +
                                     " (expected one of: " + join(allowed) + ")");
  }
}

std::string string_value(const Ctx& c, const ojson& j, const std::string& ptr) {
  if (!j.is_string()) c.fail(ptr, "must be a string (got " + describe(j) + ")");
  return j.get<std::string>();
}

double number(const Ctx& c, const ojson& j, const std::string& ptr, const char* expected = "a finite number") {
  if (!j.is_number()) c.fail(ptr, std::string("must be ") + expected + " (got " + describe(j) + ")");
  const double v = j.get<double>();
  if (!std::isfinite(v)) c.fail(ptr, std::string("must be ") + expected + " (got " + fmt_num(v) + ")");
  return v;
}

double positive(const Ctx& c, const ojson& j, const std::string& ptr) {
  const char* expected = "a positive finite number";
  const double v = number(c, j, ptr, expected);
  if (!(v > 0)) c.fail(ptr, std::string("must be ") + expected + " (got " + fmt_num(v) + ")");
  return v;
}

double non_negative(const Ctx& c, const ojson& j, const std::string& ptr) {
  const char* expected = "a non-negative finite number";
  const double v = number(c, j, ptr, expected);
  if (!(v >= 0)) c.fail(ptr, std::string("must be ") + expected + " (got " + fmt_num(v) + ")");
  return v;
}

Eigen::Vector3d vec3(const Ctx& c, const ojson& j, const std::string& ptr) {
  if (!j.is_array() || j.size() != 3) c.fail(ptr, "must be an array of 3 finite numbers (got " + describe(j) + ")");
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v[static_cast<int>(i)] = number(c, j[i], child(ptr, i));
  return v;
}

/// A nonzero vector, returned normalized.
Eigen::Vector3d direction(const Ctx& c, const ojson& j, const std::string& ptr) {
  const Eigen::Vector3d v = vec3(c, j, ptr);
  const double n = v.stableNorm();
  if (!(n > 0) || !std::isfinite(n)) c.fail(ptr, "must be a nonzero vector (got " + describe(j) + ")");
  return v / n;
}

std::pair<double, double> range(const Ctx& c, const ojson& j, const std::string& ptr) {
  if (!j.is_array() || j.size() != 2)
    c.fail(ptr, "must be a range [lo, hi] of 2 finite numbers (got " + describe(j) + ")");
  const double lo = number(c, j[0], child(ptr, std::size_t{0}));
  const double hi = number(c, j[1], child(ptr, std::size_t{1}));
  if (lo == hi) c.fail(ptr, "empty range: lo must be less than hi (got " + describe(j) + ")");
  if (lo > hi) c.fail(ptr, "inverted range: lo must be less than hi (got " + describe(j) + ")");
  return {lo, hi};
}

/// An expression field: a JSON number or a string over `vars`.
Expr expression(const Ctx& c, const ojson& j, const std::string& ptr, const std::vector<std::string>& vars) {
  std::string text;
  if (j.is_number()) {
    number(c, j, ptr, "a finite number or an expression");
    text = j.dump();
  } else if (j.is_string()) {
    text = j.get<std::string>();
  } else {
    c.fail(ptr, "must be an expression (a string or a number) (got " + describe(j) + ")");
  }
  try {
    return Expr::parse(text, vars);
  } catch (const ExprError& e) {
    // The message quotes the expression and gives the 1-based column of the offending character.
    c.fail(ptr, std::string("invalid expression: ") + e.what());
  }
}

/// Samples `f` (one variable) over [lo, hi]; on a non-finite value reports it at `ptr`.
/// `shown` is the expression as written, `display_scale` converts the variable to the spec's units.
void check_finite_over(const Ctx& c, const Expr& f, double lo, double hi, const std::string& ptr,
                       const std::string& var, const std::string& shown, double display_scale = 1.0) {
  const int n = 256;
  for (int k = 0; k <= n; ++k) {
    const double t = lo + (hi - lo) * k / n;
    const double v = f.eval(&t);
    if (!std::isfinite(v))
      c.fail(ptr, "expression \"" + shown + "\" is not finite at " + var + " = " + fmt_num(t * display_scale) +
                      " (got " + fmt_num(v) + ")");
  }
}

/// Range [min f, max f] of a continuous one-variable expression over [lo, hi].
std::pair<double, double> value_interval(const Expr& f, double lo, double hi) {
  const int n = 1024;
  std::vector<double> xs(n + 1), ys(n + 1);
  for (int k = 0; k <= n; ++k) {
    xs[k] = k == n ? hi : lo + (hi - lo) * k / n;
    ys[k] = f.eval(&xs[k]);
  }
  const auto refine = [&](double sign) {
    int best = 0;
    for (int k = 1; k <= n; ++k)
      if (sign * ys[k] < sign * ys[best]) best = k;
    double result = ys[best];
    double a = xs[std::max(best - 1, 0)], b = xs[std::min(best + 1, n)];
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = f.eval(&x1), f2 = f.eval(&x2);
    for (int it = 0; it < 100 && b - a > 0; ++it) {
      if (sign * f1 < sign * result) result = f1;
      if (sign * f2 < sign * result) result = f2;
      if (sign * f1 < sign * f2) {
        b = x2;
        x2 = x1;
        f2 = f1;
        x1 = b - g * (b - a);
        f1 = f.eval(&x1);
      } else {
        a = x1;
        x1 = x2;
        f1 = f2;
        x2 = a + g * (b - a);
        f2 = f.eval(&x2);
      }
    }
    if (std::isfinite(f1) && sign * f1 < sign * result) result = f1;
    if (std::isfinite(f2) && sign * f2 < sign * result) result = f2;
    return result;
  };
  return {refine(1.0), refine(-1.0)};
}

Eigen::Isometry3d placement(const Ctx& c, const ojson& j, const std::string& ptr) {
  object(c, j, ptr);
  check_fields(c, j, ptr, {"translate", "rotate", "matrix"}, "a placement");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (const ojson* m = optional_field(j, "matrix")) {
    const std::string mp = child(ptr, "matrix");
    for (const char* other : {"translate", "rotate"})
      if (optional_field(j, other))
        c.fail(child(ptr, other), "cannot be combined with 'matrix' (give either a matrix or translate/rotate)");
    if (!m->is_array() || m->size() != 4)
      c.fail(mp, "must be a 4x4 matrix given as 4 rows of 4 numbers (got " + describe(*m) + ")");
    Eigen::Matrix4d M;
    for (std::size_t r = 0; r < 4; ++r) {
      const ojson& row = (*m)[r];
      const std::string rp = child(mp, r);
      if (!row.is_array() || row.size() != 4) c.fail(rp, "must be a row of 4 finite numbers (got " + describe(row) + ")");
      for (std::size_t k = 0; k < 4; ++k)
        M(static_cast<int>(r), static_cast<int>(k)) = number(c, row[k], child(rp, k));
    }
    const double tol = 1e-9;
    if (std::abs(M(3, 0)) > tol || std::abs(M(3, 1)) > tol || std::abs(M(3, 2)) > tol || std::abs(M(3, 3) - 1) > tol)
      c.fail(child(mp, std::size_t{3}), "the last row of a placement matrix must be [0, 0, 0, 1] (got " +
                                            describe((*m)[3]) + ")");
    const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
    const double ortho = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    const double det = R.determinant();
    if (ortho > tol || std::abs(det - 1) > tol)
      c.fail(mp, "must be a rigid motion: the upper-left 3x3 block must be a rotation (orthonormal, determinant +1, "
                 "within 1e-9; got orthonormality error " + fmt_num(ortho) + ", determinant " + fmt_num(det) + ")");
    T.linear() = R;
    T.translation() = M.topRightCorner<3, 1>();
    return T;
  }
  if (const ojson* r = optional_field(j, "rotate")) {
    const std::string rp = child(ptr, "rotate");
    object(c, *r, rp);
    check_fields(c, *r, rp, {"axis", "angle"}, "a rotation");
    const Eigen::Vector3d axis = direction(c, field(c, *r, rp, "axis"), child(rp, "axis"));
    const double angle = number(c, field(c, *r, rp, "angle"), child(rp, "angle")) * c.angle_scale();
    T.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  }
  if (const ojson* t = optional_field(j, "translate")) T.translation() = vec3(c, *t, child(ptr, "translate"));
  return T;
}

// ---------------------------------------------------------------------------------------------
// Entities

struct EntityKindInfo {
  const char* name;
  EntityKind kind;
  std::vector<std::string> fields;
};

const std::vector<EntityKindInfo>& entity_kinds() {
  static const std::vector<EntityKindInfo> kinds = {
      {"point", EntityKind::Point, {"at"}},
      {"curve", EntityKind::Curve, {"params", "xyz"}},
      {"surface", EntityKind::Surface, {"params", "xyz"}},
      {"sphere", EntityKind::Sphere, {"center", "radius"}},
      {"box", EntityKind::Box, {"min", "max"}},
      {"cylinder", EntityKind::Cylinder, {"base", "axis", "radius", "height"}},
      {"cone", EntityKind::Cone, {"base", "axis", "radius1", "radius2", "height"}},
      {"torus", EntityKind::Torus, {"center", "axis", "major", "minor"}},
      {"elliptic_cylinder", EntityKind::EllipticCylinder, {"base", "axis", "a", "b", "height", "twist"}},
      {"implicit", EntityKind::Implicit, {"inequalities", "bounds"}},
      {"brep", EntityKind::Brep, {"file"}},
      {"mesh", EntityKind::Mesh, {"file", "scale"}},
      {"tube", EntityKind::Tube, {"spine", "radius"}},
  };
  return kinds;
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  return true;
}

bool is_reserved_name(const std::string& s) {
  static const char* const names[] = {"pi",   "e",    "sin", "cos", "tan", "asin", "acos", "atan",
                                      "atan2", "sqrt", "exp", "log", "abs", "min",  "max"};
  for (const char* n : names)
    if (s == n) return true;
  return false;
}

std::vector<ParamRange> params(const Ctx& c, const ojson& obj, const std::string& ptr, std::size_t count) {
  const std::string pp = child(ptr, "params");
  const ojson& p = object(c, field(c, obj, ptr, "params"), pp);
  std::vector<ParamRange> out;
  for (auto it = p.begin(); it != p.end(); ++it) {
    if (is_comment(it.key())) continue;
    const std::string np = child(pp, it.key());
    if (!is_identifier(it.key())) c.fail(np, "parameter name '" + it.key() + "' is not a valid identifier");
    if (is_reserved_name(it.key()))
      c.fail(np, "parameter name '" + it.key() + "' is reserved (a constant or function of expressions)");
    const auto r = range(c, *it, np);
    out.push_back({it.key(), r.first, r.second});
  }
  if (out.size() != count) {
    std::vector<std::string> names;
    for (const auto& r : out) names.push_back(r.name);
    c.fail(pp, std::string("must name exactly ") + (count == 1 ? "one parameter, e.g. {\"t\": [0, 1]}"
                                                               : "two parameters, e.g. {\"u\": [0, 1], \"v\": [0, 1]}") +
                   " (got " + std::to_string(out.size()) + (names.empty() ? "" : ": " + join(names)) + ")");
  }
  return out;
}

std::string resolve_file(const Ctx& c, const ojson& obj, const std::string& ptr, const std::vector<std::string>& exts,
                         const char* what) {
  const std::string fp = child(ptr, "file");
  const std::string name = string_value(c, field(c, obj, ptr, "file"), fp);
  if (name.empty()) c.fail(fp, "must be a file name (got \"\")");
  fs::path path(name);
  if (path.is_relative() && !c.base_dir.empty()) path = fs::path(c.base_dir) / path;
  path = path.lexically_normal();
  const std::string ext = lower(path.extension().string());
  if (std::find(exts.begin(), exts.end(), ext) == exts.end())
    c.fail(fp, std::string("must be ") + what + " (" + join(exts) + ") (got '" + name + "')");
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!fs::is_regular_file(path, ec) || !in) c.fail(fp, "cannot read file '" + path.string() + "'");
  return path.string();
}

EntitySpec entity(const Ctx& c, const ojson& j, const std::string& ptr) {
  object(c, j, ptr);
  const std::string kp = child(ptr, "kind");
  const std::string kind = string_value(c, field(c, j, ptr, "kind"), kp);
  const EntityKindInfo* info = nullptr;
  std::vector<std::string> names;
  for (const auto& k : entity_kinds()) {
    names.push_back(k.name);
    if (kind == k.name) info = &k;
  }
  if (!info) c.fail(kp, "unknown entity kind '" + kind + "' (expected one of: " + join(names) + ")");
  std::vector<std::string> allowed = {"kind"};
  allowed.insert(allowed.end(), info->fields.begin(), info->fields.end());
  allowed.push_back("placement");
  check_fields(c, j, ptr, allowed, std::string("entity kind '") + info->name + "'");

  EntitySpec e;
  e.kind = info->kind;
  const auto req = [&](const char* key) -> const ojson& { return field(c, j, ptr, key); };
  const auto at = [&](const char* key) { return child(ptr, key); };

  switch (e.kind) {
    case EntityKind::Point:
      e.at = vec3(c, req("at"), at("at"));
      break;
    case EntityKind::Curve:
    case EntityKind::Surface: {
      e.params = params(c, j, ptr, e.kind == EntityKind::Curve ? 1 : 2);
      std::vector<std::string> vars;
      for (const auto& p : e.params) vars.push_back(p.name);
      const ojson& xyz = req("xyz");
      if (!xyz.is_array() || xyz.size() != 3)
        c.fail(at("xyz"), "must be an array of 3 expressions [x, y, z] (got " + describe(xyz) + ")");
      for (std::size_t i = 0; i < 3; ++i) e.xyz[i] = expression(c, xyz[i], child(at("xyz"), i), vars);
      break;
    }
    case EntityKind::Sphere:
      e.center = vec3(c, req("center"), at("center"));
      e.radius = positive(c, req("radius"), at("radius"));
      break;
    case EntityKind::Box: {
      e.min = vec3(c, req("min"), at("min"));
      e.max = vec3(c, req("max"), at("max"));
      for (int i = 0; i < 3; ++i)
        if (!(e.min[i] < e.max[i]))
          c.fail(at("max"), "must be greater than 'min' in every coordinate (got min " + describe(j["min"]) +
                                ", max " + describe(j["max"]) + ")");
      break;
    }
    case EntityKind::Cylinder:
      e.base = vec3(c, req("base"), at("base"));
      e.axis = direction(c, req("axis"), at("axis"));
      e.radius = positive(c, req("radius"), at("radius"));
      e.height = positive(c, req("height"), at("height"));
      break;
    case EntityKind::Cone:
      e.base = vec3(c, req("base"), at("base"));
      e.axis = direction(c, req("axis"), at("axis"));
      e.radius1 = non_negative(c, req("radius1"), at("radius1"));
      e.radius2 = non_negative(c, req("radius2"), at("radius2"));
      if (e.radius1 == 0 && e.radius2 == 0)
        c.fail(at("radius2"), "radius1 and radius2 cannot both be 0 (the cone would be degenerate)");
      e.height = positive(c, req("height"), at("height"));
      break;
    case EntityKind::Torus:
      e.center = vec3(c, req("center"), at("center"));
      e.axis = direction(c, req("axis"), at("axis"));
      e.major = positive(c, req("major"), at("major"));
      e.minor = positive(c, req("minor"), at("minor"));
      if (!(e.minor < e.major))
        c.fail(at("minor"), "must be less than 'major' (got minor " + fmt_num(e.minor) + ", major " +
                                fmt_num(e.major) + ")");
      break;
    case EntityKind::EllipticCylinder:
      e.base = vec3(c, req("base"), at("base"));
      e.axis = direction(c, req("axis"), at("axis"));
      e.a = positive(c, req("a"), at("a"));
      e.b = positive(c, req("b"), at("b"));
      e.height = positive(c, req("height"), at("height"));
      if (const ojson* tw = optional_field(j, "twist")) {
        e.twist = expression(c, *tw, at("twist"), {"u"});
        check_finite_over(c, *e.twist, 0.0, 1.0, at("twist"), "u", e.twist->text());
      }
      break;
    case EntityKind::Implicit: {
      const ojson& ineq = req("inequalities");
      if (!ineq.is_array() || ineq.empty())
        c.fail(at("inequalities"), "must be a non-empty list of expressions in x, y, z (got " + describe(ineq) + ")");
      for (std::size_t i = 0; i < ineq.size(); ++i)
        e.inequalities.push_back(expression(c, ineq[i], child(at("inequalities"), i), {"x", "y", "z"}));
      const std::string bp = at("bounds");
      const ojson& b = object(c, req("bounds"), bp);
      check_fields(c, b, bp, {"min", "max"}, "bounds");
      e.min = vec3(c, field(c, b, bp, "min"), child(bp, "min"));
      e.max = vec3(c, field(c, b, bp, "max"), child(bp, "max"));
      for (int i = 0; i < 3; ++i)
        if (!(e.min[i] < e.max[i]))
          c.fail(child(bp, "max"), "must be greater than 'min' in every coordinate (got min " + describe(b["min"]) +
                                       ", max " + describe(b["max"]) + ")");
      break;
    }
    case EntityKind::Brep:
      e.file = resolve_file(c, j, ptr, {".step", ".stp", ".brep"}, "a STEP or BREP file");
      break;
    case EntityKind::Mesh:
      e.file = resolve_file(c, j, ptr, {".stl", ".off"}, "an STL or OFF file");
      if (const ojson* s = optional_field(j, "scale")) e.scale = positive(c, *s, at("scale"));
      break;
    case EntityKind::Tube: {
      const std::string sp = at("spine");
      const ojson& s = object(c, req("spine"), sp);
      const std::string skp = child(sp, "kind");
      const std::string skind = string_value(c, field(c, s, sp, "kind"), skp);
      if (skind != "curve") c.fail(skp, "the spine of a tube must be a curve (got '" + skind + "')");
      e.spine = std::make_shared<EntitySpec>(entity(c, s, sp));
      const ParamRange& p = e.spine->params.at(0);
      e.tube_radius = expression(c, req("radius"), at("radius"), {p.name});
      const int n = 256;
      for (int k = 0; k <= n; ++k) {
        const double t = p.lo + (p.hi - p.lo) * k / n;
        const double r = e.tube_radius->eval(&t);
        if (!std::isfinite(r) || !(r > 0))
          c.fail(at("radius"), "must be positive over the spine's range (got " + fmt_num(r) + " at " + p.name +
                                   " = " + fmt_num(t) + ")");
      }
      break;
    }
  }
  if (const ojson* pl = optional_field(j, "placement")) e.placement = placement(c, *pl, at("placement"));
  return e;
}

// ---------------------------------------------------------------------------------------------
// Motions

JointType joint_type(const Ctx& c, const ojson& joint, const std::string& ptr) {
  const std::string tp = child(ptr, "type");
  const std::string t = string_value(c, field(c, joint, ptr, "type"), tp);
  if (t == "revolute") return JointType::Revolute;
  if (t == "prismatic") return JointType::Prismatic;
  if (t == "helical") return JointType::Helical;
  c.fail(tp, "unknown joint type '" + t + "' (expected one of: revolute, prismatic, helical)");
}

const ojson& joint_list(const Ctx& c, const ojson& m, const std::string& ptr) {
  const std::string jp = child(ptr, "joints");
  const ojson& joints = field(c, m, ptr, "joints");
  if (!joints.is_array() || joints.empty())
    c.fail(jp, "must be a non-empty list of joints (got " + describe(joints) + ")");
  return joints;
}

/// Helical pitch (length per turn): required and nonzero for helical joints, absent otherwise.
double joint_pitch(const Ctx& c, const ojson& joint, const std::string& ptr, JointType type) {
  const std::string pp = child(ptr, "pitch");
  if (type != JointType::Helical) {
    if (optional_field(joint, "pitch"))
      c.fail(pp, std::string("'pitch' is only allowed for helical joints (this joint is ") + to_string(type) + ")");
    return 0.0;
  }
  const double p = number(c, field(c, joint, ptr, "pitch"), pp, "a nonzero finite number (length per turn)");
  if (p == 0)
    c.fail(pp, "must be a nonzero finite number (length per turn) (got 0); use a revolute joint for pitch 0");
  return p;
}

void parse_axes(const Ctx& c, const ojson& m, const std::string& ptr, MotionSpec& out) {
  check_fields(c, m, ptr, {"kind", "joints"}, "an 'axes' motion");
  const ojson& joints = joint_list(c, m, ptr);
  const std::string jp = child(ptr, "joints");
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string p = child(jp, i);
    const ojson& j = object(c, joints[i], p);
    check_fields(c, j, p, {"type", "point", "direction", "pitch", "range"}, "a joint");
    ScrewJoint s;
    s.type = joint_type(c, j, p);
    if (s.type == JointType::Prismatic) {
      if (const ojson* pt = optional_field(j, "point")) s.point = vec3(c, *pt, child(p, "point"));
    } else {
      s.point = vec3(c, field(c, j, p, "point"), child(p, "point"));
    }
    s.direction = direction(c, field(c, j, p, "direction"), child(p, "direction"));
    s.pitch = joint_pitch(c, j, p, s.type) / (2 * kPi);
    const auto r = range(c, field(c, j, p, "range"), child(p, "range"));
    const double scale = s.is_rotation() ? c.angle_scale() : 1.0;
    s.lo = r.first * scale;
    s.hi = r.second * scale;
    out.motion.joints.push_back(s);
  }
}

void parse_screw(const Ctx& c, const ojson& m, const std::string& ptr, MotionSpec& out) {
  check_fields(c, m, ptr, {"kind", "point", "direction", "pitch", "range"}, "a 'screw' motion");
  ScrewJoint s;
  s.point = vec3(c, field(c, m, ptr, "point"), child(ptr, "point"));
  s.direction = direction(c, field(c, m, ptr, "direction"), child(ptr, "direction"));
  const double pitch = number(c, field(c, m, ptr, "pitch"), child(ptr, "pitch"), "a finite number (length per turn)");
  s.type = pitch == 0 ? JointType::Revolute : JointType::Helical;
  s.pitch = pitch / (2 * kPi);
  const auto r = range(c, field(c, m, ptr, "range"), child(ptr, "range"));
  s.lo = r.first * c.angle_scale();
  s.hi = r.second * c.angle_scale();
  out.motion.joints.push_back(s);
}

/// Lexically replaces the identifier `var` in expression text by `replacement`.
std::string substitute(const std::string& text, const std::string& var, const std::string& replacement) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char ch = static_cast<unsigned char>(text[i]);
    if (std::isdigit(ch) || (ch == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
      const std::size_t b = i;
      while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t k = i + 1;
        if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
        if (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) {
          i = k;
          while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
        }
      }
      out += text.substr(b, i - b);
    } else if (std::isalpha(ch) || ch == '_') {
      const std::size_t b = i;
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
      const std::string id = text.substr(b, i - b);
      out += id == var ? replacement : id;
    } else {
      out += text[i++];
    }
  }
  return out;
}

/// `e` (an expression in q) rewritten to take q in radians and return radians, when the spec is in
/// degrees. `q_is_angle` says whether q itself is in degrees (revolute/helical theta).
Expr to_radians(const Ctx& c, const Expr& e, bool q_is_angle) {
  if (!c.degrees) return e;
  const std::string body = q_is_angle ? substitute(e.text(), "q", "(q*180/pi)") : e.text();
  try {
    return Expr::parse("(" + body + ")*pi/180", {"q"});
  } catch (const ExprError& err) {
    throw InternalError("cannot convert expression \"" + e.text() + "\" to radians: " + err.what());
  }
}

Eigen::Isometry3d dh_transform(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(0, 0, d));
  T.translate(Eigen::Vector3d(a, 0, 0));
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  return T;
}

void parse_dh(const Ctx& c, const ojson& m, const std::string& ptr, MotionSpec& out) {
  check_fields(c, m, ptr, {"kind", "joints", "base"}, "a 'dh' motion");
  const ojson& joints = joint_list(c, m, ptr);
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  if (const ojson* b = optional_field(m, "base")) frame = placement(c, *b, child(ptr, "base"));
  const std::string jp = child(ptr, "joints");
  const double zero = 0.0;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string p = child(jp, i);
    const ojson& j = object(c, joints[i], p);
    check_fields(c, j, p, {"type", "theta", "d", "a", "alpha", "range", "pitch"}, "a DH joint");
    DhRow row;
    row.type = joint_type(c, j, p);
    const bool rotation = row.type != JointType::Prismatic;
    const char* var_field = rotation ? "theta" : "d";
    const char* names[4] = {"theta", "d", "a", "alpha"};
    Expr raw[4];
    for (int k = 0; k < 4; ++k) {
      const std::string fp = child(p, names[k]);
      raw[k] = expression(c, field(c, j, p, names[k]), fp, {"q"});
      const bool is_var = std::string(names[k]) == var_field;
      if (is_var && !raw[k].uses(0))
        c.fail(fp, std::string("must be an expression in q: the joint variable of a ") + to_string(row.type) +
                       " joint is " + var_field + " (got " + describe(j[names[k]]) + ")");
      if (!is_var && raw[k].uses(0))
        c.fail(fp, std::string("must be a constant: only ") + var_field + " may depend on q for a " +
                       to_string(row.type) + " joint (got " + describe(j[names[k]]) + ")");
    }
    row.pitch = joint_pitch(c, j, p, row.type);
    const auto r = range(c, field(c, j, p, "range"), child(p, "range"));
    const double qscale = rotation ? c.angle_scale() : 1.0;
    row.lo = r.first * qscale;
    row.hi = r.second * qscale;
    row.theta = to_radians(c, raw[0], rotation);
    row.d = raw[1];
    row.a = raw[2];
    row.alpha = to_radians(c, raw[3], false);
    const Expr* fields[4] = {&row.theta, &row.d, &row.a, &row.alpha};

    // Constant parts (the joint variable is 0 in the zero configuration).
    double value[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      if (std::string(names[k]) == var_field) continue;
      value[k] = fields[k]->eval(&zero);
      if (!std::isfinite(value[k]))
        c.fail(child(p, names[k]), "must evaluate to a finite number (got " + fmt_num(value[k]) + ")");
    }
    const Expr& var = rotation ? row.theta : row.d;
    check_finite_over(c, var, row.lo, row.hi, child(p, var_field), "q", raw[rotation ? 0 : 1].text(), 1.0 / qscale);
    const auto interval = value_interval(var, row.lo, row.hi);

    ScrewJoint s;
    s.type = row.type;
    s.point = frame.translation();
    s.direction = frame.linear().col(2).normalized();
    s.pitch = row.type == JointType::Helical ? row.pitch / (2 * kPi) : 0.0;
    s.lo = interval.first;
    s.hi = interval.second;
    out.motion.joints.push_back(s);
    out.dh.push_back(row);
    frame = frame * dh_transform(value[0], value[1], value[2], value[3]);
  }
  out.motion.home = frame;
}

/// An angle expression in t, in radians (the spec's angle unit applies to the value).
Expr angle_in_t(const Ctx& c, const ojson& j, const std::string& ptr) {
  const Expr e = expression(c, j, ptr, {"t"});
  if (!c.degrees) return e;
  try {
    return Expr::parse("(" + e.text() + ")*pi/180", {"t"});
  } catch (const ExprError& err) {
    throw InternalError("cannot convert expression \"" + e.text() + "\" to radians: " + err.what());
  }
}

/// One rotation of a path, {axis: 3 numbers or expressions in t, angle: expression in t}, checked
/// finite over [lo, hi] with an axis that never vanishes.
PathRotation path_rotation(const Ctx& c, const ojson& r, const std::string& rp, double lo, double hi) {
  object(c, r, rp);
  check_fields(c, r, rp, {"axis", "angle"}, "a rotation of a path");
  const std::string ap = child(rp, "axis");
  const ojson& a = field(c, r, rp, "axis");
  if (!a.is_array() || a.size() != 3)
    c.fail(ap, "must be an array of 3 numbers or expressions in t (got " + describe(a) + ")");
  PathRotation out;
  for (std::size_t k = 0; k < 3; ++k) {
    out.axis[k] = expression(c, a[k], child(ap, k), {"t"});
    check_finite_over(c, out.axis[k], lo, hi, child(ap, k), "t", out.axis[k].text());
  }
  const ojson& angle = field(c, r, rp, "angle");
  out.angle = angle_in_t(c, angle, child(rp, "angle"));
  check_finite_over(c, out.angle, lo, hi, child(rp, "angle"), "t", expression(c, angle, child(rp, "angle"), {"t"}).text());
  const int n = 1024;
  for (int s = 0; s <= n; ++s) {
    const double t = lo + (hi - lo) * s / n;
    const Eigen::Vector3d v(out.axis[0].eval(&t), out.axis[1].eval(&t), out.axis[2].eval(&t));
    if (!(v.norm() > 1e-12)) c.fail(ap, "the rotation axis vanishes at t = " + fmt_num(t) + " (got " + describe(a) + ")");
  }
  return out;
}

void parse_path(const Ctx& c, const ojson& m, const std::string& ptr, MotionSpec& out) {
  check_fields(c, m, ptr, {"kind", "t", "translate", "rotate"}, "a 'path' motion");
  const auto r = range(c, field(c, m, ptr, "t"), child(ptr, "t"));
  const std::string tp = child(ptr, "translate");
  const ojson& tr = field(c, m, ptr, "translate");
  if (!tr.is_array() || tr.size() != 3)
    c.fail(tp, "must be an array of 3 expressions in t (got " + describe(tr) + ")");
  Expr translate[3];
  for (std::size_t k = 0; k < 3; ++k) {
    translate[k] = expression(c, tr[k], child(tp, k), {"t"});
    check_finite_over(c, translate[k], r.first, r.second, child(tp, k), "t", translate[k].text());
  }
  std::vector<PathRotation> rotations;
  if (const ojson* rot = optional_field(m, "rotate")) {
    const std::string rp = child(ptr, "rotate");
    if (rot->is_array()) {
      if (rot->empty()) c.fail(rp, "must be a rotation or a non-empty list of rotations (got [])");
      for (std::size_t k = 0; k < rot->size(); ++k)
        rotations.push_back(path_rotation(c, (*rot)[k], child(rp, k), r.first, r.second));
    } else {
      rotations.push_back(path_rotation(c, *rot, rp, r.first, r.second));
    }
  }
  out.stage = std::make_shared<PathMotion>(r.first, r.second, translate, std::move(rotations), ptr);
}

void parse_keyframes(const Ctx& c, const ojson& m, const std::string& ptr, MotionSpec& out) {
  check_fields(c, m, ptr, {"kind", "poses", "interpolation"}, "a 'keyframes' motion");
  auto interpolation = KeyframeMotion::Interpolation::Screw;
  if (const ojson* ip = optional_field(m, "interpolation")) {
    const std::string how = string_value(c, *ip, child(ptr, "interpolation"));
    if (how == "linear")
      interpolation = KeyframeMotion::Interpolation::Linear;
    else if (how != "screw")
      c.fail(child(ptr, "interpolation"), "must be \"screw\" or \"linear\" (got \"" + how + "\")");
  }
  const std::string pp = child(ptr, "poses");
  const ojson& poses = field(c, m, ptr, "poses");
  if (!poses.is_array() || poses.size() < 2)
    c.fail(pp, "must be a list of at least two poses {t, translate, rotate} or {t, matrix} (got " + describe(poses) + ")");
  std::vector<double> times;
  std::vector<Eigen::Isometry3d> placements;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const std::string kp = child(pp, k);
    object(c, poses[k], kp);
    const double t = number(c, field(c, poses[k], kp, "t"), child(kp, "t"));
    if (!times.empty() && !(t > times.back()))
      c.fail(child(kp, "t"), "the times must increase (got " + fmt_num(t) + " after " + fmt_num(times.back()) + ")");
    ojson pose = poses[k];
    pose.erase("t");
    times.push_back(t);
    placements.push_back(placement(c, pose, kp));
  }
  out.stage = std::make_shared<KeyframeMotion>(std::move(times), std::move(placements), interpolation, ptr);
}

MotionSpec motion(const Ctx& c, const ojson& j, const std::string& ptr) {
  object(c, j, ptr);
  const std::string kp = child(ptr, "kind");
  const std::string kind = string_value(c, field(c, j, ptr, "kind"), kp);
  MotionSpec m;
  if (kind == "dh") {
    m.kind = MotionKind::Dh;
    parse_dh(c, j, ptr, m);
  } else if (kind == "axes") {
    m.kind = MotionKind::Axes;
    parse_axes(c, j, ptr, m);
  } else if (kind == "screw") {
    m.kind = MotionKind::Screw;
    parse_screw(c, j, ptr, m);
  } else if (kind == "path") {
    m.kind = MotionKind::Path;
    parse_path(c, j, ptr, m);
  } else if (kind == "keyframes") {
    m.kind = MotionKind::Keyframes;
    parse_keyframes(c, j, ptr, m);
  } else if (kind == "toolpath" || kind == "polyscrew") {
    c.fail(kp, "motion kind '" + kind + "' is not supported yet");
  } else {
    c.fail(kp, "unknown motion kind '" + kind +
                   "' (expected one of: dh, axes, screw, path, keyframes, toolpath, polyscrew)");
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
// Overrides

/// Applies one "--set /pointer=value" and returns the pointer's tokens.
std::vector<std::string> apply_override(ojson& doc, const std::string& arg) {
  const std::size_t eq = arg.find('=');
  if (eq == std::string::npos)
    throw InputError("", "--set " + arg + ": expected /json/pointer=value");
  const std::string ptr = arg.substr(0, eq), text = arg.substr(eq + 1);
  std::vector<std::string> tokens;
  if (ptr.empty() || !split_pointer(ptr, tokens))
    throw InputError(ptr, "--set " + arg + ": '" + ptr + "' is not a JSON pointer (e.g. /entity/radius)");
  ojson value;
  try {
    value = ojson::parse(text);
  } catch (const ojson::out_of_range&) {
    throw InputError(ptr, "--set " + arg + ": the value must be a finite number (got " + text + ")");
  } catch (const ojson::exception&) {
    value = text;
  }
  ojson* node = &doc;
  for (std::size_t k = 0; k + 1 < tokens.size(); ++k) {
    std::size_t index = 0;
    if (node->is_object() && node->contains(tokens[k])) {
      node = &(*node)[tokens[k]];
    } else if (node->is_array() && parse_index(tokens[k], index) && index < node->size()) {
      node = &(*node)[index];
    } else {
      throw InputError(ptr, "--set " + ptr + ": no such field (" + join_pointer(tokens, k + 1) + " does not exist)");
    }
  }
  const std::string& last = tokens.back();
  if (node->is_object()) {
    (*node)[last] = std::move(value);
  } else if (node->is_array()) {
    std::size_t index = 0;
    if (last == "-" || (parse_index(last, index) && index == node->size())) {
      node->push_back(std::move(value));
    } else if (parse_index(last, index) && index < node->size()) {
      (*node)[index] = std::move(value);
    } else {
      throw InputError(ptr, "--set " + ptr + ": no such element (the array " + join_pointer(tokens, tokens.size() - 1) +
                                " has " + std::to_string(node->size()) + " elements)");
    }
  } else {
    throw InputError(ptr, "--set " + ptr + ": no such field (" + join_pointer(tokens, tokens.size() - 1) +
                              " is not an object or array)");
  }
  return tokens;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

const char* to_string(EntityKind k) {
  for (const auto& info : entity_kinds())
    if (info.kind == k) return info.name;
  return "?";
}

const char* to_string(MotionKind k) {
  switch (k) {
    case MotionKind::Dh: return "dh";
    case MotionKind::Axes: return "axes";
    case MotionKind::Screw: return "screw";
    case MotionKind::Path: return "path";
    case MotionKind::Keyframes: return "keyframes";
    case MotionKind::Toolpath: return "toolpath";
    case MotionKind::PolyScrew: return "polyscrew";
  }
  return "?";
}

Eigen::Matrix3d EntitySpec::elliptic_frame() const {
  const Eigen::Vector3d z = axis.normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - z * z.x();
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitY() - z * z.y();
  x.normalize();
  Eigen::Matrix3d F;
  F << x, z.cross(x), z;
  return F;
}

int EntitySpec::dimension() const {
  switch (kind) {
    case EntityKind::Point: return 0;
    case EntityKind::Curve: return 1;
    case EntityKind::Surface: return 2;
    default: return 3;
  }
}

std::pair<int, int> locate_pointer(const std::string& text, const std::string& pointer) {
  std::pair<int, int> result{0, 0};
  Scanner scan(text, [&](const std::string& p, std::size_t begin, std::size_t) {
    if (p != pointer) return false;
    result = line_col(text, begin);
    return true;
  });
  scan.run();
  return result;
}

Spec parse_spec(const std::string& text, const std::string& base_dir, const std::vector<std::string>& overrides) {
  ojson doc;
  try {
    doc = ojson::parse(text);
  } catch (const ojson::parse_error& e) {
    const auto loc = line_col(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string msg = e.what();
    const std::size_t colon = msg.find(": ");
    if (colon != std::string::npos) msg = msg.substr(colon + 2);
    throw InputError("", "malformed JSON: " + msg, loc.first, loc.second);
  } catch (const ojson::exception& e) {
    std::string ptr;
    std::size_t offset = 0;
    std::string token;
    if (find_overflowing_number(text, ptr, offset, token)) {
      const auto loc = line_col(text, offset);
      throw InputError(ptr, "must be a finite number (got " + token + ", which is out of range)", loc.first,
                       loc.second);
    }
    throw InputError("", std::string("malformed JSON: ") + e.what());
  }

  Ctx c{text, base_dir, false, {}};
  for (const auto& o : overrides) c.overridden.push_back(apply_override(doc, o));

  object(c, doc, "");
  Spec spec;
  {
    const ojson& v = field(c, doc, "", "sweep");
    if (!v.is_number()) c.fail("/sweep", "must be the format version 1 (got " + describe(v) + ")");
    if (v.get<double>() != 1.0)
      c.fail("/sweep", "unsupported spec version " + describe(v) + " (this program reads version 1)");
    spec.version = 1;
  }
  if (const ojson* a = optional_field(doc, "angles")) {
    const std::string s = a->is_string() ? a->get<std::string>() : std::string();
    if (s != "rad" && s != "deg") c.fail("/angles", "must be \"rad\" or \"deg\" (got " + describe(*a) + ")");
    c.degrees = s == "deg";
  }
  check_fields(c, doc, "", {"sweep", "name", "angles", "entity", "motion", "tolerance"}, "");
  if (const ojson* n = optional_field(doc, "name")) spec.name = string_value(c, *n, "/name");
  if (const ojson* t = optional_field(doc, "tolerance")) spec.tolerance = positive(c, *t, "/tolerance");
  spec.degrees = c.degrees;
  spec.entity = entity(c, field(c, doc, "", "entity"), "/entity");
  spec.motion = motion(c, field(c, doc, "", "motion"), "/motion");
  spec.json = nlohmann::json::parse(doc.dump());
  return spec;
}

Spec load_spec(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path, ec)) throw InputError("", "cannot read spec file '" + path + "'");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("", "cannot read spec file '" + path + "'");
  std::string dir = fs::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  return parse_spec(text, dir, overrides);
}

}  // namespace sweep
