// How the fuzz targets that take several messages read their input: records back to back, each
//
//   selector (1 byte) | length (2 bytes, little-endian) | that many bytes
//
// The selector picks what the bytes are (a channel, a kind of frame); the last record takes
// what is left when fewer bytes follow than its length claims, so every input means something.
// The corpus generator writes seeds in the same form (EncodeRecord).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace flagsim::fuzz {

struct Record {
  uint8_t selector = 0;
  const uint8_t* data = nullptr;
  size_t size = 0;
};

class Records {
 public:
  Records(const uint8_t* data, size_t size) : data_(data), left_(size) {}

  /// The next record; false once the input is used up.
  bool Next(Record* record) {
    if (left_ == 0) return false;
    record->selector = data_[0];
    const size_t claimed = left_ >= 3 ? size_t(data_[1]) | size_t(data_[2]) << 8 : 0;
    const size_t head = left_ >= 3 ? 3 : left_;
    record->data = data_ + head;
    record->size = std::min(claimed, left_ - head);
    data_ += head + record->size;
    left_ -= head + record->size;
    return true;
  }

 private:
  const uint8_t* data_;
  size_t left_;
};

/// One record's bytes, as Records reads them back (at most 65535 bytes of `bytes`).
inline std::vector<uint8_t> EncodeRecord(uint8_t selector, const std::vector<uint8_t>& bytes) {
  const size_t size = std::min<size_t>(bytes.size(), 0xffff);
  std::vector<uint8_t> record(3 + size);
  record[0] = selector;
  record[1] = uint8_t(size & 0xff);
  record[2] = uint8_t(size >> 8);
  std::copy_n(bytes.begin(), size, record.begin() + 3);
  return record;
}

}  // namespace flagsim::fuzz
