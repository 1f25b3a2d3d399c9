// Wind: the chosen wind (dial + number boxes) and the wind now (from `/flag/state`).
//
//   dial pick / boxes --> chosen (vx, vy, vz), gust, ramp --Apply--> `/flag/wind`
//   /flag/state wind, wind_speed, wind_gust --> the dial's arrow and the "now" line
//
// The chosen wind starts as the wind now, until the user changes it.
import { el, formatNumber, numberInput } from "./dom.js";
import { WindDial } from "./wind_dial.js";

const kMaxSpeed = 60;  ///< m/s, the server's limit
const kMaxRamp = 60;   ///< s

export class WindPanel {
  constructor({ container, connection }) {
    this.connection = connection;
    this.touched = false;  // the user changed the chosen wind: the state no longer overwrites it
    this.shownWind = "";   // the wind now as last shown
    this.dial = new WindDial({ onPick: (vx, vz) => this.pick(vx, vz) });
    this.speed = numberInput({ min: 0, max: kMaxSpeed, step: 0.5, title: "ground-plane speed, m/s" });
    this.direction = numberInput({ min: -180, max: 360, step: 5, title: "direction in the ground plane, degrees from +x (along the flag) toward +z (across)" });
    this.up = numberInput({ min: -kMaxSpeed, max: kMaxSpeed, step: 0.5, value: 0, title: "vertical component, m/s (y up)" });
    this.gust = numberInput({ min: 0, max: 1, step: 0.05, value: 0, title: "gust strength: fraction of the speed, 0 .. 1" });
    this.ramp = numberInput({ min: 0, max: kMaxRamp, step: 0.5, value: 1, title: "seconds of simulated time to move from the wind now to this one" });
    this.now = el("div", { class: "readout" }, "wind now: –");
    this.result = el("div", { class: "result" });
    for (const box of [this.speed, this.direction, this.up, this.gust, this.ramp]) {
      box.addEventListener("input", () => this.onBoxes());
    }
    container.append(
      el("div", { class: "wind-layout" }, this.dial.element,
        el("div", { class: "form-grid wind-grid" },
          el("label", {}, "Speed"), this.speed, el("span", { class: "unit" }, "m/s"),
          el("label", {}, "Direction"), this.direction, el("span", { class: "unit" }, "°"),
          el("label", {}, "Up"), this.up, el("span", { class: "unit" }, "m/s"),
          el("label", {}, "Gust"), this.gust, el("span", { class: "unit" }, "0..1"),
          el("label", {}, "Ramp"), this.ramp, el("span", { class: "unit" }, "s"),
          el("span"), el("button", { type: "button", class: "primary", onclick: () => this.apply() }, "Apply"), el("span"))),
      this.now, this.result);
    this.setChosen(0, 0);
  }

  /// The dial picked (vx, vz): speed and direction follow.
  pick(vx, vz) {
    this.touched = true;
    this.setChosen(vx, vz);
  }

  setChosen(vx, vz) {
    this.speed.value = formatNumber(Math.hypot(vx, vz), 3);
    this.direction.value = formatNumber((Math.atan2(vz, vx) * 180) / Math.PI, 3);
    this.dial.setChosen(vx, vz);
  }

  /// Speed and direction typed: the dial follows.
  onBoxes() {
    this.touched = true;
    const [vx, , vz] = this.chosenVelocity();
    this.dial.setChosen(vx, vz);
  }

  /// [vx, vy, vz] m/s from the boxes.
  chosenVelocity() {
    const speed = Number(this.speed.value) || 0;
    const angle = ((Number(this.direction.value) || 0) * Math.PI) / 180;
    return [round(speed * Math.cos(angle)), Number(this.up.value) || 0, round(speed * Math.sin(angle))];
  }

  apply() {
    const request = { velocity: this.chosenVelocity(), gust: Number(this.gust.value) || 0, ramp: Number(this.ramp.value) || 0 };
    this.result.className = "result pending";
    this.result.textContent = "sending …";
    this.connection.call("/flag/wind", request).then(
      (answer) => this.showResult(answer?.accepted !== false, answer?.accepted === false ? answer.reason : `applied at step ${answer?.step ?? "?"}`),
      (error) => this.showResult(false, error.message),
    );
  }

  showResult(accepted, text) {
    this.result.className = `result ${accepted ? "ok" : "error"}`;
    this.result.textContent = text;
  }

  /// `/flag/state`: the wind now (the DOM only changes when it does).
  updateState(state) {
    const wind = state.wind ?? {};
    const [x, y, z] = [wind.x ?? 0, wind.y ?? 0, wind.z ?? 0];
    const key = `${x},${y},${z},${state.wind_gust}`;
    if (key === this.shownWind) return;
    this.shownWind = key;
    this.dial.setCurrent(x, z);
    const speed = state.wind_speed ?? Math.hypot(x, y, z);
    this.now.textContent = `wind now: (${formatNumber(x, 3)}, ${formatNumber(y, 3)}, ${formatNumber(z, 3)}) m/s · ${formatNumber(speed, 3)} m/s · gust ${formatNumber(state.wind_gust ?? 0, 2)}`;
    if (!this.touched) {
      this.setChosen(x, z);
      this.up.value = formatNumber(y, 3);
      this.gust.value = formatNumber(state.wind_gust ?? 0, 2);
    }
  }
}

/// To 1 mm/s, so a typed 6 m/s at 0 degrees sends exactly [6, vy, 0].
function round(value) {
  return Math.round(value * 1000) / 1000;
}
