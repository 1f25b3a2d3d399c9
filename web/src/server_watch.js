// Whether the server behind the gateway is there, from `/flag/status` (once a second) and the
// server id each one carries; the gateway's own connection is the page's other half:
//
//   waiting    connected, no STATUS yet
//   alive      a STATUS within the last kAliveWithin ms
//   gone       none for longer: the gateway is up, flagd is not (or not on this prefix)
//   restarted  a STATUS from a new server id, for kRestartShown ms; then alive
//
// A restart also calls `onRestart(newId, oldId)`: the new server's frames and time start again.

export const kAliveWithin = 2000;   ///< ms: STATUS comes once a second
export const kRestartShown = 5000;  ///< ms the restart is said for

export class ServerWatch {
  constructor({ now = () => performance.now(), onRestart = () => {} } = {}) {
    this.now = now;
    this.onRestart = onRestart;
    this.serverId = "";  ///< a string: 63 bits do not fit a JavaScript number
    this.lastStatus = -Infinity;
    this.restartedAt = -Infinity;
  }

  /// One flagsim.Status.
  onStatus(status) {
    const id = String(status?.server_id ?? "");
    const now = this.now();
    if (id && this.serverId && id !== this.serverId) {
      this.restartedAt = now;
      this.onRestart(id, this.serverId);
    }
    if (id) this.serverId = id;
    this.lastStatus = now;
  }

  /// The gateway's connection was lost: nothing is known of the server until it is back.
  onDisconnect() {
    this.lastStatus = -Infinity;
  }

  /// "waiting" | "alive" | "gone" | "restarted", as above.
  state() {
    const now = this.now();
    if (this.lastStatus === -Infinity) return this.serverId ? "gone" : "waiting";
    if (now - this.lastStatus > kAliveWithin) return "gone";
    if (now - this.restartedAt < kRestartShown) return "restarted";
    return "alive";
  }

  /// The state in words for the status bar.
  describe() {
    const state = this.state();
    switch (state) {
      case "waiting":
        return "waiting for the server's STATUS";
      case "gone":
        return this.lastStatus === -Infinity
          ? "server not heard"
          : `server gone: no STATUS for ${((this.now() - this.lastStatus) / 1000).toFixed(0)} s`;
      case "restarted":
        return "server restarted";
      default:
        return "server alive";
    }
  }
}
