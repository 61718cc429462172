#include "millsim/std/NumberToText.h"

#include <cmath>
#include <cstdio>

namespace millsim {

const NodeType& NumberToText::type() {
  static const NodeType t = makeNodeType<NumberToText>(
      "NumberToText", "children", "MillSim",
      "Writes a number as a line of text (prefix, value × scale with fixed decimals, suffix); evaluated by the event clock when "
      "set_value arrives.");
  return t;
}

bool NumberToText::processEvents() {
  if (!takeEvent(set_value, seen_)) return false;
  const double v = double(set_value.get()) * double(scale.get());
  char number[64];
  if (std::isfinite(v))
    std::snprintf(number, sizeof number, "%.*f", int(decimals.get()), v);
  else
    std::snprintf(number, sizeof number, "%s", std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf");
  string_changed.set({prefix.get() + number + suffix.get()});
  return true;
}

}  // namespace millsim
