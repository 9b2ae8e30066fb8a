// A point as messages write it (point_text.hpp).
#include "sweep/point_text.hpp"

#include <sstream>

namespace sweep {

std::string point_text(const Eigen::Vector3d& p, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

}  // namespace sweep
