#pragma once
// Field: one typed, named X3D field of a node. A field declares itself once, in
// its node's class, with name, access, default and one line of documentation:
//
//   SFFloat tipRadius{this, "tipRadius", Access::InputOutput, 0.0015f,
//                     "Radius of the burr sphere (m).", Range::positive()};
//
// That declaration is the single table the parser, validation, `millsim nodes`
// and docs/nodes.md all read.
//
// Routes and lazy evaluation (as in H3DAPI): setting a field marks everything
// routed from it out of date; a field pulls its new value only when read. Fields
// belong to the scene thread; the haptic thread never touches them (it reads a
// compiled run instead: the VoxelScene, the algorithm and LoopSettings, see docs/architecture.md).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/FieldValues.h"

namespace millsim {

class Node;

struct RouteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Field {
public:
  Field(Node* owner, std::string_view name, Access access, std::string_view doc);
  virtual ~Field();
  Field(const Field&) = delete;
  Field& operator=(const Field&) = delete;

  std::string_view name() const { return name_; }
  std::string_view doc() const { return doc_; }
  Access access() const { return access_; }
  Node* owner() const { return owner_; }
  virtual FieldType type() const = 0;
  bool isNodeField() const { return type() == FieldType::SFNode || type() == FieldType::MFNode; }

  // X3D XML spelling of the value. setFromString throws ValueError with a message
  // naming what was expected.
  virtual void setFromString(std::string_view text) = 0;
  // The value as a scene file wrote it, in that file's units (its <unit>
  // statements): numbers of the field's Quantity, and rotation angles, are
  // converted to SI before the range check.
  virtual void setFromSceneText(std::string_view text, const UnitScale& /*units*/) { setFromString(text); }
  virtual std::string toString() const = 0;
  // Extra constraint shown in docs and checked on set ("> 0"); empty if none.
  virtual std::string constraint() const { return {}; }
  // The bounds every number of the value must meet; null for fields that take no numbers or declare none.
  virtual const Range* range() const { return nullptr; }

  // Routes. routeTo checks that types match and that access allows it.
  void routeTo(Field& destination);
  void unrouteTo(Field& destination);
  const std::vector<Field*>& routesOut() const { return out_; }
  const std::vector<Field*>& routesIn() const { return in_; }

  // Lazy evaluation state.
  bool upToDate() const { return !stale_; }
  std::uint64_t lastEvent() const { return lastEvent_; }  // global event order of the last change

protected:
  // Called after the stored value changed: stamps an event and marks routed fields stale.
  void changed();
  // Called by readers: brings a stale field up to date before its value is used.
  void refresh() const {
    if (stale_ && !pulling_) {
      auto* self = const_cast<Field*>(this);
      self->pulling_ = true;
      self->pull();
      self->pulling_ = false;
    }
  }
  // Recompute from the routes in. The default copies the value of the most recent source.
  virtual void pull();
  virtual void assignFrom(const Field& source) = 0;
  // Used by computed fields, which take inputs without being an X3D route destination.
  void addInput(Field& source);

  void markStale(std::uint64_t epoch);
  bool stale_ = false;
  bool pulling_ = false;  // breaks route cycles while a value is being pulled
  std::uint64_t lastEvent_ = 0;

private:
  Node* owner_;
  std::string_view name_;
  std::string_view doc_;
  Access access_;
  std::vector<Field*> out_;
  std::vector<Field*> in_;
  std::uint64_t markEpoch_ = 0;  // last propagation that visited this field
};

namespace detail {
// x scaled by f and rounded once: a float is taken as the decimal it was
// written as, so that 0.4 mm reads as 0.0004f, not 0.00040000002f.
template <class X> X scaled(X x, double f) {
  if constexpr (std::is_same_v<X, float>) return float(std::strtod(formatNumber(x).c_str(), nullptr) * f);
  else return X(x * f);
}
// Converts one value written in `units` to SI: the numbers of quantity `q`
// (only the last one for a plane equation, only the translation of a matrix),
// and a rotation's angle.
template <class T> void convertToSI(T& v, const Quantity& q, const UnitScale& units) {
  if constexpr (std::is_same_v<T, Rotation>) {
    v.angle = scaled(v.angle, units.angle);
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!(q.minusOneIsNone && v == T(-1))) v = scaled(v, units.factor(q));
  } else if constexpr (std::is_same_v<T, glm::vec2> || std::is_same_v<T, glm::vec3> ||
                       std::is_same_v<T, glm::vec4> || std::is_same_v<T, glm::dvec3>) {
    if (q.minusOneIsNone && v == T(-1)) return;
    const double f = units.factor(q);
    for (int i = q.lastOnly ? T::length() - 1 : 0; i < T::length(); ++i) v[i] = scaled(v[i], f);
  } else if constexpr (std::is_same_v<T, glm::mat4>) {
    const double f = units.factor(q);
    for (int col = q.translationOnly ? 3 : 0; col < 4; ++col)
      for (int row = 0; row < (q.translationOnly ? 3 : 4); ++row) v[col][row] = scaled(v[col][row], f);
  }
}
}  // namespace detail

// A single value of type T (SFFloat, SFVec3f, ...).
template <class T> class SField : public Field {
public:
  using value_type = T;
  SField(Node* owner, std::string_view name, Access access, T initial, std::string_view doc,
         std::optional<Range> range = std::nullopt)
      : Field(owner, name, access, doc), value_(std::move(initial)), range_(range) {}

  const T& get() const {
    refresh();
    return value_;
  }
  void set(T v) {
    check(v);
    value_ = std::move(v);
    stale_ = false;
    changed();
  }

  FieldType type() const override { return X3DValue<T>::sf; }
  void setFromString(std::string_view text) override { set(parseSingle<T>(text)); }
  void setFromSceneText(std::string_view text, const UnitScale& units) override {
    T v = parseSingle<T>(text);
    if (!units.si()) detail::convertToSI(v, range_ ? range_->quantity : Quantity{}, units);
    set(std::move(v));
  }
  std::string toString() const override {
    if constexpr (std::is_same_v<T, std::string>) {
      return get();
    } else {
      std::string s;
      X3DValue<T>::write(get(), s);
      return s;
    }
  }
  std::string constraint() const override { return range_ ? range_->str() : std::string(); }
  const Range* range() const override { return range_ ? &*range_ : nullptr; }

protected:
  void check(const T& v) const {
    validate(v);  // first: GCC 12 -O3 dropped asFloat's rounding below when this call came after it
    if (!range_) return;
    const Range r = storesFloats<T>() ? range_->asFloat() : *range_;
    X3DValue<T>::numbers(v, [&](double x) {
      if (!r.contains(x))
        throw ValueError("value " + formatComponent(x) + " is outside the expected range " + range_->str());
    });
  }
  // A constraint beyond the range that a field class adds (an invertible
  // matrix): throws ValueError saying what was expected.
  virtual void validate(const T&) const {}
  void assignFrom(const Field& source) override { value_ = static_cast<const SField&>(source).get(); }

  mutable T value_;
  std::optional<Range> range_;
};

// A list of values of type T (MFFloat, MFVec3f, MFString, ...).
template <class T> class MField : public Field {
public:
  using value_type = std::vector<T>;
  MField(Node* owner, std::string_view name, Access access, std::vector<T> initial, std::string_view doc,
         std::optional<Range> range = std::nullopt)
      : Field(owner, name, access, doc), value_(std::move(initial)), range_(range) {}

  const std::vector<T>& get() const {
    refresh();
    return value_;
  }
  void set(std::vector<T> v) {
    check(v);
    value_ = std::move(v);
    stale_ = false;
    changed();
  }

  FieldType type() const override { return X3DValue<T>::mf; }
  void setFromString(std::string_view text) override { set(parseMultiple<T>(text)); }
  void setFromSceneText(std::string_view text, const UnitScale& units) override {
    std::vector<T> v = parseMultiple<T>(text);
    if constexpr (!std::is_same_v<T, bool>)  // vector<bool> has no T& (and nothing to convert)
      if (!units.si())
        for (T& item : v) detail::convertToSI(item, range_ ? range_->quantity : Quantity{}, units);
    set(std::move(v));
  }
  std::string toString() const override {
    std::string s;
    const auto& v = get();
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) s += std::is_same_v<T, std::string> ? " " : ", ";
      X3DValue<T>::write(v[i], s);
    }
    return s;
  }
  std::string constraint() const override { return range_ ? range_->str() : std::string(); }
  const Range* range() const override { return range_ ? &*range_ : nullptr; }

protected:
  void check(const std::vector<T>& v) const {
    if (!range_) return;
    const Range r = storesFloats<T>() ? range_->asFloat() : *range_;
    for (std::size_t i = 0; i < v.size(); ++i)
      X3DValue<T>::numbers(v[i], [&](double x) {
        if (!r.contains(x))
          throw ValueError("item " + std::to_string(i + 1) + ": value " + formatComponent(x) +
                           " is outside the expected range " + range_->str());
      });
  }
  void assignFrom(const Field& source) override { value_ = static_cast<const MField&>(source).get(); }

  mutable std::vector<T> value_;
  std::optional<Range> range_;
};

using SFBool = SField<bool>;
using SFInt32 = SField<std::int32_t>;
using SFFloat = SField<float>;
using SFDouble = SField<double>;
using SFTime = SField<Time>;
using SFString = SField<std::string>;
using SFVec2f = SField<glm::vec2>;
using SFVec3f = SField<glm::vec3>;
using SFVec3d = SField<glm::dvec3>;
using SFVec4f = SField<glm::vec4>;
using SFRotation = SField<Rotation>;
using SFColor = SField<Color>;
using SFMatrix4f = SField<glm::mat4>;
using MFBool = MField<bool>;
using MFInt32 = MField<std::int32_t>;
using MFFloat = MField<float>;
using MFDouble = MField<double>;
using MFTime = MField<Time>;
using MFString = MField<std::string>;
using MFVec2f = MField<glm::vec2>;
using MFVec3f = MField<glm::vec3>;
using MFVec3d = MField<glm::dvec3>;
using MFVec4f = MField<glm::vec4>;
using MFRotation = MField<Rotation>;
using MFColor = MField<Color>;

// An outputOnly field whose value is computed from other fields, on demand:
// the function runs only when the field is read after one of its inputs changed.
template <class FieldT> class Computed : public FieldT {
public:
  using value_type = typename FieldT::value_type;
  template <class Fn>
  Computed(Node* owner, std::string_view name, std::string_view doc, std::initializer_list<Field*> inputs, Fn fn)
      : FieldT(owner, name, Access::OutputOnly, value_type{}, doc), fn_(std::move(fn)) {
    for (Field* f : inputs) this->addInput(*f);
    this->stale_ = true;
  }
  std::uint64_t computeCount() const { return computeCount_; }

protected:
  void pull() override {
    ++computeCount_;
    this->value_ = fn_();
    this->stale_ = false;
    std::uint64_t latest = 0;
    for (Field* f : this->routesIn()) latest = std::max(latest, f->lastEvent());
    this->lastEvent_ = latest;
  }

private:
  std::function<value_type()> fn_;
  std::uint64_t computeCount_ = 0;
};

}  // namespace millsim
