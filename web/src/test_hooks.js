// `window.flagsim`: read-only state for browser tests (and the curious), in one place.
//
//   window.flagsim.connected, framesShown, shownFps, frame { id, width, height, hash, hashOk },
//     params, timeline, camera, lastAck, lastError, refreshes
//   window.flagsim.imageRGB()      -> a copy of the assembled RGB8 image (Uint8Array)
//   window.flagsim.frameHashHex()  -> XXH3-64 of that image, 16 hex digits (computed now)
//   window.flagsim.waitForFrame(predicate, timeoutMs) -> resolves with the first frame shown
//     (from now on) for which predicate(frame) holds; rejects after timeoutMs
//   window.flagsim.server   -> the prefix of the server steered ("" until chosen)
//   window.flagsim.servers  -> the newest /gateway/servers, read (null before the first)
//   window.flagsim.beside   -> the picture beside: null, or { prefix, framesShown (since it was
//     chosen), frame { id, width, height, step, hash, hashOk } }
//   window.flagsim.besideImageRGB() -> a copy of the picture beside, RGB8 (empty while closed)
//
// `page` is the page's live state, owned by main.js; nothing here changes it.

export function installTestHooks(page) {
  const waiters = new Set();
  const frame = () => ({
    id: page.image.frameId,
    width: page.image.width,
    height: page.image.height,
    step: page.image.step,
    hash: page.image.frameHash,
    hashOk: page.image.hashOk,
  });
  const hooks = {
    get connected() { return page.connection.connected; },
    get serverName() { return page.connection.serverInfo?.name ?? ""; },
    get framesShown() { return page.view.framesShown; },
    get shownFps() { return page.view.shownFps(); },
    get frame() { return frame(); },
    get params() { return page.params; },
    get timeline() { return page.timeline; },
    get camera() { return page.camera; },
    get state() { return page.state; },
    get status() { return page.status; },
    get lastAck() { return page.lastAck; },
    get lastError() { return page.lastError; },
    get refreshes() { return page.stream.refreshes; },
    get server() { return page.server; },
    get servers() { return page.servers; },
    get beside() { return page.beside.hookState(); },
    imageRGB: () => page.image.rgb.slice(),
    besideImageRGB: () => page.beside.imageRGB(),
    frameHashHex: () => page.hasher.hex(page.image.rgb),
    waitForFrame(predicate = () => true, timeoutMs = 10000) {
      return new Promise((resolve, reject) => {
        const waiter = { predicate, resolve, timer: 0 };
        waiter.timer = setTimeout(() => {
          waiters.delete(waiter);
          reject(new Error(`no matching frame within ${timeoutMs} ms`));
        }, timeoutMs);
        waiters.add(waiter);
      });
    },
  };
  Object.defineProperty(window, "flagsim", { value: Object.freeze(hooks), configurable: false });
  /// Called by main.js after each frame shown.
  return function frameShown() {
    const current = frame();
    for (const waiter of [...waiters]) {
      let matches = false;
      try {
        matches = Boolean(waiter.predicate(current));
      } catch (error) {
        matches = false;
      }
      if (!matches) continue;
      clearTimeout(waiter.timer);
      waiters.delete(waiter);
      waiter.resolve(current);
    }
  };
}
