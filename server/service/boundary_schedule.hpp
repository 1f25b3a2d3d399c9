// What falls due at a step boundary, on simulated time alone, for the live server and a render
// alike: which steps publish is part of the session, not of the machine's speed or of how it is
// driven, so a render of a scene publishes at the steps a live server of it would.
//
//   STATE   every 1/state_rate s (StateRate: once a second while the flag sleeps)
//   frame   every 1/frame_rate s
//
// Both first at time 0; a time half a step short of the due time counts, so that rounding in the
// sum of steps never moves a publication to the next step. (The periodic CHECKPOINT falls on step
// numbers: Journal::AtBoundary.)
#pragma once

#include "server/service/session.hpp"
#include "server/service/sim_cadence.hpp"

namespace flagsim {

struct BoundaryDue {
  bool state = false;  ///< a STATE
  bool frame = false;  ///< a frame
};

class BoundarySchedule {
 public:
  /// What is due at the session's current step boundary; call once at every boundary, the
  /// first (time 0) included.
  BoundaryDue At(const Session& session);

 private:
  SimCadence state_, frame_;
};

}  // namespace flagsim
