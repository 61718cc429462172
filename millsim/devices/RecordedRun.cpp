#include "millsim/devices/RecordedRun.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "millsim/core/FieldValues.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/driver/SafetyLayer.h"

namespace millsim {

namespace {

// A frame log starts like a trajectory, then the force: "t,x,y,z,qw,qx,qy,qz,fx".
constexpr std::string_view kLogStart = "t,x,y,z,qw,qx,qy,qz,fx,";
// The columns a review needs; the log has more (FrameLog.cpp), in any order here.
constexpr const char* kNeeded[] = {"t", "x", "y", "z", "qw", "qx", "qy", "qz", "button", "period_us"};
constexpr int kNeededCount = int(sizeof kNeeded / sizeof kNeeded[0]);

std::string_view stripBom(std::string_view s) {
  if (s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);
  return s;
}

std::vector<std::string_view> cellsOf(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

bool RecordedRun::isFrameLog(const std::string& text) { return stripBom(text).substr(0, kLogStart.size()) == kLogStart; }

RecordedRun RecordedRun::load(const std::filesystem::path& file) { return parse(readTrajectoryText(file), file.string()); }

RecordedRun RecordedRun::parse(const std::string& text, const std::string& file) {
  RecordedRun run;
  std::string_view rest = stripBom(text);
  int lineNo = 0;
  int column[kNeededCount];
  int flagsColumn = -1, rendererColumn = -1, toolColumn = -1;
  std::size_t width = 0;
  bool stopped = false;
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    std::string_view line = rest.substr(0, newline);
    rest = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) continue;
    const auto where = [&] { return file + ":" + std::to_string(lineNo) + ": "; };
    const auto cells = cellsOf(line);
    if (width == 0) {
      if (line.substr(0, kLogStart.size()) != kLogStart)
        throw TrajectoryError(where() + "not a MillSim frame log: its header starts with '" + std::string(kLogStart) + "'");
      for (int c = 0; c < kNeededCount; ++c) {
        const auto it = std::find(cells.begin(), cells.end(), kNeeded[c]);
        if (it == cells.end())
          throw TrajectoryError(where() + "the frame log has no '" + kNeeded[c] + "' column, which a review needs");
        column[c] = int(it - cells.begin());
      }
      if (auto it = std::find(cells.begin(), cells.end(), "flags"); it != cells.end()) flagsColumn = int(it - cells.begin());
      if (auto it = std::find(cells.begin(), cells.end(), "renderer"); it != cells.end())
        rendererColumn = int(it - cells.begin());
      if (auto it = std::find(cells.begin(), cells.end(), "tool"); it != cells.end()) toolColumn = int(it - cells.begin());
      width = cells.size();
      continue;
    }
    if (cells.size() != width)
      throw TrajectoryError(where() + "expected " + std::to_string(width) + " columns as in the header, found " +
                            std::to_string(cells.size()));
    if (stopped) throw TrajectoryError(where() + "a row after the stop row (flag " + std::to_string(kSafetyStopped) + ")");
    const auto number = [&](int c) {
      const std::string_view cell = cells[std::size_t(column[c])];
      double v = 0.0;
      const auto [p, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (cell.empty() || ec != std::errc() || p != cell.data() + cell.size() || !std::isfinite(v))
        throw TrajectoryError(where() + "column '" + kNeeded[c] + "' is not a finite number: '" + std::string(cell) + "'");
      return v;
    };
    if (flagsColumn >= 0) {
      const std::string_view cell = cells[std::size_t(flagsColumn)];
      unsigned long flags = 0;
      const auto [p, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), flags);
      if (ec != std::errc() || p != cell.data() + cell.size())
        throw TrajectoryError(where() + "column 'flags' is not a whole number: '" + std::string(cell) + "'");
      run.torqueNotOutput_ |= (flags & kSafetyTorqueNotOutput) != 0;
      if (flags & kSafetyStopped) {  // the zero output at the stop: not a frame to step
        stopped = true;
        continue;
      }
    }
    RecordedFrame f;
    f.t = number(0);
    f.device.position = glm::dvec3(number(1), number(2), number(3));
    f.device.orientation = glm::dquat(number(4), number(5), number(6), number(7));
    const double button = number(8);
    f.periodUs = number(9);
    Trajectory::checkRow(where(), f.t, f.device.position, f.device.orientation,
                         run.frames_.empty() ? NAN : run.frames_.back().t);
    if (button != 0.0 && button != 1.0)
      throw TrajectoryError(where() + "column 'button' must be 0 or 1, found '" + formatNumber(button) + "'");
    f.button = button == 1.0;
    if (f.periodUs < 0.0 || f.periodUs > 1e9)
      throw TrajectoryError(where() + "column 'period_us' = " + formatNumber(f.periodUs) + " is outside [0, 1e9] µs");
    if (rendererColumn >= 0) {
      const std::string_view name = cells[std::size_t(rendererColumn)];
      auto known = std::find(run.renderers_.begin(), run.renderers_.end(), name);
      if (known == run.renderers_.end()) known = run.renderers_.insert(run.renderers_.end(), std::string(name));
      f.renderer = int(known - run.renderers_.begin());
    }
    if (toolColumn >= 0) {
      const std::string_view cell = cells[std::size_t(toolColumn)];
      ToolGeometry tool;
      if (!parseToolCell(cell, tool))
        throw TrajectoryError(where() + "column 'tool' is not a burr ('shape tipRadius tipLength tipEndRadius "
                                        "shaftRadius shaftLength', m): '" + std::string(cell) + "'");
      auto known = std::find(run.tools_.begin(), run.tools_.end(), tool);
      if (known == run.tools_.end()) known = run.tools_.insert(run.tools_.end(), tool);
      f.tool = int(known - run.tools_.begin());
    }
    if (run.frames_.size() >= Trajectory::kMaxRows)
      throw TrajectoryError(where() + "more than " + std::to_string(Trajectory::kMaxRows) + " rows");
    run.frames_.push_back(f);
  }
  if (width == 0) throw TrajectoryError(file + ": empty frame log; expected its header");
  if (run.frames_.empty()) throw TrajectoryError(file + ": the frame log has a header but no frames");
  return run;
}

}  // namespace millsim
