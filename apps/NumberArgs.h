#pragma once
// Numeric command-line options: a number, finite, inside a stated range.
// CLI11's own Range and PositiveNumber let NaN through (every comparison with
// NaN is false), so the verbs use this instead.
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace millsim::app {

// Accepts a finite number in [lo, hi]; the message names the value and the range with its unit.
inline CLI::Validator finiteIn(double lo, double hi, const std::string& unit) {
  auto fmt = [](double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  };
  const std::string range = "[" + fmt(lo) + ", " + fmt(hi) + "] " + unit;
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        std::size_t used = 0;
        double v = 0.0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size()) return "'" + text + "' is not a number; expected one in " + range;
        if (!std::isfinite(v) || v < lo || v > hi) return text + " is out of range; expected a number in " + range;
        return {};
      },
      "NUMBER in " + range);
}

}  // namespace millsim::app
