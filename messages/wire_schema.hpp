// The layout of every flagsim LCM type, read from the .lcm sources, and a checker that walks
// received bytes against it before lcm-gen's decode touches them.
//
// Why: LCM 1.3.1's generated decode resizes each variable array to the length it reads from the
// wire before it checks that the bytes are there, so a hostile length allocates gigabytes.
// CheckWire() proves that every length fits in the bytes received; only then do we decode.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace flagsim::wire {

enum class Primitive { kInt8, kInt16, kInt32, kInt64, kFloat, kDouble, kBoolean, kByte, kString, kStruct };

/// One array dimension: a literal size, or the name of an earlier integer field of the struct.
struct Dimension {
  int64_t fixed_size = -1;  ///< >= 0 for `x[3]`
  std::string count_field;  ///< set for `x[num_x]`
};

struct Field {
  std::string name;
  Primitive type = Primitive::kInt8;
  std::string struct_name;            ///< for kStruct: the nested type, without package
  std::vector<Dimension> dimensions;  ///< empty for a scalar
};

struct StructLayout {
  std::string name;  ///< without package, e.g. "state_t"
  std::vector<Field> fields;
};

/// The layouts of a set of .lcm sources. Throws std::runtime_error on a syntax it does not know.
class Schema {
 public:
  /// `lcm_sources`: (name, .lcm text) pairs.
  explicit Schema(const std::vector<std::pair<std::string_view, std::string_view>>& lcm_sources);

  /// The schema of messages/*.lcm, built once.
  static const Schema& Flagsim();

  const StructLayout* Find(const std::string& type_name) const;

  /// Walks `size` bytes of an encoded `type_name` (starting with its 8-byte fingerprint).
  /// Returns "" when every length fits, strings hold no NUL but their last byte, booleans are
  /// 0 or 1, and the bytes end exactly with the message (so they re-encode to themselves);
  /// otherwise what is wrong, e.g. "names: 1000000 elements but 12 bytes left".
  std::string CheckWire(const std::string& type_name, const uint8_t* data, size_t size) const;

 private:
  std::map<std::string, StructLayout> layouts_;
};

/// (stem, text) of each messages/*.lcm, generated at build time.
const std::vector<std::pair<std::string_view, std::string_view>>& LcmSources();

}  // namespace flagsim::wire
