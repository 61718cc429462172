#pragma once
// The value types behind X3D fields and their X3D XML spelling: how each one is
// read from an attribute string and written back. One trait per value type
// (X3DValue<T>) so every field type, the parser and the docs agree.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "millsim/core/Quantity.h"

namespace millsim {

enum class FieldType : std::uint8_t {
  SFBool, SFInt32, SFFloat, SFDouble, SFTime, SFString, SFVec2f, SFVec3f, SFVec3d, SFRotation, SFColor, SFNode,
  MFBool, MFInt32, MFFloat, MFDouble, MFTime, MFString, MFVec2f, MFVec3f, MFVec3d, MFRotation, MFColor, MFNode,
  SFVec4f, MFVec4f,  // appended so that the values above keep their numbers
  SFMatrix4f,
};
std::string_view fieldTypeName(FieldType t);

// X3D access types: who may set a field and which way routes may go.
enum class Access : std::uint8_t { InitializeOnly, InputOnly, OutputOnly, InputOutput };
std::string_view accessName(Access a);
inline bool settableInFile(Access a) { return a == Access::InitializeOnly || a == Access::InputOutput; }
inline bool canRouteFrom(Access a) { return a == Access::OutputOnly || a == Access::InputOutput; }
inline bool canRouteTo(Access a) { return a == Access::InputOnly || a == Access::InputOutput; }

// A bad attribute value. The message says what was expected and what was found;
// the loader adds file:line:column and the field's name.
struct ValueError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Distinct C++ types for X3D types that share a representation, so the type
// system (and routes) keep SFTime apart from SFDouble and SFColor from SFVec3f.
struct Time {
  double seconds = 0;
  friend bool operator==(const Time&, const Time&) = default;
};
struct Color {
  glm::vec3 rgb{0.f};
  friend bool operator==(const Color&, const Color&) = default;
};
// Axis-angle rotation as X3D writes it; the axis is kept normalised.
struct Rotation {
  glm::vec3 axis{0.f, 0.f, 1.f};
  float angle = 0.f;  // radians
  glm::quat quat() const { return glm::angleAxis(angle, axis); }
  friend bool operator==(const Rotation&, const Rotation&) = default;
};

// Splits an attribute into tokens separated by whitespace and commas, as the
// X3D XML encoding allows ("1 2 3, 4 5 6").
class ValueLexer {
public:
  explicit ValueLexer(std::string_view text) : s_(text) {}
  bool atEnd();
  std::string_view next();         // throws ValueError at end of input
  std::string nextQuotedString();  // an MFString item: "..." with \" and \\ escapes

private:
  void skipSeparators();
  std::string_view s_;
  std::size_t pos_ = 0;
};

// Inclusive/exclusive numeric bounds checked on every number of a field's value.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool loOpen = false;
  bool hiOpen = false;
  // What the numbers measure (the bounds are in its SI unit): how a scene's
  // <unit> statements convert them. Dimensionless unless declared with in().
  Quantity quantity{};
  Range in(Quantity q) const {
    Range r = *this;
    r.quantity = q;
    return r;
  }
  bool contains(double v) const {
    return (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi);
  }
  bool unbounded() const { return std::isinf(lo) && std::isinf(hi); }
  std::string str() const;  // "> 0", "[0, 1]", ">= 1"
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range nonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range atLeast(double v) { return {v, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range openClosed(double a, double b) { return {a, b, true, false}; }  // (a, b]
  // The bounds as a single-precision field stores them, so that a float field
  // accepts the value its bound reads as ('0.00001' is below 1e-5 as a float).
  Range asFloat() const { return {double(float(lo)), double(float(hi)), loOpen, hiOpen}; }

  // The values lessons use, [usualLo, usualHi] in the quantity's SI unit: a
  // scene value ten times or more outside them is a likely unit slip (0.2
  // meant as N·m in a file whose <unit> makes it N·mm), which the loader
  // warns of. Unset (both 0) on most fields.
  double usualLo = 0.0, usualHi = 0.0;
  bool hasUsual() const { return usualHi > 0.0; }
  Range usually(double usualLow, double usualHigh) const {
    Range r = *this;
    r.usualLo = usualLow, r.usualHi = usualHigh;
    return r;
  }
};

std::string formatNumber(double v);
std::string formatNumber(float v);
// A number that came from a float component, printed as that float (0.1, not 0.10000000149).
inline std::string formatComponent(double v) {
  return double(float(v)) == v ? formatNumber(float(v)) : formatNumber(v);
}

// Whether a value type keeps its numbers in single precision (range checks then
// compare against the bounds as floats).
template <class T> constexpr bool storesFloats() {
  return std::is_same_v<T, float> || std::is_same_v<T, glm::vec2> || std::is_same_v<T, glm::vec3> ||
         std::is_same_v<T, glm::vec4> || std::is_same_v<T, Color> || std::is_same_v<T, glm::mat4>;
}

// X3DValue<T>: read one value of T from the lexer, write it back, and list its numbers.
template <class T> struct X3DValue;

template <> struct X3DValue<bool> {
  static constexpr FieldType sf = FieldType::SFBool, mf = FieldType::MFBool;
  static bool read(ValueLexer& lx);
  static void write(const bool& v, std::string& out) { out += v ? "true" : "false"; }
  template <class F> static void numbers(const bool&, F&&) {}
};
template <> struct X3DValue<std::int32_t> {
  static constexpr FieldType sf = FieldType::SFInt32, mf = FieldType::MFInt32;
  static std::int32_t read(ValueLexer& lx);
  static void write(const std::int32_t& v, std::string& out) { out += std::to_string(v); }
  template <class F> static void numbers(const std::int32_t& v, F&& f) { f(double(v)); }
};
template <> struct X3DValue<float> {
  static constexpr FieldType sf = FieldType::SFFloat, mf = FieldType::MFFloat;
  static float read(ValueLexer& lx);
  static void write(const float& v, std::string& out) { out += formatNumber(v); }
  template <class F> static void numbers(const float& v, F&& f) { f(double(v)); }
};
template <> struct X3DValue<double> {
  static constexpr FieldType sf = FieldType::SFDouble, mf = FieldType::MFDouble;
  static double read(ValueLexer& lx);
  static void write(const double& v, std::string& out) { out += formatNumber(v); }
  template <class F> static void numbers(const double& v, F&& f) { f(v); }
};
template <> struct X3DValue<Time> {
  static constexpr FieldType sf = FieldType::SFTime, mf = FieldType::MFTime;
  static Time read(ValueLexer& lx) { return {X3DValue<double>::read(lx)}; }
  static void write(const Time& v, std::string& out) { out += formatNumber(v.seconds); }
  template <class F> static void numbers(const Time& v, F&& f) { f(v.seconds); }
};
template <> struct X3DValue<std::string> {
  static constexpr FieldType sf = FieldType::SFString, mf = FieldType::MFString;
  static std::string read(ValueLexer& lx) { return lx.nextQuotedString(); }
  static void write(const std::string& v, std::string& out);  // quoted, for MFString
  template <class F> static void numbers(const std::string&, F&&) {}
};
template <> struct X3DValue<glm::vec2> {
  static constexpr FieldType sf = FieldType::SFVec2f, mf = FieldType::MFVec2f;
  static glm::vec2 read(ValueLexer& lx);
  static void write(const glm::vec2& v, std::string& out);
  template <class F> static void numbers(const glm::vec2& v, F&& f) { f(v.x), f(v.y); }
};
template <> struct X3DValue<glm::vec3> {
  static constexpr FieldType sf = FieldType::SFVec3f, mf = FieldType::MFVec3f;
  static glm::vec3 read(ValueLexer& lx);
  static void write(const glm::vec3& v, std::string& out);
  template <class F> static void numbers(const glm::vec3& v, F&& f) { f(v.x), f(v.y), f(v.z); }
};
template <> struct X3DValue<glm::dvec3> {
  static constexpr FieldType sf = FieldType::SFVec3d, mf = FieldType::MFVec3d;
  static glm::dvec3 read(ValueLexer& lx);
  static void write(const glm::dvec3& v, std::string& out);
  template <class F> static void numbers(const glm::dvec3& v, F&& f) { f(v.x), f(v.y), f(v.z); }
};
template <> struct X3DValue<glm::vec4> {
  static constexpr FieldType sf = FieldType::SFVec4f, mf = FieldType::MFVec4f;
  static glm::vec4 read(ValueLexer& lx);
  static void write(const glm::vec4& v, std::string& out);
  template <class F> static void numbers(const glm::vec4& v, F&& f) { f(v.x), f(v.y), f(v.z), f(v.w); }
};
template <> struct X3DValue<Rotation> {
  static constexpr FieldType sf = FieldType::SFRotation, mf = FieldType::MFRotation;
  static Rotation read(ValueLexer& lx);
  static void write(const Rotation& v, std::string& out);
  template <class F> static void numbers(const Rotation&, F&&) {}
};
template <> struct X3DValue<Color> {
  static constexpr FieldType sf = FieldType::SFColor, mf = FieldType::MFColor;
  static Color read(ValueLexer& lx);
  static void write(const Color& v, std::string& out) { X3DValue<glm::vec3>::write(v.rgb, out); }
  template <class F> static void numbers(const Color& v, F&& f) { f(v.rgb.r), f(v.rgb.g), f(v.rgb.b); }
};

// SFMatrix4f (H3DAPI's MatrixTransform.matrix; no MFMatrix4f). Written as
// H3DAPI reads and writes a Matrix4f (X3DFieldConversion.h: m[0][0], m[0][1],
// ... of its row-major matrix): row by row, so the translation is the 4th, 8th
// and 12th number ("1 0 0 tx  0 1 0 ty  0 0 1 tz  0 0 0 1"). Stored as glm
// keeps it (m[column][row]).
template <> struct X3DValue<glm::mat4> {
  static constexpr FieldType sf = FieldType::SFMatrix4f;
  static glm::mat4 read(ValueLexer& lx);
  static void write(const glm::mat4& v, std::string& out);
  template <class F> static void numbers(const glm::mat4& v, F&& f) {
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) f(double(v[col][row]));
  }
};

// Whole-attribute parsing for single and multiple values.
template <class T> T parseSingle(std::string_view text) {
  ValueLexer lx(text);
  T v = X3DValue<T>::read(lx);
  if (!lx.atEnd()) throw ValueError("unexpected extra text '" + std::string(lx.next()) + "' after the value");
  return v;
}
template <> std::string parseSingle<std::string>(std::string_view text);  // SFString: the raw attribute

template <class T> std::vector<T> parseMultiple(std::string_view text) {
  ValueLexer lx(text);
  std::vector<T> out;
  while (!lx.atEnd()) {
    try {
      out.push_back(X3DValue<T>::read(lx));
    } catch (const ValueError& e) {
      throw ValueError("item " + std::to_string(out.size() + 1) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace millsim
