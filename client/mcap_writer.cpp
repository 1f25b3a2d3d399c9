#include "client/mcap_writer.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace flagsim {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";  ///< 8 bytes, at both ends
enum Opcode : uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B, kSummaryOffset = 0x0E, kDataEnd = 0x0F,
};

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as MCAP and zlib compute it; `crc`
/// is the value so far (0 to start).
uint32_t Crc32(uint32_t crc, std::string_view bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> entries{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      entries[n] = c;
    }
    return entries;
  }();
  crc = ~crc;
  for (const unsigned char byte : bytes) crc = table[(crc ^ byte) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

/// Little-endian fields, appended to a record's content.
struct Fields {
  std::string bytes;
  template <class Integer>
  Fields& Int(Integer value) {
    for (size_t k = 0; k < sizeof(Integer); ++k) bytes += char((uint64_t(value) >> (8 * k)) & 0xFF);
    return *this;
  }
  Fields& String(std::string_view text) {  ///< also MCAP's bytes: a uint32 length, then them
    Int(uint32_t(text.size()));
    bytes.append(text);
    return *this;
  }
  Fields& Raw(std::string_view raw) {
    bytes.append(raw);
    return *this;
  }
};

/// opcode, content length (uint64), content.
std::string Record(Opcode opcode, const Fields& content) {
  Fields record;
  record.Int(uint8_t(opcode)).Int(uint64_t(content.bytes.size())).Raw(content.bytes);
  return record.bytes;
}

}  // namespace

McapWriter::McapWriter(const std::string& path, std::string_view profile, std::string_view library)
    : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  Emit(std::string(kMagic, 8));
  Emit(Record(kHeader, Fields().String(profile).String(library)));
}

McapWriter::~McapWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void McapWriter::Emit(const std::string& bytes) {
  if (!failed_ && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) failed_ = true;
  offset_ += bytes.size();
  data_crc_ = Crc32(data_crc_, bytes);
}

uint16_t McapWriter::AddSchema(std::string_view name, std::string_view encoding, std::string_view data) {
  const auto id = uint16_t(schema_records_.size() + 1);  // 0 means "no schema"
  schema_records_.push_back(Record(kSchema, Fields().Int(id).String(name).String(encoding).String(data)));
  chunk_ += schema_records_.back();  // a reader meets it before the messages that use it
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding) {
  const auto id = uint16_t(channel_records_.size());
  const std::string no_metadata(4, '\0');  // an empty map: its byte length, 0
  channel_records_.push_back(
      Record(kChannel, Fields().Int(id).Int(schema_id).String(topic).String(message_encoding).Raw(no_metadata)));
  chunk_ += channel_records_.back();
  return id;
}

// message => the open chunk, its offset there into the chunk's index of its channel
void McapWriter::Write(uint16_t channel_id, uint64_t log_time, uint64_t publish_time, std::string_view data) {
  const uint32_t sequence = uint32_t(channel_counts_[channel_id]++);
  chunk_index_[channel_id].emplace_back(log_time, chunk_.size());
  chunk_ += Record(kMessage, Fields().Int(channel_id).Int(sequence).Int(log_time).Int(publish_time).Raw(data));
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  start_time_ = std::min(start_time_, log_time);
  end_time_ = std::max(end_time_, log_time);
  ++message_count_;
  if (chunk_.size() >= kChunkBytes) FlushChunk();
}

// Chunk record, then a Message Index per channel in it; their places go into a Chunk Index.
void McapWriter::FlushChunk() {
  if (chunk_.empty()) return;
  ChunkIndex index;
  index.start_time = chunk_start_ == UINT64_MAX ? 0 : chunk_start_;
  index.end_time = chunk_end_;
  index.offset = offset_;
  index.size = chunk_.size();
  const std::string record = Record(kChunk, Fields()
                                                .Int(index.start_time)
                                                .Int(index.end_time)
                                                .Int(uint64_t(chunk_.size()))
                                                .Int(Crc32(0, chunk_))
                                                .String("")  // no compression
                                                .Int(uint64_t(chunk_.size()))
                                                .Raw(chunk_));
  index.length = record.size();
  Emit(record);
  const uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    Fields content;
    content.Int(channel).Int(uint32_t(entries.size() * 16));
    for (const auto& [time, offset] : entries) content.Int(time).Int(offset);
    index.message_index_offsets[channel] = offset_;
    Emit(Record(kMessageIndex, content));
  }
  index.message_index_length = offset_ - indexes_start;
  chunks_.push_back(index);
  chunk_.clear();
  chunk_index_.clear();
  chunk_start_ = UINT64_MAX;
  chunk_end_ = 0;
}

std::string McapWriter::Close() {
  if (file_ == nullptr) return "already closed";
  FlushChunk();
  Emit(Record(kDataEnd, Fields().Int(data_crc_)));

  // The summary, a group of records per opcode, each group's place in the summary offsets.
  const uint64_t summary_start = offset_;
  data_crc_ = 0;  // from here, the summary's CRC
  std::vector<std::string> offsets;
  const auto group = [&](Opcode opcode, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const uint64_t start = offset_;
    for (const std::string& record : records) Emit(record);
    offsets.push_back(Record(kSummaryOffset, Fields().Int(uint8_t(opcode)).Int(start).Int(offset_ - start)));
  };
  group(kSchema, schema_records_);
  group(kChannel, channel_records_);
  std::vector<std::string> chunk_indexes;
  for (const ChunkIndex& chunk : chunks_) {
    Fields offsets_map;
    for (const auto& [channel, offset] : chunk.message_index_offsets) offsets_map.Int(channel).Int(offset);
    chunk_indexes.push_back(Record(kChunkIndex, Fields()
                                                    .Int(chunk.start_time)
                                                    .Int(chunk.end_time)
                                                    .Int(chunk.offset)
                                                    .Int(chunk.length)
                                                    .String(offsets_map.bytes)
                                                    .Int(chunk.message_index_length)
                                                    .String("")
                                                    .Int(chunk.size)
                                                    .Int(chunk.size)));
  }
  group(kChunkIndex, chunk_indexes);
  Fields counts;
  for (const auto& [channel, count] : channel_counts_) counts.Int(channel).Int(count);
  group(kStatistics, {Record(kStatistics, Fields()
                                              .Int(message_count_)
                                              .Int(uint16_t(schema_records_.size()))
                                              .Int(uint32_t(channel_records_.size()))
                                              .Int(uint32_t(0))  // attachments
                                              .Int(uint32_t(0))  // metadata
                                              .Int(uint32_t(chunks_.size()))
                                              .Int(message_count_ > 0 ? start_time_ : 0)
                                              .Int(end_time_)
                                              .String(counts.bytes))});
  const uint64_t summary_offset_start = offset_;
  for (const std::string& offset : offsets) Emit(offset);

  // Footer: its CRC covers the summary and the footer up to the CRC itself.
  Fields footer;
  footer.Int(uint8_t(kFooter)).Int(uint64_t(8 + 8 + 4)).Int(summary_start).Int(summary_offset_start);
  const uint32_t summary_crc = Crc32(data_crc_, footer.bytes);
  footer.Int(summary_crc);
  Emit(footer.bytes);
  Emit(std::string(kMagic, 8));
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed_ || !closed) return path_ + ": could not be written whole: " + std::strerror(errno);
  return "";
}

}  // namespace flagsim
