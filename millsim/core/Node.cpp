#include "millsim/core/Node.h"

namespace millsim {

Field* Node::field(std::string_view name) const {
  for (Field* f : fields_)
    if (f->name() == name) return f;
  return nullptr;
}

}  // namespace millsim
