// Every numeric field a scene can set, on every registered node type, declares
// a finite range; its default lies inside; a value just outside either bound,
// NaN and infinity are refused. So `check`, `run` and docs/nodes.md agree on
// what a field takes, and no unbounded number (a billion surface points, a
// 10 m burr) reaches an algorithm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "millsim/core/Field.h"
#include "millsim/core/Node.h"
#include "millsim/core/NodeRegistry.h"

using namespace millsim;

namespace {

// Numbers per value (per element for MF types); 0 for fields that take no numbers.
int components(FieldType t) {
  switch (t) {
    case FieldType::SFInt32: case FieldType::SFFloat: case FieldType::SFDouble: case FieldType::SFTime:
    case FieldType::MFInt32: case FieldType::MFFloat: case FieldType::MFDouble: case FieldType::MFTime:
      return 1;
    case FieldType::SFVec2f: case FieldType::MFVec2f:
      return 2;
    case FieldType::SFVec3f: case FieldType::SFVec3d: case FieldType::SFColor:
    case FieldType::MFVec3f: case FieldType::MFVec3d: case FieldType::MFColor:
      return 3;
    case FieldType::SFVec4f: case FieldType::SFRotation: case FieldType::MFVec4f: case FieldType::MFRotation:
      return 4;
    case FieldType::SFMatrix4f:
      return 16;
    default:
      return 0;
  }
}

bool integral(FieldType t) { return t == FieldType::SFInt32 || t == FieldType::MFInt32; }
// A rotation's axis is normalised and its angle is periodic: no range, but finite.
bool rotation(FieldType t) { return t == FieldType::SFRotation || t == FieldType::MFRotation; }

// The value text with every number equal to x.
std::string repeated(const std::string& x, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += (i ? " " : "") + x;
  return s;
}

std::string number(double v, bool isInt) {
  if (isInt) return std::to_string(static_cast<long long>(v));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// A value of type t with its numbers at x: every number, or for a matrix
// (which must be invertible) x on the diagonal and 0 elsewhere.
std::string valueAt(FieldType t, const std::string& x, int n) {
  if (t != FieldType::SFMatrix4f) return repeated(x, n);
  std::string s;
  for (int i = 0; i < 16; ++i) s += (i ? " " : "") + (i % 5 == 0 ? x : std::string("0"));
  return s;
}

bool refused(Field& f, const std::string& text) {
  try {
    f.setFromString(text);
  } catch (const ValueError&) {
    return true;
  }
  return false;
}

}  // namespace

TEST(FieldRanges, EveryNumericFieldASceneCanSetIsBoundedOnBothSides) {
  const NodeRegistry registry = builtinRegistry();
  int checked = 0;
  for (const NodeType* type : registry.all()) {
    const auto node = type->create();
    for (Field* f : node->fields()) {
      const int n = components(f->type());
      if (n == 0 || !settableInFile(f->access()) || rotation(f->type())) continue;
      const std::string where = type->name + "." + std::string(f->name());
      const Range* r = f->range();
      ASSERT_NE(r, nullptr) << where << " declares no range";
      EXPECT_TRUE(std::isfinite(r->lo) && std::isfinite(r->hi))
          << where << " has the half-open range " << r->str() << ": give it a finite upper and lower bound";
      ++checked;
    }
  }
  EXPECT_GT(checked, 80) << "fewer numeric fields than MillSim has: is the registry complete?";
}

TEST(FieldRanges, ValuesJustOutsideTheRangeNaNAndInfinityAreRefused) {
  const NodeRegistry registry = builtinRegistry();
  for (const NodeType* type : registry.all()) {
    auto node = type->create();
    for (Field* f : node->fields()) {
      const int n = components(f->type());
      if (n == 0 || !settableInFile(f->access())) continue;
      if (rotation(f->type())) {
        EXPECT_TRUE(refused(*f, "0 1 0 nan")) << type->name << "." << f->name() << " accepts a NaN angle";
        EXPECT_TRUE(refused(*f, "inf 0 0 1")) << type->name << "." << f->name() << " accepts an infinite axis";
        continue;
      }
      const Range* r = f->range();
      if (!r || !std::isfinite(r->lo) || !std::isfinite(r->hi)) continue;
      const std::string where = type->name + "." + std::string(f->name()) + " " + r->str();
      const std::string defaultText = f->toString();
      // The default lies inside (setting it again is accepted).
      EXPECT_FALSE(refused(*f, defaultText)) << where << ": its default '" << defaultText << "' is refused";
      const bool isInt = integral(f->type());
      const double stepLo = isInt ? 1.0 : 1e-3 * std::max(1.0, std::abs(r->lo));
      const double stepHi = isInt ? 1.0 : 1e-3 * std::max(1.0, std::abs(r->hi));
      const double below = r->loOpen ? r->lo : r->lo - stepLo;
      const double above = r->hiOpen ? r->hi : r->hi + stepHi;
      EXPECT_TRUE(refused(*f, valueAt(f->type(), number(below, isInt), n))) << where << " accepts " << number(below, isInt);
      EXPECT_TRUE(refused(*f, valueAt(f->type(), number(above, isInt), n))) << where << " accepts " << number(above, isInt);
      if (!isInt) {
        EXPECT_TRUE(refused(*f, valueAt(f->type(), "nan", n))) << where << " accepts NaN";
        EXPECT_TRUE(refused(*f, valueAt(f->type(), "inf", n))) << where << " accepts infinity";
      }
      // Inside the range both ends are accepted (a bound that is too tight would refuse real scenes).
      if (!r->loOpen) {
        EXPECT_FALSE(refused(*f, valueAt(f->type(), number(r->lo, isInt), n))) << where << " refuses its lower bound";
      }
      if (!r->hiOpen) {
        EXPECT_FALSE(refused(*f, valueAt(f->type(), number(r->hi, isInt), n))) << where << " refuses its upper bound";
      }
    }
  }
}
