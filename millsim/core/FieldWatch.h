#pragma once
// FieldWatch: has any of these fields had an event since the last mark()?
// The scene thread's one change detector (the fields a run follows live, the
// renderer nodes a pool prepared, what graphics draws). It asks each field's
// global event order (Field::lastEvent) rather than comparing values, so a
// check costs a read per field and no string; a routed field whose source
// changed is stale until read, and counts as changed.
#include <cstdint>
#include <vector>

namespace millsim {

class Field;
class Node;

class FieldWatch {
public:
  FieldWatch() = default;
  // Starts marked: what the fields hold now is the baseline.
  explicit FieldWatch(std::vector<Field*> fields);
  // Every field of `node` (its type's table).
  static FieldWatch ofNode(const Node& node);
  bool changed() const;
  // Brings every watched field up to date (a stale routed field pulls its
  // value in) and remembers the newest event: the new baseline.
  void mark();
  bool empty() const { return fields_.empty(); }

private:
  std::vector<Field*> fields_;
  std::uint64_t newest_ = 0;
};

}  // namespace millsim
