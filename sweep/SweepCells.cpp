#include "sweep/SweepCells.h"

#include <unistd.h>

#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace millsim::sweep {
namespace fs = std::filesystem;

fs::path defaultOutput(const Sweep& sweep) { return sweep.folder / (sweep.name + ".sweep"); }

fs::path cellFolder(const fs::path& out, const Cell& cell) { return out / "cells" / cell.id; }

std::string shellQuoted(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) {
    if (!s.empty()) s += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789-_./=:,+@%") == std::string::npos;
    if (plain) {
      s += a;
      continue;
    }
    s += '\'';
    for (const char c : a) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
    s += '\'';
  }
  return s;
}

std::optional<CellStatus> readStatus(const fs::path& folder) {
  std::ifstream in(folder / "status.json", std::ios::binary);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    CellStatus s;
    s.exitCode = j.at("exit").get<int>();
    s.seconds = j.at("seconds").get<double>();
    s.host = j.at("host").get<std::string>();
    s.executor = j.value("executor", "");
    s.command = j.at("command").get<std::string>();
    s.finished = j.value("finished", "");
    return s;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: as if it had not finished
  }
}

void writeStatus(const fs::path& folder, const CellStatus& s) {
  const nlohmann::json j{{"exit", s.exitCode},     {"seconds", s.seconds}, {"host", s.host},
                         {"executor", s.executor}, {"command", s.command}, {"finished", s.finished}};
  const fs::path tmp = folder / ("status.json.tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(tmp, std::ios::binary);
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    out.close();
    if (!out) throw std::runtime_error((folder / "status.json").string() + ": cannot write the cell's status");
  }
  fs::rename(tmp, folder / "status.json");
}

CellState stateOf(const fs::path& out, const Cell& cell, std::optional<CellStatus>* status) {
  std::optional<CellStatus> s = readStatus(cellFolder(out, cell));
  const CellState state = !s                                   ? CellState::Pending
                          : s->command != shellQuoted(cell.args) ? CellState::Stale
                          : s->exitCode == 0                     ? CellState::Done
                                                                 : CellState::Failed;
  if (status) *status = std::move(s);
  return state;
}

std::string hostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace millsim::sweep
