// The wind's ground-plane component on a dial, seen from above: x (along the flag) to the
// right, z (across it) down, speed outward. Click or drag to set (vx, vz).
//
//   pointer at (px, py) --> (vx, vz) m/s --onPick--> the wind panel
//   setChosen(vx, vz), setCurrent(vx, vz) --> the knob, and the arrow of the wind now
import { svg } from "./dom.js";

const kSize = 200;              ///< viewBox side
const kCentre = kSize / 2;
const kRadius = 84;             ///< viewBox units of the outer ring
export const kDialSpeed = 30;   ///< m/s at the outer ring; faster winds are drawn on it
const kRings = [10, 20, 30];    ///< m/s

export class WindDial {
  constructor({ onPick }) {
    this.onPick = onPick;
    this.currentArrow = svg("line", { class: "wind-current", x1: kCentre, y1: kCentre, x2: kCentre, y2: kCentre, "marker-end": "url(#wind-head)" });
    this.chosenLine = svg("line", { class: "wind-chosen-line", x1: kCentre, y1: kCentre, x2: kCentre, y2: kCentre });
    this.knob = svg("circle", { class: "wind-knob", cx: kCentre, cy: kCentre, r: 6 });
    this.element = svg("svg", { class: "wind-dial", viewBox: `0 0 ${kSize} ${kSize}`, role: "img", "aria-label": "wind direction and speed in the ground plane" },
      svg("defs", {}, svg("marker", { id: "wind-head", viewBox: "0 0 10 10", refX: 8, refY: 5, markerWidth: 5, markerHeight: 5, orient: "auto-start-reverse" },
        svg("path", { d: "M 0 0 L 10 5 L 0 10 z", class: "wind-current-head" }))),
      ...this.drawGrid(), this.currentArrow, this.chosenLine, this.knob);
    this.attachPointer();
  }

  /// Rings every 10 m/s, the axes and their names.
  drawGrid() {
    const parts = kRings.map((speed) => svg("circle", { class: "dial-ring", cx: kCentre, cy: kCentre, r: (speed / kDialSpeed) * kRadius }));
    parts.push(svg("line", { class: "dial-axis", x1: kCentre - kRadius, y1: kCentre, x2: kCentre + kRadius, y2: kCentre }));
    parts.push(svg("line", { class: "dial-axis", x1: kCentre, y1: kCentre - kRadius, x2: kCentre, y2: kCentre + kRadius }));
    for (const speed of kRings) {
      const text = svg("text", { class: "dial-label", x: kCentre + 3, y: kCentre - (speed / kDialSpeed) * kRadius + 9 });
      text.textContent = `${speed}`;
      parts.push(text);
    }
    const xLabel = svg("text", { class: "dial-axis-label", x: kSize - 2, y: kCentre - 4, "text-anchor": "end" });
    xLabel.textContent = "+x";
    const zLabel = svg("text", { class: "dial-axis-label", x: kCentre + 4, y: kSize - 4 });
    zLabel.textContent = "+z";
    parts.push(xLabel, zLabel);
    return parts;
  }

  attachPointer() {
    let dragging = false;
    const pick = (event) => {
      const box = this.element.getBoundingClientRect();
      const x = ((event.clientX - box.left) / box.width) * kSize - kCentre;
      const y = ((event.clientY - box.top) / box.height) * kSize - kCentre;
      const scale = kDialSpeed / kRadius;
      let [vx, vz] = [x * scale, y * scale];
      const speed = Math.hypot(vx, vz);
      if (speed > kDialSpeed) [vx, vz] = [(vx * kDialSpeed) / speed, (vz * kDialSpeed) / speed];
      this.onPick(round(vx), round(vz));
    };
    this.element.addEventListener("pointerdown", (event) => {
      dragging = true;
      this.element.setPointerCapture(event.pointerId);
      pick(event);
    });
    this.element.addEventListener("pointermove", (event) => dragging && pick(event));
    this.element.addEventListener("pointerup", () => (dragging = false));
    this.element.addEventListener("pointercancel", () => (dragging = false));
  }

  setChosen(vx, vz) {
    const [x, y] = toDial(vx, vz);
    this.knob.setAttribute("cx", x);
    this.knob.setAttribute("cy", y);
    this.chosenLine.setAttribute("x2", x);
    this.chosenLine.setAttribute("y2", y);
  }

  setCurrent(vx, vz) {
    const [x, y] = toDial(vx, vz);
    this.currentArrow.setAttribute("x2", x);
    this.currentArrow.setAttribute("y2", y);
  }
}

/// (vx, vz) m/s -> dial coordinates, speeds past the outer ring drawn on it.
function toDial(vx, vz) {
  const speed = Math.hypot(vx, vz);
  const scale = (speed > kDialSpeed ? kDialSpeed / speed : 1) * (kRadius / kDialSpeed);
  return [kCentre + vx * scale, kCentre + vz * scale];
}

/// To 0.1 m/s: the dial is not finer than that.
function round(value) {
  return Math.round(value * 10) / 10;
}
