#pragma once
// What `millsim sweep` does once its file is read: run the cells here, submit
// them to Slurm, run one cell (what a Slurm task runs), report the state of
// the cells, or merge their results. Every executor runs a cell the same way
// (runOneCell's command in the cell's folder), so its result files are the
// same wherever it ran.
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "sweep/SweepFile.h"

namespace millsim::app {

struct SweepRequest {
  std::string verb;  // run, status, collect, cell
  sweep::Sweep sweep;
  std::filesystem::path out;
  bool slurm = false, retryFailed = false, dryRun = false, wait = false;
  int jobs = 0;            // --local: at once; 0: the cores
  double timeout = 3600;   // --slurm --wait
  std::uint64_t cell = 0;  // cell
  std::filesystem::path submitted;  // cell: the submission's list of cells and commands (SweepSlurm.h)
  std::string csv;         // collect
};

// Which cells an executor runs now: every cell not done and not still in
// Slurm's queue (`queued`), failed ones only when retrying; the rest counted.
struct CellSelection {
  std::vector<std::uint64_t> toRun;
  std::uint64_t done = 0, failed = 0;
};
CellSelection selectCells(const SweepRequest& request, const std::set<std::uint64_t>& queued);

// The command's exit code: 0 all done, 1 a cell failed or is left, 2 bad
// input, 130 interrupted (Ctrl-C; finished cells stay).
int runSweepRequest(const SweepRequest& request);

}  // namespace millsim::app
