// A person's image arrives in pieces (design_piece_t): on DESIGN from a client, and on
// DESIGN_FILE from a server for its recordings. The pieces of each file are held by its digest
// until the file is whole, then the whole is checked against the digest.
//
//   piece => checked (name, digest, size within the limit, offset on the grid of PIECE_BYTES,
//   its length) => held => whole? => SHA-256 matches the digest? => the file's bytes
//
// At most kMaxFiles files are held part-way; a piece of another file drops the one touched
// longest ago. A piece held already is taken again and changes nothing (a retry).
#pragma once

#include <cstdint>
#include <list>
#include <map>
#include <string>
#include <vector>

#include "flagsim/design_piece_t.hpp"
#include "server/scene/design_file.hpp"

namespace flagsim {

class DesignAssembly {
 public:
  static constexpr size_t kMaxFiles = 4;

  struct Outcome {
    std::string problem;  ///< "" or what is wrong with the piece, or with the whole file
    bool whole = false;   ///< the file is complete and matches its digest: `bytes` hold it
    std::vector<uint8_t> bytes;
    int64_t held = 0;  ///< bytes of the file held so far
  };

  /// Takes one piece; a problem drops nothing held, except a whole file whose digest does not
  /// match (dropped, to be sent again).
  Outcome Add(const design_piece_t& piece);

 private:
  struct File {
    std::string name;
    std::vector<uint8_t> bytes;
    std::vector<bool> pieces;  ///< held, by index
    int64_t held = 0;
  };
  std::list<std::pair<std::string, File>> files_;  ///< by digest, the one touched last first
};

/// The design files a log holds (its DESIGN_FILE pieces), by digest: what a replay needs to
/// show a design again, and to read a checkpoint taken while one was in force.
class DesignLibrary {
 public:
  /// Takes a DESIGN_FILE piece; a file made whole is decoded and kept. "" or what is wrong.
  std::string Add(const design_piece_t& piece);
  /// The file with SHA-256 `digest`, or null.
  DesignFilePtr Find(const std::string& digest) const;

 private:
  DesignAssembly assembly_;
  std::map<std::string, DesignFilePtr> files_;
};

}  // namespace flagsim
