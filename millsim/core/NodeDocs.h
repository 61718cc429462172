#pragma once
// The node reference, generated from the field declarations themselves:
// `millsim nodes` prints it and docs/nodes.md is this text (a test keeps it current).
#include <string>

#include "millsim/core/NodeRegistry.h"

namespace millsim {

std::string nodeReferenceMarkdown(const NodeRegistry& registry);
std::string nodeReferenceText(const NodeRegistry& registry);

}  // namespace millsim
