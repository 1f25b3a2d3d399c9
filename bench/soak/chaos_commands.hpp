// The soak's chaos: random commands of every kind a client may send (wind, parameters, camera
// moves, keyframe edits, resets, keyframe requests and questions), valid and invalid. Valid ones
// are drawn from a bounded region, the grids, steps, rates and image sizes a two-core machine
// holds in real time, so that the server owes each an answer in time; invalid ones break one rule
// each (a NaN, a value out of range, an unknown name or operation, a key that cannot be
// animated), so that the server owes each a rejection that changes nothing.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "flagsim/camera_command_t.hpp"
#include "flagsim/keyframe_command_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/wind_command_t.hpp"

namespace flagsim::soak {

enum class ChaosKind { kWind, kParameters, kCamera, kKeyframe, kReset, kKeyframeRequest, kQuestion };
constexpr int kChaosKinds = 7;
const char* ChaosKindName(ChaosKind kind);

using ChaosMessage =
    std::variant<wind_command_t, param_command_t, camera_command_t, keyframe_command_t, refresh_request_t>;

/// One command to send, and what it was drawn as.
struct ChaosCommand {
  ChaosKind kind;
  bool valid;        ///< from the valid region; false: it breaks a rule on purpose
  std::string what;  ///< a short description, for the report
  ChaosMessage message;
};

class ChaosCommands {
 public:
  /// `invalid_fraction` of the commands (0 .. 1) break a rule.
  ChaosCommands(uint64_t seed, double invalid_fraction);

  ChaosCommand Next();

 private:
  ChaosCommand Wind(bool valid);
  ChaosCommand Parameters(bool valid);
  ChaosCommand Camera(bool valid);
  ChaosCommand Keyframe(bool valid);
  ChaosCommand Reset();
  ChaosCommand KeyframeRequest(bool tables_only);

  double Uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random_);
  }
  int Integer(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  bool Chance(double p) { return Uniform(0, 1) < p; }
  /// A valid key at `time`: some of wind, animatable parameters and camera, and a law.
  timeline_key_t Key(double time);

  std::mt19937_64 random_;
  double invalid_fraction_;
  std::vector<double> key_times_;  ///< s: keys this client added (some may have gone since)
};

}  // namespace flagsim::soak
