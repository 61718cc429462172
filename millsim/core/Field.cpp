#include "millsim/core/Field.h"

#include <algorithm>
#include <atomic>

#include "millsim/core/Node.h"

namespace millsim {

namespace {
// One clock for all fields so "the most recent event" is well defined across
// several routes into one field. Atomic only so that independent scenes on
// different threads (tests, tools) stay correct; a scene itself is single-threaded.
std::atomic<std::uint64_t> eventClock{0};
}  // namespace

Field::Field(Node* owner, std::string_view name, Access access, std::string_view doc)
    : owner_(owner), name_(name), doc_(doc), access_(access) {
  if (owner_) owner_->registerField(this);
}

Field::~Field() {
  for (Field* f : out_) std::erase(f->in_, this);
  for (Field* f : in_) std::erase(f->out_, this);
}

void Field::routeTo(Field& destination) {
  if (&destination == this) throw RouteError("a field cannot be routed to itself");
  if (destination.type() != type())
    throw RouteError("type mismatch: " + std::string(fieldTypeName(type())) + " cannot be routed to " +
                     std::string(fieldTypeName(destination.type())));
  if (!canRouteFrom(access()))
    throw RouteError("field '" + std::string(name()) + "' is " + std::string(accessName(access())) +
                     " and cannot send events (expected outputOnly or inputOutput)");
  if (!canRouteTo(destination.access()))
    throw RouteError("field '" + std::string(destination.name()) + "' is " +
                     std::string(accessName(destination.access())) +
                     " and cannot receive events (expected inputOnly or inputOutput)");
  if (std::find(out_.begin(), out_.end(), &destination) != out_.end())
    throw RouteError("this route already exists");
  out_.push_back(&destination);
  destination.in_.push_back(this);
  // As in H3DAPI, a new route delivers the current value: the destination
  // becomes stale and pulls on its next read (unless the source never sent an
  // event: an event node's output before its first event is no value, and
  // must not overwrite what the scene wrote, e.g. a Switch's whichChoice).
  destination.markStale(++eventClock);
}

void Field::addInput(Field& source) {
  source.out_.push_back(this);
  in_.push_back(&source);
}

void Field::unrouteTo(Field& destination) {
  std::erase(out_, &destination);
  std::erase(destination.in_, this);
}

void Field::changed() {
  const std::uint64_t epoch = ++eventClock;
  lastEvent_ = epoch;
  markEpoch_ = epoch;  // the origin of an event is never made stale by a route cycle
  for (Field* f : out_) f->markStale(epoch);
}

void Field::markStale(std::uint64_t epoch) {
  if (markEpoch_ == epoch) return;  // already visited in this propagation (route cycles)
  markEpoch_ = epoch;
  stale_ = true;
  for (Field* f : out_) f->markStale(epoch);
}

void Field::pull() {
  for (const Field* f : in_) f->refresh();  // sources first, so their event stamps are current
  const Field* newest = nullptr;
  for (const Field* f : in_)
    if (f->lastEvent() > 0 && (!newest || f->lastEvent() > newest->lastEvent())) newest = f;
  if (newest) {
    assignFrom(*newest);
    lastEvent_ = newest->lastEvent();
  }
  stale_ = false;
}

}  // namespace millsim
