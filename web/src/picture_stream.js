// The picture's data flow, from the wire to the screen:
//
//   /flag/tiles bytes --parseTileUpdate--> update --FrameImage.apply--> rgb + changed rects
//       --FrameView.show--> canvas;  onFrame(image, result) for the status bar, hooks, tools
//   a frame that cannot be completed --> `/flag/refresh` (one in flight, at most one a second):
//       the gateway's next update to this page is then a keyframe
//
// Subscribing to `/flag/tiles` brings a keyframe first, so joining needs no refresh.
import { parseTileUpdate } from "./tile_decoder.js";

const kMinRefreshGap = 1000;  ///< ms between two refresh requests

export class PictureStream {
  constructor({ connection, image, view, onFrame, onProblem }) {
    this.connection = connection;
    this.image = image;
    this.view = view;
    this.onFrame = onFrame;
    this.onProblem = onProblem;
    this.refreshInFlight = false;
    this.lastRefresh = -Infinity;
    this.refreshes = 0;  ///< refresh requests sent
    connection.subscribe("/flag/tiles");
    connection.on("message", (topic, data) => topic === "/flag/tiles" && this.receive(data));
    connection.on("state", (connected) => connected || this.onDisconnect());
  }

  /// One update: parsed, applied, shown; a keyframe asked for if the frame is not exact.
  receive(data) {
    let update;
    try {
      update = parseTileUpdate(data);
    } catch (error) {
      this.onProblem(`tile update refused: ${error.message}`);
      this.requestKeyframe(error.message);
      return;
    }
    const result = this.image.apply(update);
    if (result.problems.length > 0) this.onProblem(result.problems.join("; "));
    if (result.needKeyframe) this.requestKeyframe(result.problems[0] ?? "");
    if (!result.applied) return;
    this.view.show(this.image, result.rects);
    this.onFrame(this.image, result);
  }

  /// Asks the gateway for a keyframe (`/flag/refresh`), unless one is on its way or was asked
  /// for within the last second.
  requestKeyframe(reason) {
    const now = performance.now();
    if (this.refreshInFlight || now - this.lastRefresh < kMinRefreshGap || !this.connection.connected) return;
    this.refreshInFlight = true;
    this.lastRefresh = now;
    this.refreshes += 1;
    if (reason) this.onProblem(`keyframe requested: ${reason}`);
    this.connection.call("/flag/refresh", {}).catch((error) => this.onProblem(`/flag/refresh: ${error.message}`))
      .finally(() => (this.refreshInFlight = false));
  }

  /// After a reconnect the gateway starts this page afresh with a keyframe.
  onDisconnect() {
    this.image.started = false;
    this.refreshInFlight = false;
  }
}
