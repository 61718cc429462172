#include "millsim/std/KeySensor.h"

namespace millsim {

const NodeType& KeySensor::type() {
  static const NodeType t = makeNodeType<KeySensor>(
      "KeySensor", "children", "KeyDeviceSensor",
      "Keys pressed in the `millsim run` window, as events (every enabled KeySensor sees every key; the window's "
      "own keys keep their meaning too). Characters are what the key prints, upper case with Shift.");
  return t;
}

bool KeySensor::keyEvent(const KeyEvent& e) {
  if (!enabled.get()) return false;
  switch (e.modifier) {
    case KeyEvent::Modifier::Shift: shiftKey.set(e.press); break;
    case KeyEvent::Modifier::Control: controlKey.set(e.press); break;
    case KeyEvent::Modifier::Alt: altKey.set(e.press); break;
    case KeyEvent::Modifier::None: break;
  }
  if (!e.character.empty()) (e.press ? keyPress : keyRelease).set(e.character);
  if (e.actionKey > 0) (e.press ? actionKeyPress : actionKeyRelease).set(e.actionKey);
  isActive.set(e.press);
  return true;
}

}  // namespace millsim
