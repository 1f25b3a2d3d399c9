#include "server/service/design_assembly.hpp"

#include <algorithm>

#include "common/design_image.hpp"

namespace flagsim {
namespace {

constexpr int64_t kPiece = design_piece_t::PIECE_BYTES;

/// "" if the piece is one of a file within the limits, else what is wrong and what is allowed.
std::string CheckPiece(const design_piece_t& piece) {
  std::string problem = CheckDesignName(piece.name);
  if (!problem.empty()) return problem;
  const bool hex = piece.digest.size() == 64 &&
                   std::all_of(piece.digest.begin(), piece.digest.end(),
                               [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
  if (!hex) return "digest: allowed the file's SHA-256 as 64 lowercase hex digits";
  if (piece.total_bytes < 1 || size_t(piece.total_bytes) > kMaxDesignFileBytes)
    return "total_bytes: " + std::to_string(piece.total_bytes) + "; allowed: " + DesignLimits();
  if (piece.offset < 0 || piece.offset >= piece.total_bytes || piece.offset % kPiece != 0)
    return "offset: " + std::to_string(piece.offset) + "; allowed multiples of " + std::to_string(kPiece) +
           " below total_bytes " + std::to_string(piece.total_bytes);
  const int64_t length = std::min<int64_t>(kPiece, piece.total_bytes - piece.offset);
  if (piece.num_bytes != length)
    return "num_bytes: " + std::to_string(piece.num_bytes) + "; the piece at offset " +
           std::to_string(piece.offset) + " of a file of " + std::to_string(piece.total_bytes) +
           " bytes holds " + std::to_string(length);
  return "";
}

}  // namespace

DesignAssembly::Outcome DesignAssembly::Add(const design_piece_t& piece) {
  Outcome outcome;
  outcome.problem = CheckPiece(piece);
  if (!outcome.problem.empty()) return outcome;
  auto it = std::find_if(files_.begin(), files_.end(),
                         [&](const auto& entry) { return entry.first == piece.digest; });
  if (it == files_.end()) {
    if (files_.size() >= kMaxFiles) files_.pop_back();
    File file;
    file.name = piece.name;
    file.bytes.resize(size_t(piece.total_bytes));
    file.pieces.resize(size_t((piece.total_bytes + kPiece - 1) / kPiece));
    files_.emplace_front(piece.digest, std::move(file));
    it = files_.begin();
  } else {
    files_.splice(files_.begin(), files_, it);  // touched last
  }
  File& file = it->second;
  if (file.name != piece.name || int64_t(file.bytes.size()) != piece.total_bytes) {
    outcome.problem = "this piece says " + piece.name + " of " + std::to_string(piece.total_bytes) +
                      " bytes; earlier pieces with its digest said " + file.name + " of " +
                      std::to_string(file.bytes.size());
    return outcome;
  }
  const size_t index = size_t(piece.offset / kPiece);
  if (!file.pieces[index]) {
    std::copy(piece.data.begin(), piece.data.end(), file.bytes.begin() + piece.offset);
    file.pieces[index] = true;
    file.held += piece.num_bytes;
  }
  outcome.held = file.held;
  if (file.held < int64_t(file.bytes.size())) return outcome;
  const std::string digest = Sha256Hex(file.bytes.data(), file.bytes.size());
  if (digest != piece.digest) {
    outcome.problem = piece.name + ": the whole file's SHA-256 is " + digest +
                      ", not the digest its pieces carry (" + piece.digest +
                      "): a piece was damaged or mixed up; send the file again";
  } else {
    outcome.whole = true;
    outcome.bytes = std::move(file.bytes);
  }
  files_.erase(it);
  return outcome;
}

std::string DesignLibrary::Add(const design_piece_t& piece) {
  if (files_.count(piece.digest) > 0) return "";  // known already
  DesignAssembly::Outcome outcome = assembly_.Add(piece);
  if (!outcome.problem.empty() || !outcome.whole) return outcome.problem;
  DesignFilePtr file;
  const std::string problem = MakeDesignFile(piece.name, std::move(outcome.bytes), &file);
  if (!problem.empty()) return piece.name + ": " + problem;
  files_[piece.digest] = file;
  return "";
}

DesignFilePtr DesignLibrary::Find(const std::string& digest) const {
  const auto it = files_.find(digest);
  return it == files_.end() ? nullptr : it->second;
}

}  // namespace flagsim
