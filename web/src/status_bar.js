// The status bar: connection, server, the model of the flag, frame id, frames shown per second,
// hash ok, last ACK.
//
//   connection state, serverInfo (and the server steered), /flag/status, each frame shown,
//   /flag/acks --> one line of fields
import { el, formatNumber } from "./dom.js";

export class StatusBar {
  constructor(container) {
    this.connection = el("span", { class: "field connection disconnected" }, "connecting …");
    this.server = el("span", { class: "field server" }, "–");
    this.model = el("span", { class: "field model" }, "model –");
    this.frame = el("span", { class: "field frame" }, "frame –");
    this.fps = el("span", { class: "field fps" }, "– fps");
    this.hash = el("span", { class: "field hash" }, "hash –");
    this.ack = el("span", { class: "field ack" }, "no ACK yet");
    container.append(this.connection, this.server, this.model, this.frame, this.fps, this.hash, this.ack);
  }

  /// `state`: "connected" (the gateway and a live server), "no-server" (the gateway without one)
  /// or "disconnected" (no gateway); `text` says which, and why.
  setConnection(state, text) {
    this.connection.className = `field connection ${state}`;
    this.connection.textContent = text;
  }

  /// The gateway's serverInfo name, after the prefix of the server steered when the gateway
  /// serves several ("" when it serves one).
  setServer(name, prefix = "") {
    this.server.textContent = prefix ? `${prefix} · ${name || "–"}` : name || "–";
    this.server.title = prefix ? `the server steered, ${prefix}; the gateway's serverInfo name: ${name}` : "the gateway's serverInfo name";
  }

  /// The model in force from a flagsim.Status: grid, integrator, substeps, auto's estimate of
  /// screen_error and the cost as a fraction of real time; auto's word in the tooltip.
  setModel(status) {
    const chooser = status.model_auto === "nothing" ? "set" : `auto: ${status.model_auto}`;
    const estimate = status.screen_error_px >= 0
      ? ` · ${formatNumber(status.screen_error_px, 2)} px · ${formatNumber(status.model_cost, 2)} of real time`
      : "";
    this.model.textContent =
      `${status.cols}×${status.rows} ${status.integrator} ×${status.substeps}${estimate} (${chooser})`;
    this.model.title = status.model_note ?? "";
    this.model.className = `field model ${/real time not held/.test(status.model_note ?? "") ? "bad" : ""}`;
  }

  /// The frame shown: its id, size, step and whether its hash checked.
  setFrame(image) {
    this.frame.textContent = `frame ${image.frameId} · ${image.width}×${image.height} · step ${image.step}`;
    this.hash.textContent = image.hashOk ? "hash ok" : "hash mismatch";
    this.hash.className = `field hash ${image.hashOk ? "ok" : "bad"}`;
    this.hash.title = `frame hash ${image.frameHash}`;
  }

  setFps(fps) {
    this.fps.textContent = `${formatNumber(fps, 3)} fps shown`;
  }

  /// A flagsim.Ack: { client_id, sequence, channel, accepted, reason, step }.
  setAck(ack) {
    const verdict = ack.accepted ? `accepted at step ${ack.step}` : `rejected: ${ack.reason}`;
    this.ack.textContent = `last ACK ${ack.channel} #${ack.sequence} ${verdict}`;
    this.ack.title = `${ack.client_id} #${ack.sequence} ${ack.channel}: ${ack.accepted ? "accepted" : "rejected"}${ack.reason ? ` (${ack.reason})` : ""}`;
    this.ack.className = `field ack ${ack.accepted ? "ok" : "bad"}`;
  }
}
