// A clock the test moves, for an in-process server that runs in real time on it: the server steps
// only as far as the test has moved the clock, so how many steps fall between two points of a test
// is the test's doing, never the machine's speed or load. A CommandClient on the same clock times
// out and resends on it too, so nothing in the exchange waits on the wall clock.
#pragma once

#include <functional>
#include <vector>

#include "server/service/server.hpp"

namespace flagsim::testing {

class SimulatedClock {
 public:
  double now() const { return now_; }
  /// The clock as ServerOptions::clock and CommandClient take it.
  std::function<double()> Reader() const {
    return [this] { return now_; };
  }
  /// Options for a server that steps in real time on this clock.
  ServerOptions ServerOnIt() const {
    ServerOptions options;
    options.fast = false;
    options.clock = Reader();
    return options;
  }
  /// Moves the clock on by one of `server`'s steps and runs one pass of its loop: one step (the
  /// accumulator's rounding may put it in the next pass instead, the same way every run).
  void Step(Server& server) {
    now_ += server.session().scene().sim.dt;
    server.Tick(now_);
  }
  /// As Step, for several servers of the same step that share the clock.
  void Step(const std::vector<Server*>& servers) {
    now_ += servers.front()->session().scene().sim.dt;
    for (Server* server : servers) server->Tick(now_);
  }
  /// Steps `server` until `done()` or `limit` s of the clock have passed; whether `done()`.
  template <class Done>
  bool StepUntil(Server& server, const Done& done, double limit = 60) {
    const double give_up = now_ + limit;
    while (!done() && now_ < give_up) Step(server);
    return done();
  }

 private:
  double now_ = 0;  ///< s
};

}  // namespace flagsim::testing
