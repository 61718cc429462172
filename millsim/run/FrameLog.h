#pragma once
// The frame log: one CSV row per haptic frame, written by replay and by the
// live loop alike (docs/algorithms.md, "Logs"), ending with the stop row. It
// holds the device pose, button, time and period of every frame, so a log can
// be replayed frame for frame (millsim/devices/RecordedRun, "Review"); the
// rest is what the renderer and the safety layer did.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "millsim/run/HapticLoop.h"

namespace millsim {

const char* frameLogHeader();
void appendFrameRow(std::string& out, const FrameRecord& r);

// Scene thread: drains a loop's records into a stream (or just counts them).
class FrameLogWriter {
public:
  explicit FrameLogWriter(std::ostream* out);
  // Also hands every drained record, in order, to `observer` (the window's
  // HUD statistics, the milling sound); observers add up.
  void observe(std::function<void(const FrameRecord&)> observer) { observers_.push_back(std::move(observer)); }
  // Writes every record the loop has published so far; returns how many.
  std::size_t drain(HapticLoop& loop);
  const FrameRecord& last() const { return last_; }
  long written() const { return written_; }

private:
  std::ostream* out_;
  std::vector<std::function<void(const FrameRecord&)>> observers_;
  std::string row_;
  FrameRecord last_;
  long written_ = 0;
};

}  // namespace millsim
