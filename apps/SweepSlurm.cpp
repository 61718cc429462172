#include "SweepSlurm.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "Commands.h"
#include "SweepProcesses.h"
#include "SweepResults.h"
#include "sweep/SweepCells.h"

namespace millsim::app {
namespace fs = std::filesystem;

namespace {

std::string jobName(const SweepRequest& r) { return "millsim-" + r.sweep.name; }

std::vector<std::string> recordedJobs(const SweepRequest& r) {
  std::vector<std::string> ids;
  std::ifstream in(r.out / "slurm" / "jobs.txt");
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) ids.push_back(line);
  return ids;
}

// "0-3,5,9-10": Slurm's --array list.
std::string arrayList(const std::vector<std::uint64_t>& cells) {
  std::string s;
  for (std::size_t i = 0; i < cells.size();) {
    std::size_t j = i;
    while (j + 1 < cells.size() && cells[j + 1] == cells[j] + 1) ++j;
    s += (s.empty() ? "" : ",") + std::to_string(cells[i]) + (j > i ? "-" + std::to_string(cells[j]) : "");
    i = j + 1;
  }
  return s;
}

// Slurm refuses array indices at or above MaxArraySize (1001 unless the cluster says otherwise).
std::uint64_t maxArraySize() {
  const Captured c = capture({"scontrol", "show", "config"});
  std::istringstream in(c.out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("MaxArraySize", 0) == 0)
      if (const std::size_t eq = line.find('='); eq != std::string::npos) return std::stoull(line.substr(eq + 1));
  return 1001;
}

std::string slurmFailure(const char* tool, const Captured& c) {
  if (c.exitCode < 0) return std::string(tool) + " is not on PATH: --slurm needs Slurm's client commands (Debian: slurm-client)";
  std::string err = c.err.empty() ? c.out : c.err;
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  return std::string(tool) + " failed (exit " + std::to_string(c.exitCode) + "): " + err;
}

}  // namespace

std::set<std::uint64_t> queuedCells(const SweepRequest& r) {
  std::set<std::uint64_t> queued;
  const std::vector<std::string> jobs = recordedJobs(r);
  if (jobs.empty()) return queued;
  // By name, not by id: squeue -j fails for a job it has forgotten.
  const Captured c = capture({"squeue", "-h", "-r", "--name=" + jobName(r), "-o", "%F %K"});
  if (c.exitCode != 0) throw std::runtime_error(slurmFailure("squeue", c));
  std::istringstream in(c.out);
  for (std::string job, task; in >> job >> task;)
    if (std::find(jobs.begin(), jobs.end(), job) != jobs.end() && task.find_first_not_of("0123456789") == std::string::npos)
      queued.insert(std::stoull(task));
  return queued;
}

std::string submittedCommand(const fs::path& cells, std::uint64_t index) {
  std::ifstream in(cells, std::ios::binary);
  const std::string prefix = std::to_string(index) + "\t";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  return {};
}

int runSlurm(const SweepRequest& r) {
  std::optional<FolderLock> lock(std::in_place, r.out);  // while choosing and submitting cells
  const std::set<std::uint64_t> queued = queuedCells(r);
  const CellSelection selected = selectCells(r, queued);
  const std::vector<std::uint64_t>& toRun = selected.toRun;
  const std::uint64_t done = selected.done, failed = selected.failed;
  std::cout << "sweep " << r.sweep.name << ": " << r.sweep.cellCount() << " cells, " << done << " done, " << queued.size()
            << " in Slurm's queue, " << toRun.size() << " to submit\n";
  if (failed) std::cout << "  " << failed << " failed before and left so (--retry-failed submits them again)\n";
  if (!toRun.empty()) {
    if (const std::uint64_t limit = maxArraySize(); toRun.back() >= limit)
      throw std::runtime_error("cell " + std::to_string(toRun.back()) + " is past the cluster's MaxArraySize " +
                               std::to_string(limit) + " (array indices are cell numbers): raise MaxArraySize in "
                               "slurm.conf or split the sweep");
    const fs::path slurm = r.out / "slurm";
    fs::create_directories(slurm);
    fs::create_directories(r.out / "cells");
    const std::string n = std::to_string(recordedJobs(r).size() + 1);
    // What each task must find when it starts: its cell's command as submitted.
    const fs::path cells = slurm / ("submit-" + n + ".cells"), script = slurm / ("submit-" + n + ".sh");
    {
      std::ofstream list(cells, std::ios::binary);
      for (std::uint64_t i : toRun) list << i << "\t" << sweep::shellQuoted(sweep::cellAt(r.sweep, i).args) << "\n";
      list.close();
      if (!list) throw std::runtime_error(cells.string() + ": cannot write the submitted cells");
    }
    {
      // The job's settings go to sbatch as arguments, not #SBATCH lines:
      // a path with a space or a '#' would break those.
      std::ofstream s(script);
      s << "#!/bin/sh\n# A millsim sweep's cells, one per array task; the task's index is the cell's.\n"
        << "exec "
        << sweep::shellQuoted({millsimExecutable().string(), "sweep", "cell", r.sweep.file.string()})
        << " \"$SLURM_ARRAY_TASK_ID\" "
        << sweep::shellQuoted({"--out", r.out.string(), "--submitted", cells.string(), "--yes"}) << "\n";
      s.close();
      if (!s) throw std::runtime_error(script.string() + ": cannot write the job script");
    }
    ::chmod(script.c_str(), 0755);
    std::vector<std::string> sbatch{"sbatch", "--parsable", "--job-name=" + jobName(r),
                                    "--array=" + arrayList(toRun) +
                                        (r.sweep.slurm.maxParallel ? "%" + std::to_string(r.sweep.slurm.maxParallel) : ""),
                                    "--output=" + (slurm / "task-%A_%a.out").string(), "--cpus-per-task=1"};
    if (!r.sweep.slurm.partition.empty()) sbatch.push_back("--partition=" + r.sweep.slurm.partition);
    if (!r.sweep.slurm.time.empty()) sbatch.push_back("--time=" + r.sweep.slurm.time);
    sbatch.push_back(script.string());
    const Captured c = capture(sbatch);
    if (c.exitCode != 0) throw std::runtime_error(slurmFailure("sbatch", c));
    std::string id = c.out.substr(0, c.out.find_first_of(";\n"));
    std::ofstream(slurm / "jobs.txt", std::ios::app) << id << "\n";
    std::cout << "submitted job " << id << ": cells " << arrayList(toRun)
              << (r.sweep.slurm.maxParallel ? ", at most " + std::to_string(r.sweep.slurm.maxParallel) + " at once" : "")
              << " (" << script.string() << ")\n";
  }
  lock.reset();
  if (!r.wait) {
    std::cout << "follow it with `millsim sweep status " << r.sweep.file.string() << "`\n";
    return kExitOk;
  }
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const std::size_t left = queuedCells(r).size();
    if (left == 0) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > r.timeout) {
      std::cout << left << " cells still in Slurm's queue after " << r.timeout << " s\n";
      return kExitFailure;
    }
    // Every 2 s: squeue asks the cluster's controller, which others share.
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
  return printSummary(std::cout, r);
}

}  // namespace millsim::app
