#include "millsim/haptics/MillTool.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "millsim/core/FieldValues.h"

namespace millsim {

const NodeType& MillTool::type() {
  static const NodeType t = makeNodeType<MillTool>("MillTool", "tool", "MillSim haptics",
                                                   "The burr: a cutting head (round, cylinder, taper or inverted-cone) at the tip and a shaft along local +Y.");
  return t;
}

std::string MillTool::problem() const {
  BurrShape parsed;
  if (!parseBurrShape(shape.get(), parsed))
    return "MillTool shape \"" + shape.get() + "\" is not one of: " + std::string(kBurrShapeNames);
  if ((parsed == BurrShape::Taper || parsed == BurrShape::InvertedCone) && tipEndRadius.get() > tipRadius.get())
    return "MillTool tipEndRadius " + formatNumber(tipEndRadius.get()) + " is larger than tipRadius " +
           formatNumber(tipRadius.get()) + "; tipRadius is the " + shape.get() + " head's widest radius";
  return {};
}

void MillTool::initialize(DiagnosticSink& sink) {
  if (std::string p = problem(); !p.empty()) {
    sink.error(location(), p);
    return;
  }
  if (shaftRadius.get() > tipRadius.get())
    sink.warning(location(), "MillTool shaftRadius " + formatNumber(shaftRadius.get()) + " is larger than tipRadius " +
                                 formatNumber(tipRadius.get()) + "; the shaft will touch before the burr");
}

std::string toolCell(const ToolGeometry& t) {
  std::string out(burrShapeName(t.shape));
  for (double v : {t.tipRadius, t.tipLength, t.tipEndRadius, t.shaftRadius, t.shaftLength}) {
    out += ' ';
    out += formatNumber(v);
  }
  return out;
}

bool parseToolCell(std::string_view cell, ToolGeometry& t) {
  auto next = [&cell]() {
    while (!cell.empty() && cell.front() == ' ') cell.remove_prefix(1);
    const std::size_t end = std::min(cell.find(' '), cell.size());
    const std::string_view token = cell.substr(0, end);
    cell.remove_prefix(end);
    return token;
  };
  ToolGeometry g;
  if (!parseBurrShape(next(), g.shape)) return false;
  for (double* v : {&g.tipRadius, &g.tipLength, &g.tipEndRadius, &g.shaftRadius, &g.shaftLength}) {
    const std::string_view token = next();
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), *v);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(*v) || *v < 0.0 || *v > 1.0)
      return false;
  }
  if (!next().empty() || !(g.tipRadius > 0.0)) return false;
  t = g;
  return true;
}

}  // namespace millsim
