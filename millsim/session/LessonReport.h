#pragma once
// The report of a run or replay (--report FILE.json) and `millsim report`,
// which prints one for a person. The scoring rule is docs/lessons.md's.
#include <string>
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
};

// score = 100 × the mean over targets of min(1, fraction), halved for each
// violated forbidden region; negative (written as null) without targets.
double lessonScore(const LessonReport& report);
// The JSON document (keys as issue 18 names them; volumes in mm³).
std::string reportJson(const LessonReport& report);
void writeReport(const std::string& path, const LessonReport& report);
// Reads a report back; throws std::runtime_error naming the file and the key.
LessonReport readReport(const std::string& path);
std::string describeReport(const LessonReport& report, bool markdown);

}  // namespace millsim
