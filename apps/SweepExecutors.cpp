#include "SweepExecutors.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
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

// The signals that stop a sweep, and SIGCHLD, are blocked while it runs and
// taken with sigtimedwait, so none is lost between two system calls (a
// handler's flag is missed when it is set just before waitpid blocks).
// Cells start with nothing blocked (startCell).
class StopSignals {
public:
  StopSignals() {
    sigemptyset(&set_);
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGCHLD}) sigaddset(&set_, s);
    // An inherited SIG_IGN for SIGCHLD would reap the cells behind our back.
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(SIGCHLD, &dfl, &oldChld_);
    sigprocmask(SIG_BLOCK, &set_, &old_);
  }
  ~StopSignals() {
    sigprocmask(SIG_SETMASK, &old_, nullptr);
    sigaction(SIGCHLD, &oldChld_, nullptr);
  }
  // Waits up to `ms` for a signal; returns a stop signal's number, else 0
  // (a child ended, or the time passed).
  int wait(int ms) {
    timespec t{ms / 1000, long(ms % 1000) * 1000000L};
    const int s = sigtimedwait(&set_, nullptr, &t);
    return s == SIGINT || s == SIGTERM || s == SIGHUP ? s : 0;
  }

private:
  sigset_t set_{}, old_{};
  struct sigaction oldChld_ {};
};

std::string duration(double s) {
  char text[32];
  if (s < 60) std::snprintf(text, sizeof text, "%.0f s", s);
  else if (s < 3600) std::snprintf(text, sizeof text, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else std::snprintf(text, sizeof text, "%.0f h %02.0f min", std::floor(s / 3600), std::fmod(s, 3600) / 60);
  return text;
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
  FolderLock lock(r.out);
  // Cells a Slurm job of this sweep still holds are not run here too.
  std::set<std::uint64_t> queued;
  try {
    queued = queuedCells(r);
  } catch (const std::exception&) {
    // No Slurm here.
  }
  const CellSelection selected = selectCells(r, queued);
  const std::vector<std::uint64_t>& toRun = selected.toRun;
  const std::uint64_t done = selected.done, failed = selected.failed;
  const std::uint64_t total = r.sweep.cellCount();
  const unsigned jobs = r.jobs > 0 ? unsigned(r.jobs) : std::max(1u, std::thread::hardware_concurrency());
  std::cout << "sweep " << r.sweep.name << ": " << total << " cells, " << done << " done before, " << toRun.size()
            << " to run here, " << jobs << " at once; results in " << r.out.string() << "\n";
  if (failed) std::cout << "  " << failed << " failed before and left so (--retry-failed runs them again)\n";
  if (!queued.empty()) std::cout << "  " << queued.size() << " in Slurm's queue, left to it\n";
  fs::create_directories(r.out / "cells");
  const fs::path exe = millsimExecutable();
  StopSignals signals;
  struct Running {
    sweep::Cell cell;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0, interrupted = 0, ranHere = 0, failedHere = 0;
  double cellSeconds = 0.0;
  int stopSignal = 0;
  const bool tty = isatty(STDERR_FILENO);
  auto progress = [&] {
    const std::size_t left = toRun.size() - ranHere - running.size();
    const double eta = ranHere ? cellSeconds / double(ranHere) * double(left + running.size()) / double(jobs) : NAN;
    char line[200];
    std::snprintf(line, sizeof line, "%zu/%zu cells run, %zu failed, %zu running, ETA %s", ranHere, toRun.size(),
                  failedHere, running.size(), std::isnan(eta) ? "–" : duration(eta).c_str());
    std::cerr << (tty ? "\r\033[K" : "") << "sweep " << r.sweep.name << ": " << line << (tty ? "" : "\n") << std::flush;
  };
  // Every cell's process group is signalled (a cell may have children), then reaped.
  auto stopAll = [&](int signal) {
    for (const auto& [pid, cell] : running) kill(-pid, signal);
  };
  try {
    while ((next < toRun.size() && !stopSignal) || !running.empty()) {
      while (!stopSignal && next < toRun.size() && running.size() < jobs) {
        const sweep::Cell cell = sweep::cellAt(r.sweep, toRun[next++]);
        running.emplace(startCell(exe, cell, sweep::cellFolder(r.out, cell), true), Running{cell, Clock::now()});
      }
      bool reaped = false;
      for (;;) {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, WNOHANG);
        if (pid <= 0) break;
        const auto it = running.find(pid);
        if (it == running.end()) continue;
        reaped = true;
        const double seconds = std::chrono::duration<double>(Clock::now() - it->second.start).count();
        const int code = exitCodeOf(status);
        if (stopSignal && code > 128) {
          ++interrupted;  // stopped by us: no status, so it runs again next time
        } else {
          sweep::writeStatus(sweep::cellFolder(r.out, it->second.cell),
                             {code, seconds, sweep::hostName(), "local", sweep::shellQuoted(it->second.cell.args),
                              sweep::utcNow()});
          ++ranHere, cellSeconds += seconds;
          if (code != 0) ++failedHere;
        }
        running.erase(it);
        progress();
      }
      if (reaped) continue;
      if (const int s = signals.wait(250)) {
        // The first stop signal ends the cells politely, a second at once.
        stopAll(stopSignal ? SIGKILL : SIGTERM);
        stopSignal = s;
      }
    }
  } catch (...) {
    // Leave no cell running without a sweep to record it.
    stopAll(SIGKILL);
    for (const auto& [pid, cell] : running) waitpid(pid, nullptr, 0);
    throw;
  }
  if (tty) std::cerr << "\n";
  if (stopSignal) {
    std::cout << "interrupted (" << (stopSignal == SIGINT ? "Ctrl-C" : stopSignal == SIGHUP ? "SIGHUP" : "SIGTERM")
              << "): " << ranHere << " cells finished here and kept, " << interrupted << " stopped, "
              << (toRun.size() - ranHere) << " left; run the same command again to finish them\n";
    return 130;
  }
  return printSummary(std::cout, r);
}

// What a Slurm task (or a person) runs: one cell, its status written after.
// A task started from a submission checks that the cell is still the one
// submitted (the sweep file or its glob may have changed meanwhile).
int runCell(const SweepRequest& r) {
  const sweep::Cell cell = sweep::cellAt(r.sweep, r.cell);
  const fs::path folder = sweep::cellFolder(r.out, cell);
  const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const std::string executor = job && task ? std::string("slurm job ") + job + " task " + task : "cell";
  if (!r.submitted.empty()) {
    const std::string expected = submittedCommand(r.submitted, r.cell);
    if (expected != sweep::shellQuoted(cell.args)) {
      std::cerr << "millsim sweep cell: cell " << cell.id << " is no longer the command submitted ("
                << (expected.empty() ? "it was not submitted" : expected) << "): the sweep file or a glob's files "
                << "changed since; not run\n";
      return kExitBadInput;
    }
  }
  StopSignals signals;
  const auto start = Clock::now();
  // In the task's own process group: Slurm's process tracking follows it.
  const pid_t pid = startCell(millsimExecutable(), cell, folder, false);
  int status = 0, code = -1;
  bool forwarded = false;
  while (code < 0) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) code = exitCodeOf(status);
    else if (done < 0) code = kExitFailure;  // lost the child: not a success
    // scancel sends SIGTERM to the task: the cell's command stops with it
    // and the status says so (a failed cell, which --retry-failed reruns).
    else if (signals.wait(250) && !forwarded) kill(pid, SIGTERM), forwarded = true;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  sweep::writeStatus(folder, {code, seconds, sweep::hostName(), executor, sweep::shellQuoted(cell.args), sweep::utcNow()});
  std::cout << "cell " << cell.id << ": exit " << code << " after " << seconds << " s on " << sweep::hostName() << "\n";
  return code == 0 ? kExitOk : kExitFailure;
}

}  // namespace

CellSelection selectCells(const SweepRequest& r, const std::set<std::uint64_t>& queued) {
  CellSelection c;
  for (std::uint64_t i = 0; i < r.sweep.cellCount(); ++i) {
    if (queued.count(i)) continue;
    const sweep::CellState s = sweep::stateOf(r.out, sweep::cellAt(r.sweep, i));
    if (s == sweep::CellState::Done) ++c.done;
    else if (s == sweep::CellState::Failed && !r.retryFailed) ++c.failed;
    else c.toRun.push_back(i);
  }
  return c;
}

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
