#pragma once
#include "millsim/core/Scene.h"
