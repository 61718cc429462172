#include "millsim/session/Replay.h"

#include "millsim/session/Session.h"

namespace millsim {

namespace {

SessionOptions sessionOptions(std::ostream* log, const ReplayOptions& options) {
  SessionOptions s;
  s.renderer = options.renderer;
  s.rate = options.rate;
  s.timing = options.timing;
  s.until = options.until;
  s.log = log;
  return s;
}

ReplaySummary run(Session& session, const ReplayOptions& options) {
  if (options.onLoop) options.onLoop(session.loop());
  if (options.onFrame) session.observe(options.onFrame);
  const SessionResult r = session.runSimulated();
  return ReplaySummary{r.renderer, r.rate, r.stats, r.last.out};
}

}  // namespace

ReplaySummary replay(Scene& scene, const Trajectory& trajectory, std::ostream* log, const ReplayOptions& options) {
  return run(*Session::replay(scene, trajectory, sessionOptions(log, options)), options);
}

ReplaySummary replayRecorded(Scene& scene, const RecordedRun& recorded, std::ostream* log, const ReplayOptions& options) {
  return run(*Session::review(scene, recorded, sessionOptions(log, options)), options);
}

}  // namespace millsim
