// A session snapshot on the wire (CHECKPOINT, checkpoint_t) and back. Every number travels as
// it is held (doubles as doubles, the flag's floats as floats), so a snapshot read back resumes
// the session bit for bit. Reading trusts nothing: a field out of its range, a count that does
// not match, an unknown parameter or a non-finite number is refused with the field named.
#pragma once

#include <cstdint>
#include <string>

#include "flagsim/checkpoint_t.hpp"
#include "server/service/design_assembly.hpp"
#include "server/service/session.hpp"

namespace flagsim {

/// `reason`: "start", "refresh", "periodic", "end" or "resume".
checkpoint_t MakeCheckpointMessage(const SessionSnapshot& snapshot, const std::string& reason, int64_t utime);

/// "" and `*snapshot` filled, or what is wrong with the message (then `*snapshot` is untouched).
/// A scene showing a person's image names it by digest: `designs` has to hold it.
std::string ReadCheckpoint(const checkpoint_t& message, SessionSnapshot* snapshot,
                           const DesignLibrary* designs = nullptr);

}  // namespace flagsim
