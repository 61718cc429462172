#pragma once
// Quantity: what a numeric field measures, as powers of the four base
// quantities an X3D 4.0 <unit> statement may redefine (length, angle, mass,
// force; time is always seconds). A field stores SI values; a scene written in
// other units (e.g. millimetres) has its values converted once, when the text
// is read, by UnitScale::factor. A Quantity is declared with the field's Range:
//
//   Range::openClosed(0, 0.01).in(quantity::length)           // m
//   Range::positive().in(quantity::linearStiffness)           // N/m
//
// SFRotation and MFRotation angles are angles by their type, never tagged.
#include <cmath>
#include <cstdint>
#include <string>

namespace millsim {

struct Quantity {
  std::int8_t length = 0;
  std::int8_t angle = 0;
  std::int8_t mass = 0;
  std::int8_t force = 0;
  // Seconds: named in the unit a field prints with (N·s/m), never converted
  // (X3D has no time unit; time is always seconds).
  std::int8_t time = 0;
  // Only the last number of each value carries the quantity (a plane equation's d).
  bool lastOnly = false;
  // Only the translation of a 4×4 matrix (its 4th column) carries the quantity
  // (MatrixTransform.matrix: rotation and scale are dimensionless).
  bool translationOnly = false;
  // A value of exactly -1 means "none" (X3D's bboxSize, Viewpoint's nearDistance)
  // and stays -1 in any unit.
  bool minusOneIsNone = false;

  bool dimensionless() const { return length == 0 && angle == 0 && mass == 0 && force == 0 && time == 0; }
  bool operator==(const Quantity&) const = default;
};

// The quantities fields declare (Range::in).
namespace quantity {
inline constexpr Quantity length{.length = 1};
inline constexpr Quantity angle{.angle = 1};
inline constexpr Quantity mass{.mass = 1};
inline constexpr Quantity force{.force = 1};
inline constexpr Quantity torque{.length = 1, .force = 1};  // N·m
inline constexpr Quantity linearStiffness{.length = -1, .force = 1};                         // N/m
inline constexpr Quantity linearDamping{.length = -1, .force = 1, .time = 1};               // N·s/m
inline constexpr Quantity angularStiffness{.length = 1, .angle = -1, .force = 1};           // N·m/rad
inline constexpr Quantity angularDamping{.length = 1, .angle = -1, .force = 1, .time = 1};  // N·m·s/rad
inline constexpr Quantity velocity{.length = 1, .time = -1};                                // m/s
inline constexpr Quantity angularVelocity{.angle = 1, .time = -1};                          // rad/s
inline constexpr Quantity inertia{.length = 2, .mass = 1};  // kg·m²
// A length where -1 means "none".
inline constexpr Quantity lengthOrNone{.length = 1, .minusOneIsNone = true};
}  // namespace quantity

// The SI unit of `q`, as fields' documentation writes it: "N·m", "N·s/m",
// "kg·m²", "rad/s"; empty when dimensionless.
std::string siUnit(const Quantity& q);

// The size of one unit of each base quantity in SI units, as a scene's <unit>
// statements set it (1 for each: the scene is written in SI).
struct UnitScale {
  double length = 1, angle = 1, mass = 1, force = 1;

  bool si() const { return length == 1 && angle == 1 && mass == 1 && force == 1; }
  // The factor that turns a value of quantity `q` written in these units into SI.
  double factor(const Quantity& q) const {
    return std::pow(length, q.length) * std::pow(angle, q.angle) * std::pow(mass, q.mass) * std::pow(force, q.force);
  }
};

}  // namespace millsim
