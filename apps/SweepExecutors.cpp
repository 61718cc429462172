#include "SweepExecutors.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "Commands.h"
#include "SweepProcesses.h"
#include "SweepResults.h"
#include "SweepSlurm.h"
#include "sweep/SweepCells.h"

namespace millsim::app {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

std::atomic<int> gStopSignal{0};
extern "C" void onStop(int signal) { gStopSignal.store(signal); }

// SIGINT and SIGTERM set gStopSignal and interrupt waitpid (no SA_RESTART).
void catchStopSignals() {
  gStopSignal.store(0);
  struct sigaction sa {};
  sa.sa_handler = onStop;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

std::string duration(double s) {
  char text[32];
  if (s < 60) std::snprintf(text, sizeof text, "%.0f s", s);
  else if (s < 3600) std::snprintf(text, sizeof text, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else std::snprintf(text, sizeof text, "%.0f h %02.0f min", std::floor(s / 3600), std::fmod(s, 3600) / 60);
  return text;
}

// The cells to run now: not finished, or failed when asked to retry.
std::vector<std::uint64_t> cellsToRun(const SweepRequest& r, std::uint64_t* done, std::uint64_t* failed) {
  std::vector<std::uint64_t> todo;
  for (std::uint64_t i = 0; i < r.sweep.cellCount(); ++i) {
    const sweep::CellState s = sweep::stateOf(r.out, sweep::cellAt(r.sweep, i));
    if (s == sweep::CellState::Done) ++*done;
    else if (s == sweep::CellState::Failed && !r.retryFailed) ++*failed;
    else todo.push_back(i);
  }
  return todo;
}

int dryRun(const SweepRequest& r) {
  static const char* names[] = {"pending", "done", "failed", "stale"};
  for (std::uint64_t i = 0; i < r.sweep.cellCount(); ++i) {
    const sweep::Cell c = sweep::cellAt(r.sweep, i);
    std::cout << c.id << " [" << names[int(sweep::stateOf(r.out, c))] << "] millsim " << sweep::shellQuoted(c.args) << "\n";
  }
  std::cout << r.sweep.cellCount() << " cells; results in " << r.out.string() << "\n";
  return kExitOk;
}

int runLocal(const SweepRequest& r) {
  std::uint64_t done = 0, failed = 0;
  const std::vector<std::uint64_t> todo = cellsToRun(r, &done, &failed);
  const std::uint64_t total = r.sweep.cellCount();
  const unsigned jobs = r.jobs > 0 ? unsigned(r.jobs) : std::max(1u, std::thread::hardware_concurrency());
  std::cout << "sweep " << r.sweep.name << ": " << total << " cells, " << done << " done before, " << todo.size()
            << " to run here, " << jobs << " at once; results in " << r.out.string() << "\n";
  if (failed) std::cout << "  " << failed << " failed before and left so (--retry-failed runs them again)\n";
  fs::create_directories(r.out / "cells");
  const fs::path exe = millsimExecutable();
  catchStopSignals();
  struct Running {
    sweep::Cell cell;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0, interrupted = 0, ranHere = 0, failedHere = 0;
  double cellSeconds = 0.0;
  bool stopping = false;
  const bool tty = isatty(STDERR_FILENO);
  auto progress = [&] {
    const std::size_t left = todo.size() - ranHere - running.size();
    const double eta = ranHere ? cellSeconds / double(ranHere) * double(left + running.size()) / double(jobs) : NAN;
    char line[200];
    std::snprintf(line, sizeof line, "%zu/%zu cells run, %zu failed, %zu running, ETA %s", ranHere, todo.size(),
                  failedHere, running.size(), std::isnan(eta) ? "–" : duration(eta).c_str());
    std::cerr << (tty ? "\r\033[K" : "") << "sweep " << r.sweep.name << ": " << line << (tty ? "" : "\n") << std::flush;
  };
  while ((next < todo.size() && !stopping) || !running.empty()) {
    if (gStopSignal.load() && !stopping) {
      stopping = true;
      for (const auto& [pid, cell] : running) kill(pid, SIGTERM);
    }
    while (!stopping && next < todo.size() && running.size() < jobs) {
      const sweep::Cell cell = sweep::cellAt(r.sweep, todo[next++]);
      running.emplace(startCell(exe, cell, sweep::cellFolder(r.out, cell)), Running{cell, Clock::now()});
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const double seconds = std::chrono::duration<double>(Clock::now() - it->second.start).count();
    const int code = exitCodeOf(status);
    if (stopping && code > 128) {
      ++interrupted;  // stopped by us: no status, so it runs again next time
    } else {
      sweep::writeStatus(sweep::cellFolder(r.out, it->second.cell),
                         {code, seconds, sweep::hostName(), "local", sweep::shellQuoted(it->second.cell.args), sweep::utcNow()});
      ++ranHere, cellSeconds += seconds;
      if (code != 0) ++failedHere;
    }
    running.erase(it);
    progress();
  }
  if (tty) std::cerr << "\n";
  if (stopping) {
    std::cout << "interrupted (" << (gStopSignal.load() == SIGINT ? "Ctrl-C" : "SIGTERM") << "): " << ranHere
              << " cells finished here and kept, " << interrupted << " stopped, "
              << (todo.size() - ranHere) << " left; run the same command again to finish them\n";
    return 130;
  }
  return printSummary(std::cout, r);
}

// What a Slurm task (or a person) runs: one cell, its status written after.
int runCell(const SweepRequest& r) {
  const sweep::Cell cell = sweep::cellAt(r.sweep, r.cell);
  const fs::path folder = sweep::cellFolder(r.out, cell);
  catchStopSignals();
  const auto start = Clock::now();
  const pid_t pid = startCell(millsimExecutable(), cell, folder);
  int status = 0;
  bool forwarded = false;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
    // scancel sends SIGTERM to the task: the cell's command stops with it
    // and the status says so (a failed cell, which --retry-failed reruns).
    if (gStopSignal.load() && !forwarded) kill(pid, SIGTERM), forwarded = true;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const int code = exitCodeOf(status);
  const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const std::string executor = job && task ? std::string("slurm job ") + job + " task " + task : "cell";
  sweep::writeStatus(folder, {code, seconds, sweep::hostName(), executor, sweep::shellQuoted(cell.args), sweep::utcNow()});
  std::cout << "cell " << cell.id << ": exit " << code << " after " << seconds << " s on " << sweep::hostName() << "\n";
  return code == 0 ? kExitOk : kExitFailure;
}

}  // namespace

int runSweepRequest(const SweepRequest& r) {
  try {
    if (r.verb == "status") return printSummary(std::cout, r);
    if (r.verb == "collect") return collect(std::cout, r);
    if (r.verb == "cell") return runCell(r);
    if (r.dryRun) return dryRun(r);
    return r.slurm ? runSlurm(r) : runLocal(r);
  } catch (const std::exception& e) {
    std::cerr << "millsim sweep: error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace millsim::app
