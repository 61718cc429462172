#pragma once
// The report of a run or replay (--report FILE.json) and `millsim report`,
// which prints one for a person. The scoring rule is docs/lessons.md's.
#include <string>
#include <utility>
#include <vector>

#include "millsim/lesson/RegionAccounting.h"

namespace millsim {

struct LessonReport {
  std::string scene, renderer;
  double duration = 0.0;     // s
  double removed = 0.0;      // m³
  double peakForce = 0.0;    // N
  double peakTorque = 0.0;   // N·m
  std::vector<RegionResult> regions;
  RemovalSummary removal;  // outside the targets, per tissue, time to completion
};

// score = 100 × the mean over targets of min(1, fraction), halved for each
// violated forbidden region, times max(0, 1 − overPreparationPenalty ×
// removal outside the targets / the targets' starting material); negative
// (written as null) without targets.
double lessonScore(const LessonReport& report);
// The JSON document (keys as issue 18 names them; volumes in mm³).
std::string reportJson(const LessonReport& report);
void writeReport(const std::string& path, const LessonReport& report);
// Reads a report back; throws std::runtime_error naming the file and the key.
LessonReport readReport(const std::string& path);
std::string describeReport(const LessonReport& report, bool markdown);
// A class's reports as CSV, one row per report (`millsim report --csv`):
// what a teacher's spreadsheet sorts by. The header names each column and its unit.
std::string reportsCsv(const std::vector<std::pair<std::string, LessonReport>>& reports);

}  // namespace millsim
