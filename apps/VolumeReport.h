#pragma once
#include <string>

#include "millsim/core/Scene.h"

namespace millsim::app {
std::string describeVolumes(const Scene& scene);
}
