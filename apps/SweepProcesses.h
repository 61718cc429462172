#pragma once
// Processes for `millsim sweep`: a cell's command started in its folder, and
// a short command (sbatch, squeue) run to completion with its output read.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

#include "sweep/SweepCells.h"
#include "sweep/SweepFile.h"

namespace millsim::app {

// This millsim binary (what every cell runs).
std::filesystem::path millsimExecutable();

// Empties the cell's folder and starts its command there (stdout.txt,
// stderr.txt, stdin /dev/null), in a process group of its own so that a
// terminal's Ctrl-C reaches the sweep, which stops its cells itself.
pid_t startCell(const std::filesystem::path& exe, const sweep::Cell& cell, const std::filesystem::path& folder);

// The exit code a wait status stands for (128 + n for signal n).
int exitCodeOf(int waitStatus);

struct Captured {
  int exitCode = -1;  // -1: could not start (not on PATH)
  std::string out, err;
};
// Runs argv[0] found on PATH; its output read whole.
Captured capture(const std::vector<std::string>& argv);

}  // namespace millsim::app
