// The keyframe timeline: its keys on a scrubber, the position moving, and its controls, all
// through `/flag/keyframe`:
//
//   /flag/timeline --update--> markers, play state, loop, speed
//   /flag/state sim_time --tick--> the playhead (positionAt between messages)
//   click the bar --> seek (time);  play/pause, loop, speed --> play / pause / loop / speed
//   "Add key" --> add { time: position now, law, wind?, parameters?, camera? } from the controls now
//   a marker --> selected: change its law (change, the controls kept) or remove it
import { el, formatNumber, numberInput, selectInput } from "./dom.js";
import { kLaws, positionAt } from "./timeline_model.js";

export class TimelinePanel {
  /// `current()` returns { state, params, camera }: the newest of each, for a new key.
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
    this.selectedRow = el("div", { class: "timeline-selected", hidden: true },
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

  togglePlay() {
    this.send({ operation: this.timeline?.playing ? "pause" : "play" });
  }

  /// A key at the position now, setting what is ticked, from the controls now.
  addKey() {
    const { state, params, camera } = this.current();
    const key = { time: Number(positionAt(this.timeline, this.simTime).toFixed(3)), law: this.law.value };
    if (this.setsWind.checked && state?.wind) {
      key.wind = { velocity: [state.wind.x, state.wind.y, state.wind.z], gust: state.wind_gust ?? 0 };
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
    this.selectedRow.hidden = !key;
    if (!key) return;
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
