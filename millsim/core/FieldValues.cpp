#include "millsim/core/FieldValues.h"

#include <array>
#include <charconv>
#include <cstdio>

#include <glm/geometric.hpp>

namespace millsim {

std::string_view fieldTypeName(FieldType t) {
  static constexpr std::array<std::string_view, 27> names = {
      "SFBool", "SFInt32", "SFFloat", "SFDouble", "SFTime", "SFString", "SFVec2f", "SFVec3f",
      "SFVec3d", "SFRotation", "SFColor", "SFNode", "MFBool", "MFInt32", "MFFloat", "MFDouble",
      "MFTime", "MFString", "MFVec2f", "MFVec3f", "MFVec3d", "MFRotation", "MFColor", "MFNode",
      "SFVec4f", "MFVec4f", "SFMatrix4f"};
  return names.at(static_cast<std::size_t>(t));
}

std::string_view accessName(Access a) {
  switch (a) {
    case Access::InitializeOnly: return "initializeOnly";
    case Access::InputOnly: return "inputOnly";
    case Access::OutputOnly: return "outputOnly";
    case Access::InputOutput: return "inputOutput";
  }
  return "?";
}

namespace {
bool isSeparator(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; }

std::string quoteForMessage(std::string_view tok) {
  constexpr std::size_t maxShown = 40;
  if (tok.size() > maxShown) return "'" + std::string(tok.substr(0, maxShown)) + "...'";
  return "'" + std::string(tok) + "'";
}

template <class T> T readReal(ValueLexer& lx, const char* what) {
  if (lx.atEnd()) throw ValueError(std::string("expected ") + what + ", found the end of the value");
  std::string_view tok = lx.next();
  // from_chars accepts neither a leading '+' nor nothing else; X3D allows '+'.
  std::string_view digits = tok;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  T v{};
  auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range && p == digits.data() + digits.size())
    throw ValueError(quoteForMessage(tok) + " is out of range for a " +
                     (sizeof(T) == 4 ? "32-bit float (about ±3.4e38)" : "64-bit double (about ±1.8e308)"));
  if (ec != std::errc() || p != digits.data() + digits.size())
    throw ValueError(std::string("expected ") + what + ", found " + quoteForMessage(tok));
  if (!std::isfinite(v)) throw ValueError(std::string("expected a finite number, found ") + quoteForMessage(tok));
  return v;
}
}  // namespace

bool ValueLexer::atEnd() {
  skipSeparators();
  return pos_ >= s_.size();
}

void ValueLexer::skipSeparators() {
  while (pos_ < s_.size() && isSeparator(s_[pos_])) ++pos_;
}

std::string_view ValueLexer::next() {
  skipSeparators();
  if (pos_ >= s_.size()) throw ValueError("unexpected end of the value");
  std::size_t start = pos_;
  while (pos_ < s_.size() && !isSeparator(s_[pos_])) ++pos_;
  return s_.substr(start, pos_ - start);
}

std::string ValueLexer::nextQuotedString() {
  skipSeparators();
  if (pos_ >= s_.size()) throw ValueError("expected a quoted string, found the end of the value");
  if (s_[pos_] != '"')
    throw ValueError("expected a quoted string (MFString items are written \"like\" \"this\"), found " +
                     quoteForMessage(s_.substr(pos_, 20)));
  ++pos_;
  std::string out;
  while (pos_ < s_.size()) {
    char c = s_[pos_++];
    if (c == '"') return out;
    if (c == '\\' && pos_ < s_.size()) c = s_[pos_++];
    out += c;
  }
  throw ValueError("unterminated string: a closing '\"' is missing");
}

// Force first, then mass, length, time and angle, as "N·m·s/rad" and "kg·m²" read.
std::string siUnit(const Quantity& q) {
  struct Base {
    int power;
    const char* symbol;
  };
  const Base bases[] = {{q.force, "N"}, {q.mass, "kg"}, {q.length, "m"}, {q.time, "s"}, {q.angle, "rad"}};
  auto power = [](const char* symbol, int p) {
    const char* const superscripts[] = {"", "", "²", "³", "⁴"};
    return std::string(symbol) + (p < 5 ? superscripts[p] : "^" + std::to_string(p));
  };
  std::string above, below;
  for (const Base& b : bases) {
    if (b.power > 0) above += (above.empty() ? "" : "·") + power(b.symbol, b.power);
    if (b.power < 0) below += (below.empty() ? "" : "·") + power(b.symbol, -b.power);
  }
  if (below.empty()) return above;
  return (above.empty() ? std::string("1") : above) + "/" + below;
}

std::string Range::str() const {
  const bool hasLo = !std::isinf(lo), hasHi = !std::isinf(hi);
  if (hasLo && hasHi)
    return std::string(loOpen ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + (hiOpen ? ")" : "]");
  if (hasLo) return std::string(loOpen ? "> " : ">= ") + formatNumber(lo);
  if (hasHi) return std::string(hiOpen ? "< " : "<= ") + formatNumber(hi);
  return "any";
}

// Shortest text that reads back to the same value (std::to_chars round-trips),
// in plain decimals for the sizes scenes use (0.0005 rather than 5e-04).
template <class T> static std::string shortest(T v) {
  char buf[128];
  const T mag = std::fabs(v);
  const bool plain = v == 0 || (mag >= T(1e-6) && mag < T(1e9));
  auto [p, ec] = plain ? std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed)
                       : std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, p) : std::string("0");
}
std::string formatNumber(double v) { return shortest(v); }
std::string formatNumber(float v) { return shortest(v); }

bool X3DValue<bool>::read(ValueLexer& lx) {
  if (lx.atEnd()) throw ValueError("expected true or false, found the end of the value");
  std::string_view tok = lx.next();
  // The XML encoding writes true/false; TRUE/FALSE (the classic encoding) is accepted too.
  if (tok == "true" || tok == "TRUE") return true;
  if (tok == "false" || tok == "FALSE") return false;
  throw ValueError("expected true or false, found " + quoteForMessage(tok));
}

std::int32_t X3DValue<std::int32_t>::read(ValueLexer& lx) {
  if (lx.atEnd()) throw ValueError("expected an integer, found the end of the value");
  std::string_view tok = lx.next();
  std::string_view t = tok;
  bool negative = false;
  if (!t.empty() && (t.front() == '+' || t.front() == '-')) {
    negative = t.front() == '-';
    t.remove_prefix(1);
  }
  int base = 10;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    base = 16;
    t.remove_prefix(2);
  }
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v, base);
  if (t.empty() || ec != std::errc() || p != t.data() + t.size())
    throw ValueError("expected an integer, found " + quoteForMessage(tok));
  if (negative) v = -v;
  if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
    throw ValueError("integer " + quoteForMessage(tok) + " does not fit in 32 bits");
  return static_cast<std::int32_t>(v);
}

float X3DValue<float>::read(ValueLexer& lx) { return readReal<float>(lx, "a number"); }
double X3DValue<double>::read(ValueLexer& lx) { return readReal<double>(lx, "a number"); }

glm::vec2 X3DValue<glm::vec2>::read(ValueLexer& lx) {
  const char* what = "2 numbers (x y)";
  float x = readReal<float>(lx, what), y = readReal<float>(lx, what);
  return {x, y};
}
glm::vec3 X3DValue<glm::vec3>::read(ValueLexer& lx) {
  const char* what = "3 numbers (x y z)";
  float x = readReal<float>(lx, what), y = readReal<float>(lx, what), z = readReal<float>(lx, what);
  return {x, y, z};
}
glm::vec4 X3DValue<glm::vec4>::read(ValueLexer& lx) {
  const char* what = "4 numbers (x y z w)";
  float x = readReal<float>(lx, what), y = readReal<float>(lx, what), z = readReal<float>(lx, what),
        w = readReal<float>(lx, what);
  return {x, y, z, w};
}
glm::dvec3 X3DValue<glm::dvec3>::read(ValueLexer& lx) {
  const char* what = "3 numbers (x y z)";
  double x = readReal<double>(lx, what), y = readReal<double>(lx, what), z = readReal<double>(lx, what);
  return {x, y, z};
}

glm::mat4 X3DValue<glm::mat4>::read(ValueLexer& lx) {
  const char* what = "16 numbers (a 4x4 matrix, row by row)";
  glm::mat4 m(1.f);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) m[col][row] = readReal<float>(lx, what);
  return m;
}

Rotation X3DValue<Rotation>::read(ValueLexer& lx) {
  const char* what = "4 numbers (axis x y z, angle in radians)";
  glm::vec3 axis;
  axis.x = readReal<float>(lx, what);
  axis.y = readReal<float>(lx, what);
  axis.z = readReal<float>(lx, what);
  float angle = readReal<float>(lx, what);
  float len = glm::length(axis);
  if (len < 1e-6f) {
    // A zero axis only makes sense for the identity rotation.
    if (angle != 0.f) throw ValueError("rotation axis is zero but the angle is not; expected a non-zero axis");
    return Rotation{};
  }
  return Rotation{axis / len, angle};
}

Color X3DValue<Color>::read(ValueLexer& lx) {
  const char* what = "3 numbers (red green blue)";
  glm::vec3 c;
  c.r = readReal<float>(lx, what);
  c.g = readReal<float>(lx, what);
  c.b = readReal<float>(lx, what);
  for (int i = 0; i < 3; ++i)
    if (c[i] < 0.f || c[i] > 1.f)
      throw ValueError("colour component " + formatNumber(c[i]) + " is outside the expected range [0, 1]");
  return Color{c};
}

void X3DValue<std::string>::write(const std::string& v, std::string& out) {
  out += '"';
  for (char c : v) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

void X3DValue<glm::vec2>::write(const glm::vec2& v, std::string& out) {
  out += formatNumber(v.x) + ' ' + formatNumber(v.y);
}
void X3DValue<glm::vec3>::write(const glm::vec3& v, std::string& out) {
  out += formatNumber(v.x) + ' ' + formatNumber(v.y) + ' ' + formatNumber(v.z);
}
void X3DValue<glm::vec4>::write(const glm::vec4& v, std::string& out) {
  out += formatNumber(v.x) + ' ' + formatNumber(v.y) + ' ' + formatNumber(v.z) + ' ' + formatNumber(v.w);
}
void X3DValue<glm::dvec3>::write(const glm::dvec3& v, std::string& out) {
  out += formatNumber(v.x) + ' ' + formatNumber(v.y) + ' ' + formatNumber(v.z);
}
void X3DValue<Rotation>::write(const Rotation& v, std::string& out) {
  X3DValue<glm::vec3>::write(v.axis, out);
  out += ' ' + formatNumber(v.angle);
}

void X3DValue<glm::mat4>::write(const glm::mat4& v, std::string& out) {
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      if (row || col) out += ' ';
      out += formatNumber(v[col][row]);
    }
}

template <> std::string parseSingle<std::string>(std::string_view text) { return std::string(text); }

}  // namespace millsim
