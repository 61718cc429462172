// millsim report FILE.json... [--markdown] [--csv CLASS.csv]: runs' and
// replays' reports, for a person, or a class's as one CSV row each.
#include <fstream>
#include <iostream>
#include <memory>

#include "Commands.h"
#include "millsim/session/LessonReport.h"

namespace millsim::app {

void addReportCommand(CLI::App& app, int& result) {
  struct Args {
    std::vector<std::string> files;
    bool markdown = false;
    std::string csv;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("report", "Print the reports runs or replays wrote with --report, or a class's as CSV");
  cmd->add_option("files", args->files, "Report JSON files")->required();
  cmd->add_flag("--markdown", args->markdown, "Print them as Markdown");
  cmd->add_option("--csv", args->csv,
                  "Write one row per report to this CSV (or - for standard output) instead of printing them");
  cmd->callback([args, &result] {
    result = kExitBadInput;
    std::vector<std::pair<std::string, LessonReport>> reports;
    try {
      for (const std::string& f : args->files) reports.emplace_back(f, readReport(f));
    } catch (const std::exception& e) {
      std::cerr << "millsim report: error: " << e.what() << "\n";
      return;
    }
    if (args->csv.empty()) {
      for (std::size_t i = 0; i < reports.size(); ++i)
        std::cout << (i ? "\n" : "") << describeReport(reports[i].second, args->markdown);
    } else if (args->csv == "-") {
      std::cout << reportsCsv(reports);
    } else {
      std::ofstream out(args->csv, std::ios::binary);
      out << reportsCsv(reports);
      out.close();
      if (!out) {
        std::cerr << "millsim report: error: " << args->csv << ": cannot write the CSV\n";
        return;
      }
      std::cout << "wrote " << reports.size() << " report" << (reports.size() == 1 ? "" : "s") << " to " << args->csv
                << "\n";
    }
    result = kExitOk;
  });
}

}  // namespace millsim::app
