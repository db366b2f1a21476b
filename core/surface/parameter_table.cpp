#include "core/surface/parameter_table.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynamesh {

std::string unknown_parameter_message(const std::string& scene, const std::string& name,
                                      const std::vector<SurfaceParameter>& valid) {
  std::ostringstream out;
  out << scene << ": no parameter '" << name << "'; ";
  if (valid.empty()) {
    out << "this scene has no adjustable parameters";
    return out.str();
  }
  out << "valid parameters are ";
  for (std::size_t i = 0; i < valid.size(); ++i) out << (i ? ", " : "") << valid[i].name;
  return out.str();
}

void check_parameter_value(const std::string& scene, const SurfaceParameter& p, double value) {
  if (std::isfinite(value) && value >= p.min && value <= p.max) return;
  std::ostringstream out;
  out << scene << ": " << p.name << " = " << value << " is outside its range [" << p.min << ", "
      << p.max << "] (" << p.description << ")";
  throw std::invalid_argument(out.str());
}

}  // namespace dynamesh
