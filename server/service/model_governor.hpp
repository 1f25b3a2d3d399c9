// auto in the running server: when it decides, deciding beside the loop, and when a decision
// takes effect.
//
//   ask    at a step boundary, when none is in hand: every kPeriod s of simulated time (at the
//          steps that are multiples of it, so that a session resumed from a periodic checkpoint,
//          Journal::kCheckpointSteps, asks where the original did), and, at least kLeast s after
//          the last question, when what a frame shows changed (the session's revision: the
//          camera, the image size, the parameters, the wind; not auto's own switches). A snapshot, the camera and the
//          settings go to a thread of the governor's own, which runs DecideModels
//          (server/model/auto_model.hpp) beside the stepping. Not while the flag sleeps.
//   take   kLatency s of simulated time after asking, at that step boundary: the decision, which
//          the server applies (Session::ApplyModel) and journals in APPLIED (MODEL) when it
//          differs from the model in force in what auto may change there and then. If the thread is not done by then, the loop waits
//          for it: when a decision takes effect depends on the session alone, never on how fast
//          the machine was, so a run under a simulated clock is the same every time.
//
// The estimate of the model in force and what auto would choose were it free are kept for
// STATUS, also when the user has fixed both the integrator and the grid.
#pragma once

#include <cstdint>
#include <future>
#include <optional>

#include "server/model/auto_model.hpp"
#include "server/service/session.hpp"

namespace flagsim {

class ModelGovernor {
 public:
  static constexpr double kPeriod = 2.5;   ///< s, simulated, between questions while nothing changes
  static constexpr double kLatency = 0.5;  ///< s, simulated, from question to decision
  static constexpr double kLeast = 0.5;    ///< s, simulated, between questions at the least

  ~ModelGovernor();

  /// At each step boundary of `session`: asks when a question is due, and returns the decision
  /// whose turn has come, if it switches what auto may switch.
  std::optional<model::ModelDecision> AtBoundary(const Session& session);

  /// After the server switched to a decision: the switch is no change to ask about.
  void Switched(const Session& session) { asked_revision_ = session.revision(); }

  /// The last decisions taken; none before the first.
  const std::optional<model::ModelDecisions>& last() const { return last_; }

  /// auto's settings for `session`: what it may change, its budgets, the grids' shape.
  static model::AutoSettings SettingsOf(const Session& session);

 private:
  void Ask(const Session& session);
  static int64_t Steps(double seconds, const Session& session);

  std::future<model::ModelDecisions> pending_;
  int64_t due_step_ = -1;       ///< the boundary the pending decision takes effect at; -1: none
  int64_t earliest_question_ = 0;  ///< the step from which a question for a change may come
  int64_t asked_revision_ = -1; ///< the session's revision when last asked
  std::optional<model::ModelDecisions> last_;
};

}  // namespace flagsim
