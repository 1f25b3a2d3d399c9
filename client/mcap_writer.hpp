// An MCAP file (mcap.dev/spec, major version 0), the log format Foxglove and Lichtblick open
// offline, written as its readers seek in it:
//
//   magic  Header  data: Schema and Channel records as they are added, then Chunks of messages,
//                  each followed by one Message Index per channel in it  DataEnd
//          summary: every Schema, Channel, one Chunk Index per chunk, Statistics
//          summary offsets: one per group of records in the summary  Footer  magic
//
// Chunks are uncompressed (the messages are JPEG and short JSON) and close at kChunkBytes.
// Every record is little-endian; the chunks, the data section and the summary carry CRC-32s.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace flagsim {

class McapWriter {
 public:
  static constexpr size_t kChunkBytes = 1 << 20;

  /// Creates `path`; throws std::runtime_error naming it and why if it cannot.
  McapWriter(const std::string& path, std::string_view profile = "", std::string_view library = "flagsim");
  ~McapWriter();  ///< closes the file as it stands if Close was not called (no summary)
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (e.g. "foxglove.CompressedImage", "jsonschema", its text); its id, from 1.
  uint16_t AddSchema(std::string_view name, std::string_view encoding, std::string_view data);
  /// A channel of messages in `message_encoding` ("json") with `schema_id`; its id, from 0.
  uint16_t AddChannel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding);
  /// One message on `channel_id`, at `log_time` (ns since the Unix epoch: when it was recorded)
  /// and `publish_time` (ns: when it was sent).
  void Write(uint16_t channel_id, uint64_t log_time, uint64_t publish_time, std::string_view data);
  /// The last chunk, the summary and the footer; "" or what went wrong writing the file.
  std::string Close();

 private:
  struct ChunkIndex {
    uint64_t start_time = 0, end_time = 0, offset = 0, length = 0;
    std::map<uint16_t, uint64_t> message_index_offsets;
    uint64_t message_index_length = 0, size = 0;
  };

  void Emit(const std::string& bytes);  ///< into the file, counted and into the running CRC
  void FlushChunk();

  std::FILE* file_ = nullptr;
  std::string path_;
  bool failed_ = false;
  uint64_t offset_ = 0;    ///< bytes written so far
  uint32_t data_crc_ = 0;  ///< CRC-32 of everything written, while in the data section
  std::vector<std::string> schema_records_, channel_records_;
  std::string chunk_;  ///< the open chunk's records
  uint64_t chunk_start_ = UINT64_MAX, chunk_end_ = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;  ///< channel => (time, offset in chunk)
  std::vector<ChunkIndex> chunks_;
  std::map<uint16_t, uint64_t> channel_counts_;
  uint64_t message_count_ = 0, start_time_ = UINT64_MAX, end_time_ = 0;
};

}  // namespace flagsim
