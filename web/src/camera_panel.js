// The camera in numbers: field of view, eye, target and picture size, as number boxes.
//
//   /flag/camera, or a call's answer --update--> boxes (unless the user is typing in one)
//   a box changed --> `/flag/camera` fov / eye / look_at / size, through CameraControls.move
import { el, formatNumber, isEditing, numberInput } from "./dom.js";

export class CameraPanel {
  /// `getCamera()`: the newest `/flag/camera`, shown again after each call (a rejected value
  /// goes back to the one in force, which sends no new message).
  constructor({ container, cameraControls, getCamera }) {
    this.controls = cameraControls;
    cameraControls.onSettled(() => getCamera() && this.update(getCamera()));
    this.fov = numberInput({ min: 10, max: 120, step: 1, title: "vertical field of view, degrees" });
    this.eye = [0, 1, 2].map(() => numberInput({ step: 0.1, title: "eye, m (world frame, y up)" }));
    this.target = [0, 1, 2].map(() => numberInput({ step: 0.1, title: "target: the point looked at, m" }));
    this.width = numberInput({ min: 16, max: 3840, step: 16, title: "picture width, px (every viewer's)" });
    this.height = numberInput({ min: 16, max: 2160, step: 16, title: "picture height, px" });
    this.fov.addEventListener("change", () => this.send({ operation: "fov", degrees: Number(this.fov.value) }));
    this.onVectorChange(this.eye, (vector) => ({ operation: "eye", vector }));
    this.onVectorChange(this.target, (vector) => ({ operation: "look_at", vector }));
    for (const box of [this.width, this.height]) {
      box.addEventListener("change", () => this.send({ operation: "size", width: Number(this.width.value), height: Number(this.height.value) }));
    }
    const reset = el("button", { type: "button", title: "back to the scene's camera (key r)", onclick: () => this.send({ operation: "reset" }) }, "Reset view");
    const frame = el("button", { type: "button", title: "the flag in the middle of the picture, seen from where the camera looks (key f)", onclick: () => this.send({ operation: "frame" }) }, "Frame flag");
    // One server draws one picture: its camera is every viewer's (the design keeps a single
    // renderer, so that what is recorded and replayed is the picture everyone saw).
    this.shared = el("div", { class: "hint shared-camera" }, "This camera is shared: every viewer sees and moves the same view.");
    container.append(
      this.shared,
      el("div", { class: "form-grid camera-grid" },
        el("label", {}, "Eye"), el("div", { class: "triple" }, this.eye), el("span", { class: "unit" }, "m"),
        el("label", {}, "Target"), el("div", { class: "triple" }, this.target), el("span", { class: "unit" }, "m"),
        el("label", {}, "FOV"), el("div", { class: "triple" }, this.fov), el("span", { class: "unit" }, "°"),
        el("label", {}, "Size"), el("div", { class: "triple" }, this.width, this.height), el("span", { class: "unit" }, "px")),
      el("div", { class: "button-row" }, reset, frame,
        el("span", { class: "hint" }, "drag: orbit · shift/right-drag: pan · wheel: zoom at the cursor · +/−: zoom · x y z (shift: back): rotate · arrows, PgUp/PgDn: move · f: frame the flag · r: reset")),
    );
  }

  onVectorChange(boxes, makeRequest) {
    for (const box of boxes) {
      box.addEventListener("change", () => this.send(makeRequest(boxes.map((each) => Number(each.value)))));
    }
  }

  send(request) {
    this.controls.move(request);
  }

  /// `/gateway/status`'s client count: how many viewers share the camera. A gateway serving
  /// several servers (`server` the one steered) counts the viewers of all of them.
  setViewers(count, server = "") {
    const others = Math.max(0, count - 1);
    if (server) {
      this.shared.textContent = `This camera is shared: every viewer of ${server} sees and moves the same view ` +
        `(the gateway has ${others} other client${others === 1 ? "" : "s"}, of any of its servers).`;
      return;
    }
    this.shared.textContent = others === 0
      ? "This camera is shared: every viewer sees and moves the same view (no one else is watching now)."
      : `This camera is shared: ${others} other viewer${others === 1 ? " sees" : "s see"} and move${others === 1 ? "s" : ""} the same view.`;
  }

  /// Shows the camera of the newest frame.
  update(camera) {
    setBox(this.fov, camera.fov, 3);
    camera.eye?.forEach((value, i) => setBox(this.eye[i], value, 4));
    camera.target?.forEach((value, i) => setBox(this.target[i], value, 4));
    setBox(this.width, camera.width, 6);
    setBox(this.height, camera.height, 6);
  }
}

function setBox(box, value, digits) {
  if (!isEditing(box) && Number.isFinite(value)) box.value = formatNumber(value, digits);
}
