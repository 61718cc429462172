#include "millsim/core/FieldWatch.h"

#include <algorithm>

#include "millsim/core/Field.h"
#include "millsim/core/Node.h"

namespace millsim {

FieldWatch::FieldWatch(std::vector<Field*> fields) : fields_(std::move(fields)) { mark(); }

FieldWatch FieldWatch::ofNode(const Node& node) {
  const auto fields = node.fields();
  return FieldWatch(std::vector<Field*>(fields.begin(), fields.end()));
}

bool FieldWatch::changed() const {
  // A routed field is stale until read; a field set directly has a newer event.
  return std::any_of(fields_.begin(), fields_.end(),
                     [&](const Field* f) { return !f->upToDate() || f->lastEvent() > newest_; });
}

void FieldWatch::mark() {
  for (Field* f : fields_) {
    if (!f->upToDate()) (void)f->toString();  // a read pulls the routed value in
    newest_ = std::max(newest_, f->lastEvent());
  }
}

}  // namespace millsim
