// The keyframe timeline: its keys on a scrubber, the position moving, and its controls, all
// through `/flag/keyframe`:
//
//   /flag/timeline --update--> markers, play state, loop, speed
//   /flag/state sim_time --tick--> the playhead (positionAt between messages)
//   click the bar --> seek (time);  play/pause, loop, speed --> play / pause / loop / speed
//   "Add key" --> add { time: position now, law, wind?, parameters?, camera? } from what the
//       panels show (the wind panel's chosen wind, checked as Apply checks it)
//   Play at the end of a timeline that does not loop --> seek 0, then play (from the start)
//   a marker --> selected: change its law (change, the controls kept) or remove it; the row for
//       it is always there (no layout jump), idle until a key is selected
import { el, formatNumber, numberInput, selectInput } from "./dom.js";
import { kLaws, positionAt } from "./timeline_model.js";

export class TimelinePanel {
  /// `current()` returns { wind, params, camera }: what the panels show, for a new key (wind:
  /// { request } or { problems }, as wind_form.js reads the wind panel).
  constructor({ container, connection, current, toast }) {
    this.connection = connection;
    this.current = current;
    this.toast = toast;
    this.timeline = null;
    this.simTime = null;
    this.selectedTime = null;  // s: the selected key's time, or null
    this.span = 10;            // s shown on the bar
    this.tickPending = false;  // a playhead update waits for the next animation frame
    this.keysShown = "";       // the span and keys the markers show, as JSON
    this.buildTransport();
    this.buildScrubber();
    this.buildKeyEditor();
    container.append(this.transport, this.bar, this.selectedRow);
  }

  buildTransport() {
    this.playButton = el("button", { type: "button", class: "play", onclick: () => this.togglePlay() }, "Play");
    this.loop = el("input", { type: "checkbox", onchange: () => this.send({ operation: "loop", loop: this.loop.checked }) });
    this.speed = numberInput({ min: 0.01, max: 100, step: 0.25, value: 1, title: "timeline seconds per simulated second" });
    this.speed.addEventListener("change", () => this.send({ operation: "speed", speed: Number(this.speed.value) }));
    this.positionText = el("span", { class: "readout timeline-position" }, "–");
    const clear = el("button", { type: "button", title: "remove every key", onclick: () => this.send({ operation: "clear" }) }, "Clear");
    this.clearButton = clear;
    this.transport = el("div", { class: "timeline-transport" }, el("h2", {}, "Timeline"), this.playButton,
      el("label", { class: "inline" }, this.loop, "Loop"),
      el("label", { class: "inline" }, "Speed", this.speed, "×"), this.positionText);
  }

  buildScrubber() {
    this.markers = el("div", { class: "timeline-markers" });
    this.ticks = el("div", { class: "timeline-ticks" });
    this.playhead = el("div", { class: "timeline-playhead" });
    this.bar = el("div", { class: "timeline-bar", title: "click to seek" }, this.ticks, this.markers, this.playhead);
    this.bar.addEventListener("click", (event) => {
      if (event.target.closest(".timeline-marker")) return;
      const box = this.bar.getBoundingClientRect();
      const time = Math.max(0, ((event.clientX - box.left) / box.width) * this.span);
      this.send({ operation: "seek", time: Number(time.toFixed(3)) });
    });
  }

  buildKeyEditor() {
    this.law = selectInput(kLaws, "smooth");
    this.setsWind = el("input", { type: "checkbox", checked: true });
    this.setsParameters = el("input", { type: "checkbox", checked: true });
    this.setsCamera = el("input", { type: "checkbox" });
    this.addButton = el("button", { type: "button", class: "primary", onclick: () => this.addKey() }, "Add key here");
    this.transport.append(el("span", { class: "timeline-add" }, this.addButton,
      el("span", { class: "muted" }, "sets"),
      el("label", { class: "inline" }, this.setsWind, "wind"),
      el("label", { class: "inline", title: "the animatable parameters: stiffness, damping, ..." }, this.setsParameters, "parameters"),
      el("label", { class: "inline" }, this.setsCamera, "camera"),
      el("label", { class: "inline" }, "law", this.law), this.clearButton));
    this.selectedLaw = selectInput(kLaws);
    this.selectedLaw.addEventListener("change", () => this.changeLaw());
    this.selectedText = el("span", { class: "selected-key-text" });
    const remove = el("button", { type: "button", class: "danger", onclick: () => this.removeKey() }, "Remove");
    this.removeButton = remove;
    this.selectedRow = el("div", { class: "timeline-selected idle" },
      this.selectedText, el("label", { class: "inline" }, "law", this.selectedLaw), remove);
  }

  send(request) {
    return this.connection.call("/flag/keyframe", request).then(
      (answer) => {
        if (answer?.accepted === false) this.toast(`Timeline: ${answer.reason}`);
        return answer;
      },
      (error) => this.toast(`Timeline: ${error.message}`),
    );
  }

  /// Play, or pause; at the end of a timeline that does not loop, play starts it again from 0.
  async togglePlay() {
    const timeline = this.timeline;
    if (timeline?.playing) {
      this.send({ operation: "pause" });
      return;
    }
    const atEnd = timeline && !timeline.loop && timeline.lastKeyTime > 0 &&
                  positionAt(timeline, this.simTime) >= timeline.lastKeyTime - 1e-9;
    if (atEnd) {
      const answer = await this.send({ operation: "seek", time: 0 });
      if (answer?.accepted === false) return;
      this.toast("Timeline: at its end; playing again from 0 s", "info");
    }
    this.send({ operation: "play" });
  }

  /// A key at the position now, setting what is ticked, from what the panels show.
  addKey() {
    const { wind, params, camera } = this.current();
    const key = { time: Number(positionAt(this.timeline, this.simTime).toFixed(3)), law: this.law.value };
    if (this.setsWind.checked && wind?.problems) {
      this.toast(`Timeline: the wind panel's ${wind.problems.map((p) => p.message).join("; ")}`);
      return;
    }
    if (this.setsWind.checked && wind?.request) {
      key.wind = { velocity: wind.request.velocity, gust: wind.request.gust };
    }
    if (this.setsParameters.checked && params) {
      key.parameters = Object.fromEntries(params.filter((p) => p.animatable).map((p) => [p.name, p.value]));
    }
    if (this.setsCamera.checked && camera?.eye) key.camera = { eye: camera.eye, target: camera.target, fov: camera.fov };
    if (!key.wind && !key.parameters && !key.camera) {
      this.toast("Timeline: tick what the key sets (wind, parameters or camera)");
      return;
    }
    this.selectedTime = key.time;
    this.send({ operation: "add", key });
  }

  changeLaw() {
    if (this.selectedTime === null) return;
    this.send({ operation: "change", key: { time: this.selectedTime, law: this.selectedLaw.value }, keep_law: false });
  }

  removeKey() {
    if (this.selectedTime === null) return;
    this.send({ operation: "remove", time: this.selectedTime });
    this.select(null);
  }

  select(time) {
    this.selectedTime = time;
    this.renderSelected();
    for (const marker of this.markers.children) marker.classList.toggle("selected", Number(marker.dataset.time) === time);
  }

  /// The newest `/flag/timeline` (as timeline_model.js reads it).
  update(timeline) {
    this.timeline = timeline;
    this.playButton.textContent = timeline.playing ? "Pause" : "Play";
    this.playButton.classList.toggle("playing", timeline.playing);
    this.loop.checked = timeline.loop;
    if (document.activeElement !== this.speed) this.speed.value = formatNumber(timeline.speed, 3);
    // Markers and ticks are rebuilt only when they change: a click on a marker must find it there.
    const span = niceSpan(Math.max(timeline.lastKeyTime, timeline.position, 4) * 1.05);
    const keysShown = JSON.stringify([span, timeline.keys]);
    if (keysShown !== this.keysShown) {
      this.keysShown = keysShown;
      this.span = span;
      this.renderTicks();
      this.renderMarkers();
    }
    if (this.selectedTime !== null && !timeline.keys.some((key) => key.time === this.selectedTime)) this.selectedTime = null;
    this.renderSelected();
    this.showPosition();
  }

  renderMarkers() {
    this.markers.replaceChildren(...this.timeline.keys.map((key) => {
      const marker = el("button", { type: "button", class: `timeline-marker law-${key.law}`, title: describeKey(key), dataset: { time: key.time } });
      marker.style.left = `${(key.time / this.span) * 100}%`;
      marker.classList.toggle("selected", key.time === this.selectedTime);
      marker.addEventListener("click", () => this.select(key.time));
      return marker;
    }));
  }

  renderTicks() {
    const step = niceSpan(this.span / 8);
    const ticks = [];
    for (let time = 0; time <= this.span + 1e-9; time += step) {
      const tick = el("span", { class: "timeline-tick" }, formatNumber(time, 3));
      tick.style.left = `${(time / this.span) * 100}%`;
      ticks.push(tick);
    }
    this.ticks.replaceChildren(...ticks);
  }

  renderSelected() {
    const key = this.timeline?.keys.find((each) => each.time === this.selectedTime);
    this.selectedRow.classList.toggle("idle", !key);
    this.selectedLaw.disabled = !key;
    this.removeButton.disabled = !key;
    if (!key) {
      setText(this.selectedText, "Select a key on the bar to see it, change its law or remove it.");
      this.selectedText.title = "";
      return;
    }
    this.selectedText.textContent = describeKey(key);
    this.selectedText.title = describeKey(key);
    this.selectedLaw.value = key.law;
  }

  /// The flag's time now (from `/flag/state`, which may come faster than the screen shows):
  /// the playhead moves at the next animation frame.
  tick(simTime) {
    this.simTime = simTime;
    if (this.tickPending) return;
    this.tickPending = true;
    requestAnimationFrame(() => {
      this.tickPending = false;
      this.showPosition();
    });
  }

  showPosition() {
    if (!this.timeline) return;
    const position = positionAt(this.timeline, this.simTime);
    const last = this.timeline.lastKeyTime;
    const ofLast = last > 0 ? ` / ${last.toFixed(2)}` : "";
    setText(this.positionText, `t = ${position.toFixed(2)}${ofLast} s${this.timeline.gliding ? " · gliding" : ""}`);
    setText(this.addButton, `Add key at ${position.toFixed(2)} s`);
    this.playhead.style.left = `${Math.min(100, (position / this.span) * 100).toFixed(2)}%`;
  }
}

/// Writes `text` only when it differs: no layout for what did not change.
function setText(element, text) {
  if (element.textContent !== text) element.textContent = text;
}

/// A key in words: "t 2 s · cubic · wind (1, 0, 9) m/s gust 0.3 · stiffness 5000".
export function describeKey(key) {
  const parts = [`t ${formatNumber(key.time, 4)} s`, key.law];
  if (key.wind) parts.push(`wind (${key.wind.velocity.map((v) => formatNumber(v, 3)).join(", ")}) m/s gust ${formatNumber(key.wind.gust, 2)}`);
  if (key.parameters) parts.push(Object.entries(key.parameters).map(([name, value]) => `${name} ${formatNumber(value, 4)}`).join(", "));
  if (key.camera) parts.push(`camera fov ${formatNumber(key.camera.fov, 3)}°`);
  return parts.join(" · ");
}

/// The smallest of 1, 2, 5 times a power of ten at or above `value`.
function niceSpan(value) {
  const power = 10 ** Math.floor(Math.log10(value));
  for (const factor of [1, 2, 5, 10]) if (factor * power >= value - 1e-12) return factor * power;
  return 10 * power;
}
