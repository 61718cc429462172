#pragma once
// What `millsim run` and `millsim replay` print and write after a Session:
// the statistics, the sound and graphics lines, the lesson report, the saved
// volume and mesh, and the errors; returns the command's exit code.
#include <ostream>
#include <string>

#include "millsim/core/Scene.h"
#include "millsim/session/Session.h"

namespace millsim::app {

// "MillSim — <WorldInfo title, else the file name>"
std::string windowTitle(const Scene& scene, const std::string& file);

// The real-time run's rate, compute time, safety and device lines.
void printRunSummary(std::ostream& os, const SessionResult& s);
// The simulated run's frames, forces and milling lines (timing: compute time too).
void printReplaySummary(std::ostream& os, const SessionResult& s, bool timing);

struct RunOutputs {
  std::string verb;       // "run" or "replay", for the messages
  std::string sceneFile;
  std::string log, report, saveVolume, saveMesh;  // empty: not asked for
};

// After the session (the log stream closed by the caller, `logOk` whether it
// was written): prints the sound and graphics lines, writes the report,
// the saved volume and mesh, prints every error. kExitOk, or kExitFailure.
int finishOutputs(std::ostream& out, std::ostream& err, const SessionResult& s, const Scene& scene,
                  const RunOutputs& outputs, bool logOk);

}  // namespace millsim::app
