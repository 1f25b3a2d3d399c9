#include "server/parallel/worker_pool.hpp"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace flagsim {
namespace {

/// A hint to the core that this thread is waiting.
inline void Pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

/// Polls between yields of the core (some microseconds of pauses). A yield is a system call, and
/// on a virtual machine a costly one: yielding every 64 polls made a 128 x 96 step without
/// self-collision on two threads 10-35 % slower in three paired runs (a whole flagd run of the
/// breeze with self-collision, 2.5 %), as offers waited for the yielding worker to come back.
constexpr int kPollsPerYield = 512;

/// Polls `done` for up to `seconds`, yielding the core every kPollsPerYield polls so that any
/// thread that wants it gets it; true if `done` came true.
template <typename Done>
bool PollFor(double seconds, const Done& done) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (int polls = 1;; ++polls) {
    if (done()) return true;
    Pause();
    if (polls % kPollsPerYield == 0) {
      if (std::chrono::steady_clock::now() >= until) return done();
      std::this_thread::yield();
    }
  }
}

}  // namespace

/// One participant's share of a loop's indices, [next, end), on a cache line of its own: each
/// thread claims from its own share without contention, then takes from the others'.
struct alignas(64) WorkerPool::Share {
  std::atomic<int> next{0};
  int end = 0;
  std::atomic<bool> owned{false};  ///< its participant has joined the loop

  /// The next index of this share, or -1 when none is left.
  int Claim() {
    if (next.load(std::memory_order_relaxed) >= end) return -1;
    const int index = next.fetch_add(1);
    return index < end ? index : -1;
  }
};

/// One call of Run: its indices in shares, who helps, and who is still inside.
struct WorkerPool::Loop {
  const Body* body = nullptr;
  int participants = 0;        ///< threads: the caller and its helpers
  std::atomic<int> joined{0};  ///< helpers that asked to join, including any turned away
  std::atomic<int> inside{0};  ///< helpers running indices of this loop
  Share shares[kMaxWorkers + 1];
};

WorkerPool& WorkerPool::Shared() {
  static WorkerPool pool;
  return pool;
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_.store(true);
    posted_.fetch_add(1);
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

int WorkerPool::Threads(int wanted) {
  if (wanted <= 1 || !free_cores_only_.load(std::memory_order_relaxed)) return wanted;
  const auto now = std::chrono::steady_clock::now().time_since_epoch();
  return std::min(wanted, budget_.Cores(std::chrono::duration<double>(now).count()));
}

// offer the loop => drain it here too => withdraw the offer => wait for the helpers inside
void WorkerPool::Run(int count, int threads, const Body& body) {
  static const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  const int participants = std::min({threads, count, kMaxWorkers + 1, cores});
  Loop loop;
  loop.body = &body;
  loop.participants = std::max(1, participants);
  for (int p = 0; p < loop.participants; ++p) {  // contiguous shares, as even as can be
    loop.shares[p].next.store(int(int64_t(count) * p / loop.participants), std::memory_order_relaxed);
    loop.shares[p].end = int(int64_t(count) * (p + 1) / loop.participants);
  }
  loop.shares[0].owned.store(true, std::memory_order_relaxed);
  const int slot = participants > 1 ? Offer(&loop) : -1;
  Drain(&loop, 0);
  if (slot < 0) return;
  Withdraw(slot);
  WaitForHelpers(loop);
}

// Puts the loop in a free slot and wakes sleeping workers; -1 if every slot is taken (then the
// caller runs the loop alone).
int WorkerPool::Offer(Loop* loop) {
  if (worker_count_.load() < loop->participants - 1) AddWorkers(loop->participants - 1);
  for (int slot = 0; slot < kSlots; ++slot) {
    Loop* empty = nullptr;
    if (!offered_[slot].compare_exchange_strong(empty, loop)) continue;
    posted_.fetch_add(1);
    // Wake sleepers only for the helpers that the polling workers do not already give: extra
    // workers woken for nothing would take the cores from the ones at work.
    const int short_of = loop->participants - 1 - polling_workers_.load();
    if (short_of > 0 && sleeping_workers_.load() > 0) {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (int k = 0; k < short_of; ++k) wake_.notify_one();
    }
    return slot;
  }
  return -1;
}

// After this no worker can still be about to join: one that read the slot before it was
// cleared is counted in visitors_ until it has either entered the loop or turned away.
void WorkerPool::Withdraw(int slot) {
  offered_[slot].store(nullptr);
  // A visitor is a few instructions from done, unless the kernel took its core: then yield.
  for (int polls = 1; visitors_.load() != 0; ++polls) {
    Pause();
    if (polls % 64 == 0) std::this_thread::yield();
  }
}

void WorkerPool::AddWorkers(int wanted) {
  const std::lock_guard<std::mutex> lock(mutex_);
  while (int(workers_.size()) < std::min(wanted, kMaxWorkers)) workers_.emplace_back([this] { Work(); });
  worker_count_.store(int(workers_.size()));
}

// Its own share first, then what is left of the others', each from the next one round.
void WorkerPool::Drain(Loop* loop, int participant) {
  Share& own = loop->shares[participant];
  for (int i = own.Claim(); i >= 0; i = own.Claim()) (*loop->body)(i, participant);
  for (int k = 1; k < loop->participants; ++k)
    Help(loop, &loop->shares[(participant + k) % loop->participants], participant);
}

// Another's share: taken at once if its participant has not come (it may never); left to it while
// it makes progress, so that its indices run where they ran in the last loop and their data stays
// in that core's cache; taken index by index once it has made none for kStallSeconds (the kernel
// took its core).
void WorkerPool::Help(Loop* loop, Share* share, int participant) {
  bool stalled = false;
  int seen = share->next.load(std::memory_order_relaxed);
  auto since = std::chrono::steady_clock::now();
  for (int polls = 1; share->next.load(std::memory_order_relaxed) < share->end; ++polls) {
    if (stalled || !share->owned.load(std::memory_order_acquire)) {
      const int i = share->Claim();
      if (i >= 0) (*loop->body)(i, participant);
      continue;
    }
    Pause();
    if (polls % 16 != 0) continue;
    const int now_next = share->next.load(std::memory_order_relaxed);
    const auto now = std::chrono::steady_clock::now();
    if (now_next != seen) {
      seen = now_next;
      since = now;
    } else if (now - since >= std::chrono::duration<double>(kStallSeconds)) {
      stalled = true;
    }
  }
}

// A helper still inside runs its last index, usually for microseconds: poll, then sleep.
void WorkerPool::WaitForHelpers(const Loop& loop) {
  const auto out = [&loop] { return loop.inside.load() == 0; };
  if (PollFor(kPollSeconds, out)) return;
  std::unique_lock<std::mutex> lock(mutex_);
  sleeping_callers_.fetch_add(1);
  left_.wait(lock, out);
  sleeping_callers_.fetch_sub(1);
}

// A worker: join an offered loop, drain it, leave; poll for the next offer a while (a substep's
// stages follow each other within microseconds), then sleep until one comes.
void WorkerPool::Work() {
  while (!stopping_.load()) {
    int participant = 0;
    Loop* loop = nullptr;
    const auto joined = [&] { return (loop = TryJoin(&participant)) != nullptr || stopping_.load(); };
    polling_workers_.fetch_add(1);
    const bool found = PollFor(kPollSeconds, joined);
    polling_workers_.fetch_sub(1);
    if (!found) Sleep(joined);
    if (loop == nullptr) continue;
    Drain(loop, participant);
    Leave(loop);
  }
}

// An offered loop with room for a helper, entered; null if none. visitors_ covers the moment
// between reading a slot and entering its loop (see Withdraw).
WorkerPool::Loop* WorkerPool::TryJoin(int* participant) {
  bool any = false;  // a plain look first: polling must not disturb the callers' cache lines
  for (int slot = 0; slot < kSlots; ++slot) any |= offered_[slot].load(std::memory_order_relaxed) != nullptr;
  if (!any) return nullptr;
  Loop* entered = nullptr;
  visitors_.fetch_add(1);
  for (int slot = 0; slot < kSlots && entered == nullptr; ++slot) {
    Loop* loop = offered_[slot].load();
    if (loop == nullptr) continue;
    const int helper = loop->joined.fetch_add(1) + 1;
    if (helper >= loop->participants) continue;  // full
    loop->inside.fetch_add(1);
    loop->shares[helper].owned.store(true, std::memory_order_release);
    *participant = helper;
    entered = loop;
  }
  visitors_.fetch_sub(1);
  return entered;
}

// Sleeps until a loop is offered (`joined` true) or the pool stops.
template <typename Joined>
void WorkerPool::Sleep(const Joined& joined) {
  std::unique_lock<std::mutex> lock(mutex_);
  sleeping_workers_.fetch_add(1);  // before looking: Offer sees it, or we see the offer
  // The offers counted before each look: a later one moves posted_ and ends the wait.
  for (unsigned seen = posted_.load(); !joined(); seen = posted_.load()) {
    wake_.wait(lock, [&] { return posted_.load() != seen; });
  }
  sleeping_workers_.fetch_sub(1);
}

// The loop may be gone the moment `inside` reaches 0: touch only the pool after that.
void WorkerPool::Leave(Loop* loop) {
  if (loop->inside.fetch_sub(1) != 1) return;
  if (sleeping_callers_.load() == 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  left_.notify_all();
}

}  // namespace flagsim
