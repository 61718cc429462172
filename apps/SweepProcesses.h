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
// stderr.txt, stdin /dev/null, nothing blocked). `ownGroup`: in a process
// group of its own, so that a terminal's Ctrl-C reaches the local sweep,
// which stops its cells itself; a Slurm task keeps its cell in its group,
// where Slurm's process tracking looks.
pid_t startCell(const std::filesystem::path& exe, const sweep::Cell& cell, const std::filesystem::path& folder,
                bool ownGroup);

// The exit code a wait status stands for (128 + n for signal n).
int exitCodeOf(int waitStatus);

// One executor at a time on a results folder: two would empty each other's
// running cells' folders. Held while it lives (flock on OUT/.lock: released
// if the process dies). Throws std::runtime_error when another holds it.
class FolderLock {
public:
  explicit FolderLock(const std::filesystem::path& out);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

private:
  int fd_ = -1;
};

struct Captured {
  int exitCode = -1;  // -1: could not start (not on PATH)
  std::string out, err;
};
// Runs argv[0] found on PATH; its output read whole.
Captured capture(const std::vector<std::string>& argv);

}  // namespace millsim::app
