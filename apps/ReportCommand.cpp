// millsim report FILE.json [--markdown]: a run's or replay's report, for a person.
#include <iostream>
#include <memory>

#include "Commands.h"
#include "millsim/session/LessonReport.h"

namespace millsim::app {

void addReportCommand(CLI::App& app, int& result) {
  struct Args {
    std::string file;
    bool markdown = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("report", "Print the report a run or replay wrote with --report");
  cmd->add_option("file", args->file, "Report JSON file")->required();
  cmd->add_flag("--markdown", args->markdown, "Print it as Markdown");
  cmd->callback([args, &result] {
    try {
      std::cout << describeReport(readReport(args->file), args->markdown);
      result = kExitOk;
    } catch (const std::exception& e) {
      std::cerr << "millsim report: error: " << e.what() << "\n";
      result = kExitBadInput;
    }
  });
}

}  // namespace millsim::app
