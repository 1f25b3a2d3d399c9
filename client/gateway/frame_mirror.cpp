#include "client/gateway/frame_mirror.hpp"

#include <cstring>

#include "client/gateway/foxglove_wire.hpp"

namespace flagsim::gateway {
namespace {

constexpr uint8_t kTileUpdateVersion = 1;
constexpr size_t kTileUpdateHeadBytes = 48;

void AppendI64(std::string* out, int64_t value) { AppendU64(out, static_cast<uint64_t>(value)); }

void AppendF64(std::string* out, double value) {
  uint64_t bits;
  static_assert(sizeof(bits) == sizeof(value));
  std::memcpy(&bits, &value, sizeof(bits));
  AppendU64(out, bits);
}

std::string UpdateHead(const MirroredFrame& frame, bool keyframe, uint32_t tiles) {
  std::string head;
  head.reserve(kTileUpdateHeadBytes);
  head.push_back(static_cast<char>(kTileUpdateVersion));
  head.push_back(static_cast<char>(keyframe ? 1 : 0));
  AppendU16(&head, static_cast<uint16_t>(frame.tile_size));
  AppendU32(&head, static_cast<uint32_t>(frame.width));
  AppendU32(&head, static_cast<uint32_t>(frame.height));
  AppendU32(&head, tiles);
  AppendI64(&head, frame.frame_id);
  AppendI64(&head, frame.step);
  AppendF64(&head, frame.sim_time);
  AppendU64(&head, frame.frame_hash);
  return head;
}

}  // namespace

std::string TileRecord(int index, const tile_t& tile) {
  std::string record;
  record.reserve(27 + tile.data.size());
  AppendU32(&record, static_cast<uint32_t>(index));
  for (int16_t value : {tile.x, tile.y, tile.width, tile.height})
    AppendU16(&record, static_cast<uint16_t>(value));
  record.push_back(static_cast<char>(tile.encoding));
  AppendU64(&record, static_cast<uint64_t>(tile.pixel_hash));
  AppendU32(&record, static_cast<uint32_t>(tile.data.size()));
  record.append(reinterpret_cast<const char*>(tile.data.data()), tile.data.size());
  return record;
}

FrameMirror::Result FrameMirror::AddManifest(const frame_t& manifest) {
  switch (assembler_.AddManifest(manifest)) {
    case TileAssembler::FrameResult::kComplete:
      Mirror(manifest);
      return Result::kComplete;
    case TileAssembler::FrameResult::kIncomplete:
      return Result::kIncomplete;
    default:
      return Result::kRefused;
  }
}

// Tiles whose pixels did not change keep the record the previous frame made of them.
// A tile never received (its pixels still the assembler's zeros, which the hash cannot tell
// from a black tile) has no record to resend: such a frame is not mirrored.
void FrameMirror::Mirror(const frame_t& manifest) {
  const std::vector<tile_t>& tiles = assembler_.placed_tiles();
  for (const tile_t& tile : tiles) {
    if (tile.frame_id < 0) return;
  }
  auto frame = std::make_shared<MirroredFrame>();
  frame->sequence = ++frames_;
  frame->utime = manifest.utime;
  frame->frame_id = manifest.frame_id;
  frame->step = manifest.step;
  frame->sim_time = manifest.sim_time;
  frame->width = manifest.width;
  frame->height = manifest.height;
  frame->tile_size = manifest.tile_size;
  frame->frame_hash = static_cast<uint64_t>(manifest.frame_hash);
  const bool same_grid = latest_ && latest_->width == frame->width && latest_->height == frame->height &&
                         latest_->tile_size == frame->tile_size;
  frame->tile_hashes.resize(tiles.size());
  frame->tile_records.resize(tiles.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    frame->tile_hashes[i] = static_cast<uint64_t>(tiles[i].pixel_hash);
    if (same_grid && latest_->tile_hashes[i] == frame->tile_hashes[i]) {
      frame->tile_records[i] = latest_->tile_records[i];
    } else {
      frame->tile_records[i] = std::make_shared<const std::string>(TileRecord(int(i), tiles[i]));
    }
  }
  if (keep_images_) frame->image = std::make_shared<const std::vector<uint8_t>>(assembler_.image());
  latest_ = std::move(frame);
}

void FrameMirror::ServerRestarted() {
  assembler_ = TileAssembler{};
  latest_.reset();
}

std::shared_ptr<const std::string> TileUpdateFor(const MirroredFrame& frame, ClientTiles* client) {
  if (client->sequence == frame.sequence) return nullptr;
  const bool keyframe = client->width != frame.width || client->height != frame.height ||
                        client->tile_size != frame.tile_size ||
                        client->hashes.size() != frame.tile_hashes.size();
  if (keyframe) client->hashes.assign(frame.tile_hashes.size(), 0);
  std::string body;
  uint32_t count = 0;
  for (size_t i = 0; i < frame.tile_hashes.size(); ++i) {
    if (!keyframe && client->hashes[i] == frame.tile_hashes[i]) continue;
    body += *frame.tile_records[i];
    client->hashes[i] = frame.tile_hashes[i];
    ++count;
  }
  client->sequence = frame.sequence;
  client->width = frame.width;
  client->height = frame.height;
  client->tile_size = frame.tile_size;
  return std::make_shared<const std::string>(UpdateHead(frame, keyframe, count) + body);
}

}  // namespace flagsim::gateway
