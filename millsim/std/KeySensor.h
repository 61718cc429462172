#pragma once
#include <string>

#include "millsim/core/NodeKinds.h"

namespace millsim {

// One key going down or up, as the window saw it.
struct KeyEvent {
  bool press = true;
  std::string character;  // the key's character ("a", "A", "1", " "); empty for an action or modifier key
  int actionKey = 0;      // X3D's codes: F1–F12 1–12, Home 13, End 14, PgUp 15, PgDn 16, Up 17, Down 18, Left 19, Right 20
  enum class Modifier { None, Shift, Control, Alt } modifier = Modifier::None;
};

// Keyboard input for the scene: the window's key presses and releases as X3D events.
class KeySensor : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString description{this, "description", Access::InputOutput, "", "A text for people. Accepted; not acted on by MillSim."};
  SFBool enabled{this, "enabled", Access::InputOutput, true, "Whether keys reach this sensor."};
  SFString keyPress{this, "keyPress", Access::OutputOnly, "", "The character of a key pressed (\"a\", \"A\", \" \")."};
  SFString keyRelease{this, "keyRelease", Access::OutputOnly, "", "The character of a key released."};
  SFInt32 actionKeyPress{this, "actionKeyPress", Access::OutputOnly, 0,
                         "An action key pressed: F1–F12 1–12, Home 13, End 14, PgUp 15, PgDn 16, arrows 17–20."};
  SFInt32 actionKeyRelease{this, "actionKeyRelease", Access::OutputOnly, 0, "An action key released (codes as actionKeyPress)."};
  SFBool shiftKey{this, "shiftKey", Access::OutputOnly, false, "TRUE when Shift goes down, FALSE when it comes up."};
  SFBool controlKey{this, "controlKey", Access::OutputOnly, false, "TRUE when Control goes down, FALSE when it comes up."};
  SFBool altKey{this, "altKey", Access::OutputOnly, false, "TRUE when Alt goes down, FALSE when it comes up."};
  SFBool isActive{this, "isActive", Access::OutputOnly, false, "TRUE when a key goes down, FALSE when it comes up."};

  // Sends the events of one key; true if it sent any (false when disabled).
  bool keyEvent(const KeyEvent& e);
};

}  // namespace millsim
