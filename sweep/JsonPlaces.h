#pragma once
// JsonPlaces: a JSON document read with the line and column of every value
// and key, so that a sweep file's mistakes are reported where they are
// ("grid.json:7:15: unknown renderer 'Barbic'"). nlohmann's DOM keeps no
// positions; its SAX parser reads through an iterator that counts what it
// consumed, and each event is placed where its token ends.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace millsim::sweep {

struct Place {
  int line = 0, column = 0;  // 1-based
};

// "FILE:LINE:COLUMN: message": the error every reader of a sweep throws.
class SweepError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct JsonMember;

struct JsonValue {
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Kind kind = Kind::Null;
  Place at;
  bool boolean = false;
  double number = 0.0;
  bool integer = false;  // written without a fraction or exponent
  std::string text;      // a string's value; a number as written
  std::vector<JsonValue> items;                          // an array's
  std::vector<JsonMember> members;  // an object's, in file order
  std::vector<Place> keyPlaces;                          // where each member's key is

  const char* kindName() const;
};

// Not std::pair: a pair needs JsonValue complete, which it is not inside itself.
struct JsonMember {
  std::string first;  // the key
  JsonValue second;   // the value
};

// Throws SweepError "FILE:LINE:COLUMN: not JSON: ..." on a syntax error, and
// on a key given twice in one object.
JsonValue parseJsonWithPlaces(const std::string& text, const std::string& file);

}  // namespace millsim::sweep
