// millsim nodes [--markdown]: the node reference, from the field declarations.
#include <iostream>

#include "Commands.h"
#include "millsim/core/NodeDocs.h"
#include "millsim/core/NodeRegistry.h"

namespace millsim::app {

void addNodesCommand(CLI::App& app, int& result) {
  auto* cmd = app.add_subcommand("nodes", "List every node type with its fields (docs/nodes.md is --markdown)");
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "Print the reference as Markdown");
  cmd->callback([markdown, &result] {
    NodeRegistry registry = builtinRegistry();
    std::cout << (*markdown ? nodeReferenceMarkdown(registry) : nodeReferenceText(registry));
    result = kExitOk;
  });
}

}  // namespace millsim::app
