#include "server/service/boundary_schedule.hpp"

#include "server/service/message_builders.hpp"

namespace flagsim {

BoundaryDue BoundarySchedule::At(const Session& session) {
  const double time = session.simulation().state().time, tolerance = session.scene().sim.dt / 2;
  BoundaryDue due;
  due.state = state_.Due(time, StateRate(session), tolerance);
  due.frame = frame_.Due(time, session.scene().service.frame_rate, tolerance);
  return due;
}

}  // namespace flagsim
