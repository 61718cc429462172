#pragma once
// Fixture: core and std include each other (a cycle between folders).
#include "millsim/std/Group.h"
