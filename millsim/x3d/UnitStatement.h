#pragma once
// X3D 4.0 <unit category=... name=... conversionFactor=.../> statements. A
// unit changes the meaning of every length, angle, mass or force value in the
// file, so one that is not the SI unit must never be ignored silently.
#include <optional>
#include <string>

namespace millsim {

struct UnitStatement {
  std::string category;  // angle, force, length or mass
  std::string name;
  std::string conversionFactor;  // as written
};

// What is wrong with `u` (an unknown category, a missing name, a factor that
// is not a positive number), or nullopt when it is a valid statement.
std::optional<std::string> invalidUnit(const UnitStatement& u);
// The factor as a number; only valid after invalidUnit returned nullopt.
double unitFactor(const UnitStatement& u);

}  // namespace millsim
