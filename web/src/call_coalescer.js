// One service call in flight at a time; what the user does meanwhile is merged, not queued.
//
//   push(op, request) --(nothing in flight)--> send(request) now
//                     --(a call in flight)---> merged into the one waiting slot for `op`
//   call answered --> the oldest waiting slot is sent, as one call
//
// So a fast drag or a spun wheel costs one call per round trip, and nothing piles up: at most
// one waiting request per operation.

export class CallCoalescer {
  /// `send(request)` returns a promise of the answer; `merge(waiting, next)` returns the request
  /// that does both (the default: the later one wins); `onAnswer(answer, request)` and
  /// `onError(error, request)` see each outcome.
  constructor({ send, merge = (_waiting, next) => next, onAnswer = () => {}, onError = () => {} }) {
    this.send = send;
    this.merge = merge;
    this.onAnswer = onAnswer;
    this.onError = onError;
    this.inFlight = false;
    this.waiting = new Map();  // op -> request, in the order first pushed
  }

  push(op, request) {
    const waiting = this.waiting.get(op);
    this.waiting.set(op, waiting ? this.merge(waiting, request) : request);
    if (!this.inFlight) this.sendNext();
  }

  /// Drops what waits (e.g. after a reset, earlier moves no longer mean anything).
  clear() {
    this.waiting.clear();
  }

  sendNext() {
    const next = this.waiting.entries().next();
    if (next.done) return;
    const [op, request] = next.value;
    this.waiting.delete(op);
    this.inFlight = true;
    Promise.resolve()
      .then(() => this.send(request))
      .then((answer) => this.onAnswer(answer, request), (error) => this.onError(error, request))
      .finally(() => {
        this.inFlight = false;
        this.sendNext();
      });
  }
}
