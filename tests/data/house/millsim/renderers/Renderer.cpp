// Fixture: a renderer reaches the haptic loop.
#include "millsim/run/HapticLoop.h"
