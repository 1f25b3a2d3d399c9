#include "messages/wire_schema.hpp"

#include <cctype>
#include <cstring>
#include <stdexcept>

namespace flagsim::wire {
namespace {

// ---- parsing the .lcm language (the subset lcm-gen 1.3.1 accepts) ---------------------------

/// Splits .lcm text into identifiers, numbers and single punctuation characters, dropping
/// comments and whitespace.
std::vector<std::string> Tokenize(std::string_view text) {
  std::vector<std::string> tokens;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (text.substr(i, 2) == "//") {
      i = text.find('\n', i);
      if (i == std::string_view::npos) break;
    } else if (text.substr(i, 2) == "/*") {
      i = text.find("*/", i);
      if (i == std::string_view::npos) break;
      i += 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' || c == '+') {
      size_t end = i;
      while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_' ||
                                   text[end] == '.' || text[end] == '-' || text[end] == '+')) {
        ++end;
      }
      tokens.emplace_back(text.substr(i, end - i));
      i = end;
    } else {
      tokens.emplace_back(1, c);
      ++i;
    }
  }
  return tokens;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : tokens_(Tokenize(text)) {}

  /// Parses `package p; struct a { ... } struct b { ... }`.
  std::vector<StructLayout> ParseFile() {
    std::vector<StructLayout> layouts;
    while (!AtEnd()) {
      const std::string keyword = Next();
      if (keyword == "package") {
        Next();
        Expect(";");
      } else if (keyword == "struct") {
        layouts.push_back(ParseStruct());
      } else {
        throw std::runtime_error("lcm schema: unexpected '" + keyword + "'");
      }
    }
    return layouts;
  }

 private:
  StructLayout ParseStruct() {
    StructLayout layout;
    layout.name = Next();
    Expect("{");
    while (Peek() != "}") {
      if (Peek() == "const") {
        SkipConstant();
      } else {
        layout.fields.push_back(ParseField());
      }
    }
    Expect("}");
    return layout;
  }

  /// `const type NAME = value, NAME = value;` carries no bytes on the wire.
  void SkipConstant() {
    while (Next() != ";") {
    }
  }

  /// `type name;` or `type name[dim][dim];`
  Field ParseField() {
    Field field;
    SetType(Next(), &field);
    field.name = Next();
    while (Peek() == "[") {
      Next();
      const std::string size = Next();
      Dimension dimension;
      if (std::isdigit(static_cast<unsigned char>(size[0]))) {
        dimension.fixed_size = std::stoll(size);
      } else {
        dimension.count_field = size;
      }
      field.dimensions.push_back(dimension);
      Expect("]");
    }
    Expect(";");
    return field;
  }

  static void SetType(const std::string& name, Field* field) {
    static const std::map<std::string, Primitive> primitives = {
        {"int8_t", Primitive::kInt8},     {"int16_t", Primitive::kInt16}, {"int32_t", Primitive::kInt32},
        {"int64_t", Primitive::kInt64},   {"float", Primitive::kFloat},   {"double", Primitive::kDouble},
        {"boolean", Primitive::kBoolean}, {"byte", Primitive::kByte},     {"string", Primitive::kString}};
    if (const auto found = primitives.find(name); found != primitives.end()) {
      field->type = found->second;
      return;
    }
    field->type = Primitive::kStruct;
    const size_t dot = name.rfind('.');
    field->struct_name = dot == std::string::npos ? name : name.substr(dot + 1);
  }

  bool AtEnd() const { return position_ >= tokens_.size(); }
  const std::string& Peek() const {
    if (AtEnd()) throw std::runtime_error("lcm schema: unexpected end of file");
    return tokens_[position_];
  }
  std::string Next() {
    const std::string token = Peek();
    ++position_;
    return token;
  }
  void Expect(const std::string& token) {
    const std::string got = Next();
    if (got != token) throw std::runtime_error("lcm schema: expected '" + token + "', got '" + got + "'");
  }

  std::vector<std::string> tokens_;
  size_t position_ = 0;
};

// ---- walking encoded bytes --------------------------------------------------------------------

size_t FixedSize(Primitive type) {
  switch (type) {
    case Primitive::kInt8:
    case Primitive::kBoolean:
    case Primitive::kByte:
      return 1;
    case Primitive::kInt16:
      return 2;
    case Primitive::kInt32:
    case Primitive::kFloat:
      return 4;
    case Primitive::kInt64:
    case Primitive::kDouble:
      return 8;
    case Primitive::kString:
    case Primitive::kStruct:
      return 0;
  }
  return 0;
}

/// Reads an encoded message front to back. LCM's wire format: big-endian integers and floats;
/// a string is an int32 length (counting its terminating NUL) then the bytes; nested structs
/// carry no fingerprint; arrays are their elements back to back.
class Walker {
 public:
  Walker(const std::map<std::string, StructLayout>& layouts, const uint8_t* data, size_t size)
      : layouts_(layouts), data_(data), size_(size) {}

  std::string WalkMessage(const std::string& type_name) {
    if (size_ < 8) return "message is " + std::to_string(size_) + " bytes, shorter than a fingerprint";
    offset_ = 8;
    std::string error = WalkStruct(type_name, 0);
    if (error.empty() && offset_ != size_) {
      error = std::to_string(size_ - offset_) + " bytes left over after the message";
    }
    return error;
  }

 private:
  size_t Left() const { return size_ - offset_; }

  int64_t ReadInteger(size_t bytes) {
    uint64_t value = 0;
    for (size_t i = 0; i < bytes; ++i) value = (value << 8) | data_[offset_ + i];
    offset_ += bytes;
    const int shift = static_cast<int>(64 - 8 * bytes);  // sign-extend
    return shift == 0 ? static_cast<int64_t>(value) : static_cast<int64_t>(value << shift) >> shift;
  }

  std::string WalkStruct(const std::string& type_name, int depth) {
    const auto found = layouts_.find(type_name);
    if (found == layouts_.end()) return "unknown type " + type_name;
    if (depth > 8) return "types nested too deeply";
    std::map<std::string, int64_t> integers;  // this struct's integer fields, for array counts
    for (const Field& field : found->second.fields) {
      if (IsScalarInteger(field)) {  // may count a later array: remember it
        const size_t bytes = FixedSize(field.type);
        if (Left() < bytes) return field.name + ": truncated";
        integers[field.name] = ReadInteger(bytes);
        continue;
      }
      int64_t count = 1;
      for (const Dimension& dimension : field.dimensions) {
        int64_t length = dimension.fixed_size;
        if (length < 0) {
          const auto counted = integers.find(dimension.count_field);
          if (counted == integers.end()) return field.name + ": unknown count " + dimension.count_field;
          length = counted->second;
        }
        // Every element takes at least one byte, so a count past the bytes left is a lie.
        if (length < 0 || (length > 0 && count > static_cast<int64_t>(Left()) / length)) {
          return field.name + ": " + std::to_string(length) + " elements but " + std::to_string(Left()) +
                 " bytes left";
        }
        count *= length;
      }
      std::string error = WalkElements(field, count, depth);
      if (!error.empty()) return error;
    }
    return "";
  }

  static bool IsScalarInteger(const Field& field) {
    return field.dimensions.empty() && (field.type == Primitive::kInt8 || field.type == Primitive::kInt16 ||
                                        field.type == Primitive::kInt32 || field.type == Primitive::kInt64);
  }

  std::string WalkElements(const Field& field, int64_t count, int depth) {
    if (const size_t fixed = FixedSize(field.type); fixed > 0) {
      if (static_cast<uint64_t>(count) * fixed > Left()) {
        return field.name + ": needs " + std::to_string(count * fixed) + " bytes, " + std::to_string(Left()) +
               " left";
      }
      if (field.type == Primitive::kBoolean) {  // LCM writes 0 or 1; anything else is not ours
        for (int64_t i = 0; i < count; ++i) {
          if (data_[offset_ + i] > 1) return field.name + ": a boolean must be 0 or 1";
        }
      }
      offset_ += count * fixed;
      return "";
    }
    for (int64_t i = 0; i < count; ++i) {
      std::string error =
          field.type == Primitive::kString ? WalkString(field) : WalkStruct(field.struct_name, depth + 1);
      if (!error.empty()) return error;
    }
    return "";
  }

  std::string WalkString(const Field& field) {
    if (Left() < 4) return field.name + ": truncated string length";
    const int64_t length = ReadInteger(4);
    if (length < 1 || length > static_cast<int64_t>(Left())) {
      return field.name + ": string length " + std::to_string(length) + " with " + std::to_string(Left()) +
             " bytes left";
    }
    if (std::memchr(data_ + offset_, 0, length - 1) != nullptr || data_[offset_ + length - 1] != 0) {
      return field.name + ": a string must end at its one NUL";
    }
    offset_ += length;
    return "";
  }

  const std::map<std::string, StructLayout>& layouts_;
  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

}  // namespace

Schema::Schema(const std::vector<std::pair<std::string_view, std::string_view>>& lcm_sources) {
  for (const auto& [name, text] : lcm_sources) {
    for (StructLayout& layout : Parser(text).ParseFile()) {
      std::string name = layout.name;
      layouts_.emplace(std::move(name), std::move(layout));
    }
  }
}

const Schema& Schema::Flagsim() {
  static const Schema schema(LcmSources());
  return schema;
}

const StructLayout* Schema::Find(const std::string& type_name) const {
  const auto found = layouts_.find(type_name);
  return found == layouts_.end() ? nullptr : &found->second;
}

std::string Schema::CheckWire(const std::string& type_name, const uint8_t* data, size_t size) const {
  return Walker(layouts_, data, size).WalkMessage(type_name);
}

}  // namespace flagsim::wire
