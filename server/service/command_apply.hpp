// Commands as the session takes them: each command message turned into the session's terms and
// applied. The live intake (command_intake.hpp) and replay (replay.hpp) share these, so a
// journaled command does in a replay exactly what it did when it came.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flagsim/camera_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/model_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/time_command_t.hpp"
#include "flagsim/timeline_key_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "server/model/auto_model.hpp"
#include "server/service/design_assembly.hpp"
#include "server/service/session.hpp"

namespace flagsim {

constexpr size_t kMaxNameLength = 64;  ///< characters of a parameter name in a key

sim::WindSettings WindOf(const wind_command_t& command);
ParamChange ParamChangeOf(const param_command_t& command);
render::CameraMove CameraMoveOf(const camera_command_t& command);
/// The timeline edit a KEYFRAME command asks for; "" or what is wrong with it as sent (its
/// values are checked by the session).
std::string TimelineEditOf(const keyframe_command_t& command, TimelineEdit* edit);
/// A key from the wire; "" or what is wrong with it as sent. `law`: whether key.law is read.
std::string KeyOf(const timeline_key_t& message, bool law, sim::Keyframe* key);

/// The clock control a TIME command asks for; "" or what is wrong with its operation.
std::string TimeControlOf(const time_command_t& command, TimeControl* control);

/// auto's decision as the session takes it; "" or what is wrong with it as sent.
std::string ModelSwitchOf(const model_t& message, ModelSwitch* model);
/// The MODEL message journaling `decision`.
model_t ModelMessageOf(const model::ModelDecision& decision, int64_t utime);

/// Decodes `data` as the command type of `channel` (unprefixed: WIND, PARAM, CAMERA, KEYFRAME,
/// TIME, DESIGN, and MODEL, auto's decisions as the journal holds them; REFRESH changes nothing
/// here) and applies it to `session`. A DESIGN command is the piece that completed its file, which
/// `designs` holds. Returns "" or why it could not be decoded or was rejected (then the session
/// is unchanged).
std::string ApplyCommandBytes(const std::string& channel, const std::vector<uint8_t>& data, Session* session,
                              const DesignLibrary* designs = nullptr);

}  // namespace flagsim
