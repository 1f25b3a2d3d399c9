// A second picture beside the steered one: another server of the same gateway, to watch (no
// camera controls, no panels). It has a picture stream of its own, so its frames are hash-checked
// and its refreshes asked for as the first picture's are.
//
//   want("BETA_", list) --> the stage shown, its caption naming BETA_; "waiting" until the list
//       names it, then a ServerScope on BETA_'s path --/flag/tiles--> PictureStream
//       --> FrameImage (hash-checked) --> FrameView on this stage; `/BETA_/flag/refresh` as needed
//   follow(list)        --> the caption's status (live or gone, real time, frames a second)
//   close()             --> the scope closed (the gateway stops sending BETA_'s tiles), the stage
//       hidden; onChange("") for the page's address
import { el } from "./dom.js";
import { FrameImage } from "./frame_image.js";
import { FrameView } from "./frame_view.js";
import { PictureStream } from "./picture_stream.js";
import { describeServer, waitingForServer } from "./server_list.js";
import { ServerScope } from "./server_scope.js";

export class BesideView {
  /// `connection`: the gateway's Connection; `stage`: the (empty) element the picture fills;
  /// `onChange(prefix)`: the server watched now ("" once closed); `onProblem(text)`.
  constructor({ connection, hasher, stage, onChange, onProblem }) {
    this.connection = connection;
    this.hasher = hasher;
    this.stage = stage;
    this.onChange = onChange;
    this.onProblem = onProblem;
    this.prefix = "";  ///< the server watched, "" for none
    this.scope = null;
    this.image = null;
    this.framesShown = 0;  ///< frames shown since this server was chosen
    this.canvas = el("canvas", { width: 16, height: 9 });
    this.note = el("div", { class: "stage-empty" });
    this.hud = el("div", { class: "hud", "aria-live": "off" });
    this.name = el("span", { class: "caption-name" });
    this.status = el("span", { class: "caption-state" });
    const close = el("button", { type: "button", class: "caption-close", title: "stop watching this server", "aria-label": "Close", onclick: () => this.close() }, "×");
    stage.append(this.canvas, this.note, this.hud, el("div", { class: "caption" }, this.name, this.status, close));
    this.view = new FrameView({ stage, canvas: this.canvas, hud: this.hud });
  }

  /// Watches the server `prefix` from now on (another one watched before is dropped).
  want(prefix, servers) {
    this.end();
    this.prefix = prefix;
    this.framesShown = 0;
    this.image = new FrameImage(this.hasher);
    this.scope = new ServerScope(this.connection);
    this.scope.on("state", (connected) => this.showConnection(connected));
    new PictureStream({
      connection: this.scope, image: this.image, view: this.view,
      onFrame: () => this.onFrame(),
      onProblem: (text) => this.onProblem(`beside ${prefix}: ${text}`),
    });
    this.name.textContent = prefix;
    this.stage.classList.remove("has-frame");
    this.stage.hidden = false;
    this.follow(servers);
    this.onChange(prefix);
  }

  /// The newest `/gateway/servers` (null before the first): the server's path once it is
  /// listed, its status in the caption.
  follow(servers) {
    if (!this.scope) return;
    const entry = servers?.find((server) => server.prefix === this.prefix);
    if (entry && this.scope.path === null) this.scope.setPath(entry.path);
    this.status.textContent = entry ? `watching · ${describeServer(entry)}` : "watching · not served";
    this.note.textContent = !entry ? waitingForServer(servers, this.prefix)
      : entry.live ? "waiting for the first frame …" : `${this.prefix} is gone; waiting for it to come back …`;
  }

  onFrame() {
    this.framesShown += 1;
    this.stage.classList.add("has-frame");
  }

  showConnection(connected) {
    this.stage.classList.toggle("offline", !connected);
    if (!connected) this.note.textContent = "no connection to the gateway";
  }

  /// Each half second: the frames-shown rate over the picture falls when frames stop.
  tick() {
    if (this.scope) this.view.updateHud();
  }

  /// Stops watching: the stage hidden, the page told.
  close() {
    if (!this.prefix) return;
    this.end();
    this.onChange("");
  }

  end() {
    this.scope?.close();
    this.scope = null;
    this.image = null;
    this.prefix = "";
    this.stage.hidden = true;
    this.stage.classList.remove("has-frame", "offline");
    this.view.forget();
  }

  /// For the test hooks: a copy of the picture, RGB8 (empty while closed).
  imageRGB() {
    return this.image ? this.image.rgb.slice() : new Uint8Array(0);
  }

  /// For the test hooks: null while closed, else { prefix, framesShown, frame }.
  hookState() {
    if (!this.prefix) return null;
    const image = this.image;
    return {
      prefix: this.prefix,
      framesShown: this.framesShown,
      frame: { id: image.frameId, width: image.width, height: image.height, step: image.step, hash: image.frameHash, hashOk: image.hashOk },
    };
  }
}
