// Wind: the chosen wind (dial + number boxes) and the wind now (from `/flag/state`).
//
//   dial pick / boxes --> chosen (vx, vy, vz), gust, ramp --Apply, if valid (wind_form.js)-->
//       `/flag/wind`; an invalid box is marked and named, nothing is sent
//   /flag/state wind, wind_speed, wind_gust --> the dial's arrow and the "now" line
//
// The chosen wind starts as the wind now, until the user changes it. A message about a box
// clears when that box changes.
import { el, formatNumber, numberInput } from "./dom.js";
import { WindDial } from "./wind_dial.js";
import { kMaxGust, kMaxRamp, kMaxWindSpeed, readWindForm } from "./wind_form.js";

export class WindPanel {
  constructor({ container, connection }) {
    this.connection = connection;
    this.touched = false;  // the user changed the chosen wind: the state no longer overwrites it
    this.shownWind = "";   // the wind now as last shown
    this.dial = new WindDial({ onPick: (vx, vz) => this.pick(vx, vz) });
    this.speed = numberInput({ min: 0, max: kMaxWindSpeed, step: 0.5, title: "ground-plane speed, m/s" });
    this.direction = numberInput({ min: -180, max: 360, step: 5, title: "direction in the ground plane, degrees from +x (along the flag) toward +z (across)" });
    this.up = numberInput({ min: -kMaxWindSpeed, max: kMaxWindSpeed, step: 0.5, value: 0, title: "vertical component, m/s (y up)" });
    this.gust = numberInput({ min: 0, max: kMaxGust, step: 0.05, value: 0, title: "gust strength: fraction of the speed, 0 .. 1" });
    this.ramp = numberInput({ min: 0, max: kMaxRamp, step: 0.5, value: 1, title: "seconds of simulated time to move from the wind now to this one" });
    this.now = el("div", { class: "readout" }, "wind now: –");
    this.result = el("div", { class: "result" });
    this.boxes = { speed: this.speed, direction: this.direction, up: this.up, gust: this.gust, ramp: this.ramp };
    for (const box of Object.values(this.boxes)) {
      box.addEventListener("input", () => this.onBoxes(box));
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

  /// A box typed in: its mark and any message about the boxes go; the dial follows a valid
  /// speed and direction.
  onBoxes(box) {
    this.touched = true;
    box.classList.remove("invalid");
    if (this.result.classList.contains("error")) this.showResult(true, "");
    const speed = Number(this.speed.value), degrees = Number(this.direction.value);
    if (this.speed.value.trim() === "" || this.direction.value.trim() === "" || !Number.isFinite(speed) || !Number.isFinite(degrees)) return;
    const angle = (degrees * Math.PI) / 180;
    this.dial.setChosen(speed * Math.cos(angle), speed * Math.sin(angle));
  }

  /// The boxes' texts, by field.
  texts() {
    return Object.fromEntries(Object.entries(this.boxes).map(([field, box]) => [field, box.value]));
  }

  /// The wind the panel shows, as Apply would send it: { request } or { problems }.
  chosenWind() {
    return readWindForm(this.texts());
  }

  apply() {
    const { request, problems } = this.chosenWind();
    if (problems) {
      for (const { field } of problems) this.boxes[field].classList.add("invalid");
      this.showResult(false, `not sent: ${problems.map((p) => p.message).join("; ")}`);
      return;
    }
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
