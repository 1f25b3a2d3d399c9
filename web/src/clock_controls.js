// The simulation's clock on the page: pause and resume, a step of N steps, the speed.
//
//   Pause/Resume, the space bar        --> /flag/time pause | resume
//   Step N                             --> /flag/time step { steps } (then paused)
//   Speed (0.1× .. 4×)                 --> /flag/set { time_scale }
//   /flag/status                       --> the button's word, the readout, the speed shown
// Frames go on while paused: camera moves and parameters still show.
import { el, numberInput, selectInput } from "./dom.js";
import { kMaxSteps, kTimeScales, readClock, readSteps } from "./clock_state.js";

export class ClockControls {
  constructor({ container, connection, toast }) {
    this.connection = connection;
    this.toast = toast;
    this.paused = false;
    this.pauseButton = el("button", { type: "button", class: "pause", title: "hold the flag still (space bar); frames go on", onclick: () => this.togglePause() }, "Pause");
    this.steps = numberInput({ min: 1, max: kMaxSteps, step: 1, value: 1, title: "steps of dt to take, then paused" });
    this.steps.classList.add("steps");
    this.steps.addEventListener("input", () => this.steps.classList.remove("invalid"));
    const step = el("button", { type: "button", title: "take this many steps, then stay paused", onclick: () => this.step() }, "Step");
    this.speed = selectInput(kTimeScales.map((scale) => [String(scale), `${scale}×`]), "1");
    this.speed.title = "simulated seconds per wall-clock second (time_scale)";
    this.speed.addEventListener("change", () => this.setSpeed(Number(this.speed.value)));
    this.readout = el("span", { class: "readout clock-readout" }, "–");
    container.append(el("div", { class: "toolbar clock", role: "group", "aria-label": "simulation clock" },
      this.pauseButton, step, this.steps, el("label", { class: "inline" }, "Speed", this.speed), this.readout));
    document.addEventListener("keydown", (event) => {
      if (event.key !== " " || event.ctrlKey || event.metaKey || event.altKey) return;
      if (event.target.closest?.("input, select, textarea, button, [contenteditable]")) return;
      event.preventDefault();
      this.togglePause();
    });
  }

  /// `/flag/status`: what the clock is doing now.
  update(status) {
    const clock = readClock(status);
    if (!clock) return;
    this.paused = clock.paused;
    this.pauseButton.textContent = clock.paused ? "Resume" : "Pause";
    this.pauseButton.classList.toggle("active", clock.paused);
    this.readout.textContent = clock.text;
    if (document.activeElement !== this.speed) this.showSpeed(status.time_scale);
  }

  /// The speed in force, offered too when set elsewhere (flagctl time scale 0.3).
  showSpeed(scale) {
    const value = String(scale);
    if (![...this.speed.options].some((option) => option.value === value)) {
      this.speed.append(el("option", { value }, `${value}×`));
    }
    this.speed.value = value;
  }

  togglePause() {
    const operation = this.paused ? "resume" : "pause";
    this.paused = !this.paused;  // shown at once; the next STATUS confirms it
    this.pauseButton.textContent = this.paused ? "Resume" : "Pause";
    this.send("/flag/time", { operation });
  }

  step() {
    const { steps, problem } = readSteps(this.steps.value);
    if (problem) {
      this.steps.classList.add("invalid");
      this.toast(`Step: not sent: ${problem}`, "error");
      return;
    }
    this.send("/flag/time", { operation: "step", steps });
  }

  setSpeed(scale) {
    this.send("/flag/set", { parameters: { time_scale: scale } });
  }

  send(service, request) {
    this.connection.call(service, request).then(
      (answer) => {
        if (answer?.accepted === false) this.toast(`${service}: ${answer.reason}`, "error");
      },
      (error) => this.toast(`${service}: ${error.message}`, "error"),
    );
  }
}
