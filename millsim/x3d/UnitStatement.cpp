#include "millsim/x3d/UnitStatement.h"

#include <cmath>
#include <cstdlib>

namespace millsim {

namespace {
bool parseFactor(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  return end && *end == '\0' && std::isfinite(out) && out > 0;
}
}  // namespace

std::optional<std::string> invalidUnit(const UnitStatement& u) {
  if (u.category != "angle" && u.category != "force" && u.category != "length" && u.category != "mass")
    return "unit category '" + u.category + "' is not one of angle, force, length, mass";
  if (u.name.empty()) return std::string("a <unit> statement needs a name (e.g. name='millimetre')");
  double f;
  if (!parseFactor(u.conversionFactor, f))
    return "unit conversionFactor '" + u.conversionFactor + "' is not a positive number (the size of one " +
           u.name + " in SI units)";
  return std::nullopt;
}

double unitFactor(const UnitStatement& u) {
  double f = 1;
  parseFactor(u.conversionFactor, f);
  return f;
}

}  // namespace millsim
