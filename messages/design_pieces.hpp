// A design file (a person's image) cut into the pieces DESIGN and DESIGN_FILE carry
// (design_piece_t): PIECE_BYTES each, the last what is left, each naming the whole file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flagsim/design_piece_t.hpp"

namespace flagsim {

/// The pieces of the file `bytes` named `name` with SHA-256 `digest` (hex), from `client_id`
/// (sequence, key and MAC left for the sender to fill).
std::vector<design_piece_t> SplitDesignFile(const std::string& name, const std::string& digest,
                                            const std::vector<uint8_t>& bytes, const std::string& client_id,
                                            int64_t utime);

}  // namespace flagsim
