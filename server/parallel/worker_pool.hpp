// One pool of worker threads for every stage of the server: the physics, the rasterizer and the
// tile encoder all hand their loops to it, from any thread, at once (the simulation steps while
// the last frame is drawn and encoded).
//
//   Run(count, threads, body)   body(index, participant) for every index in [0, count), on the
//                               calling thread and at most threads - 1 workers, then returns;
//                               never on more threads than the machine has cores (more would
//                               take turns on them: at 3 and 4 threads on 2 cores a 128 x 96
//                               step took 1.3 times one thread's time)
//
// Each thread starts on a contiguous share of the indices of its own and claims them one at a
// time; the same share goes to the same participant in loop after loop, so a row of the flag is
// stepped, pushed out of the pole and summed on one core and stays in its cache. A thread out of
// work helps with another's share: at once if its participant has not come (a worker that is
// asleep or busy elsewhere), else only once that share has made no progress for kStallSeconds.
// So a worker that the kernel takes off its core (a busy neighbour process, the server's own
// publisher) holds back one index, not its whole share, while a worker a little behind keeps its
// rows: taking them at once moved a fifth of a 128 x 96 flag between cores every loop.
// Results do not depend on who ran what: a body writes only what its index owns, so a loop gives
// the same bits at any thread count.
//
// The caller always works through the indices itself, so a loop finishes even when every worker
// is busy elsewhere (and a body may run a loop of its own). Idle workers, and a caller waiting for
// a helper's last index, poll for kPollSeconds, yielding the core every few polls, then sleep:
// they never hold a core that another thread wants, and a loop that follows another within
// microseconds (a substep's stages) still finds the workers awake. An offer wakes sleeping
// workers only for the helpers that the polling ones do not already give.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "server/parallel/core_budget.hpp"

namespace flagsim {

class WorkerPool {
 public:
  /// body(index, participant): participant is 0 on the caller and 1 .. threads - 1 on the workers
  /// that joined this loop; no two threads share a participant at once (per-thread scratch).
  using Body = std::function<void(int index, int participant)>;

  /// The process's pool.
  static WorkerPool& Shared();

  WorkerPool() = default;
  ~WorkerPool();  ///< waits for the workers to finish what they run, then stops them
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Runs body on every index of [0, count) on at most `threads` threads (and cores); returns when
  /// all ran.
  /// body must not throw.
  void Run(int count, int threads, const Body& body);

  /// From now on, Threads() allows no more threads than the cores the machine's other processes
  /// leave free (core_budget.hpp): for a live server beside other work. Off at first, so that
  /// tests and benchmarks get the threads they ask for.
  void ShareFreeCoresOnly(bool on) { free_cores_only_.store(on); }
  /// The threads a stage that wants `wanted` is to use now: `wanted`, or fewer while other
  /// processes take cores (ShareFreeCoresOnly).
  int Threads(int wanted);

  static constexpr int kMaxWorkers = 63;
  static constexpr double kPollSeconds = 300e-6;  ///< s an idle worker polls before it sleeps
  /// s without progress after which a participant's share is taken from it
  static constexpr double kStallSeconds = 50e-6;

 private:
  struct Share;
  struct Loop;
  static constexpr int kSlots = 4;  ///< loops offered at once (the stages' loops, nested ones)

  int Offer(Loop* loop);
  void Withdraw(int slot);
  void AddWorkers(int wanted);
  void Drain(Loop* loop, int participant);
  void Help(Loop* loop, Share* share, int participant);
  void WaitForHelpers(const Loop& loop);
  void Work();
  Loop* TryJoin(int* participant);
  template <typename Joined>
  void Sleep(const Joined& joined);
  void Leave(Loop* loop);

  alignas(64) std::atomic<Loop*> offered_[kSlots] = {};  ///< loops that take helpers
  std::atomic<int> visitors_{0};          ///< workers between reading a slot and entering its loop
  std::atomic<unsigned> posted_{0};       ///< offers so far: a sleeping worker waits for it to move
  std::atomic<int> polling_workers_{0};   ///< idle and polling: Offer wakes sleepers only beyond them
  std::atomic<int> sleeping_workers_{0};  ///< on wake_: Offer notifies only if some are
  std::atomic<int> sleeping_callers_{0};  ///< on left_: Leave notifies only if some are
  std::atomic<int> worker_count_{0};
  std::atomic<bool> stopping_{false};
  std::atomic<bool> free_cores_only_{false};
  CoreBudget budget_{std::max(1, int(std::thread::hardware_concurrency()))};
  std::mutex mutex_;              ///< for sleeping, and for adding workers
  std::condition_variable wake_;  ///< sleeping workers: an offer, or stopping
  std::condition_variable left_;  ///< sleeping callers: a helper left a loop
  std::vector<std::thread> workers_;
};

/// body(i) for i in [0, count), shared among `threads` threads of the process's pool.
template <typename Body>
void ParallelFor(int count, int threads, const Body& body) {
  if (threads <= 1 || count <= 1) {
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  WorkerPool::Shared().Run(count, threads, [&body](int i, int) { body(i); });
}

/// body(i, participant) for i in [0, count); see WorkerPool::Body.
template <typename Body>
void ParallelForEachParticipant(int count, int threads, const Body& body) {
  if (threads <= 1 || count <= 1) {
    for (int i = 0; i < count; ++i) body(i, 0);
    return;
  }
  WorkerPool::Shared().Run(count, threads, body);
}

}  // namespace flagsim
