#pragma once
// A sweep's results on disk: OUT/cells/<id>/ holds what the cell's command
// wrote (its result files, stdout.txt, stderr.txt) and, written last and
// atomically, status.json — its exit code, wall time, host and command. A
// cell is done when that status says exit 0 for the command the sweep file
// now gives it; anything else is run again (resumable, whichever executor
// ran it before).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sweep/SweepFile.h"

namespace millsim::sweep {

struct CellStatus {
  int exitCode = 0;          // the command's; 128 + n when signal n stopped it
  double seconds = 0.0;      // wall time (a timing: differs run to run)
  std::string host;          // where it ran
  std::string executor;      // "local" or "slurm job J task T"
  std::string command;       // the command line, shell-quoted
  std::string finished;      // UTC, ISO 8601
};

enum class CellState { Pending, Done, Failed, Stale };

std::filesystem::path defaultOutput(const Sweep& sweep);  // FOLDER/NAME.sweep
std::filesystem::path cellFolder(const std::filesystem::path& out, const Cell& cell);
std::string shellQuoted(const std::vector<std::string>& args);

std::optional<CellStatus> readStatus(const std::filesystem::path& cellFolder);
// Atomically (a temporary file renamed over it). Throws std::runtime_error.
void writeStatus(const std::filesystem::path& cellFolder, const CellStatus& status);
// Pending: no status; Stale: a status for another command (the file changed).
CellState stateOf(const std::filesystem::path& out, const Cell& cell, std::optional<CellStatus>* status = nullptr);

std::string hostName();
std::string utcNow();

}  // namespace millsim::sweep
