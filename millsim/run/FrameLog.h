#pragma once
// The frame log: one CSV row per haptic frame, written by replay and by the
// live loop alike (docs/algorithms.md, "Logs"). The first nine columns are a
// trajectory (t,x,y,z,qw,qx,qy,qz … button is further on), so a log can be
// replayed; the rest is what the renderer and the safety layer did.
#include <functional>
#include <ostream>
#include <string>

#include "millsim/run/HapticLoop.h"

namespace millsim {

const char* frameLogHeader();
void appendFrameRow(std::string& out, const FrameRecord& r);

// Scene thread: drains a loop's records into a stream (or just counts them).
class FrameLogWriter {
public:
  explicit FrameLogWriter(std::ostream* out);
  // Writes every record the loop has published so far; returns how many.
  std::size_t drain(HapticLoop& loop);
  const FrameRecord& last() const { return last_; }
  long written() const { return written_; }
  // Also hands every drained record, in order, to f (e.g. the milling sound).
  void setOnRecord(std::function<void(const FrameRecord&)> f) { onRecord_ = std::move(f); }

private:
  std::ostream* out_;
  std::string row_;
  FrameRecord last_;
  long written_ = 0;
  std::function<void(const FrameRecord&)> onRecord_;
};

}  // namespace millsim
