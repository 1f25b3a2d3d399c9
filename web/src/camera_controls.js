// The origin's camera controls, on the picture, as `/flag/camera` calls:
//
//   drag                          -> orbit (degrees, degrees2) about the target
//   shift-drag, right- or middle-drag -> translate in the camera's right/up plane (m)
//   wheel                         -> zoom toward what the cursor points at (factor 1.1 per notch;
//                                    the server stops it short of the flag)
//   x/X y/Y z/Z                   -> rotate_x / rotate_y / rotate_z by +-5 degrees
//   arrows, PageUp/PageDown       -> translate right/left, up/down, toward/away from the target
//   + / -                         -> zoom in / out;  f -> frame the flag;  r -> reset
//   pinch (two fingers)           -> zoom toward the point between them, by their spread's ratio
//
// Moves go through a CallCoalescer: while one call is in flight, further deltas add up into one
// waiting call per operation. A rejected move shows the server's reason on the picture.
import { CallCoalescer } from "./call_coalescer.js";
import { cameraAxes, combine, panVector } from "./camera_math.js";

const kOrbitDegreesPerPixel = 0.3;  ///< degrees of orbit per screen px of drag
const kWheelFactorPerNotch = 1.1;   ///< zoom factor of one wheel notch (100 px of deltaY)
const kKeyDegrees = 5;              ///< degrees per rotate key press
const kKeyStepFraction = 0.05;      ///< translate per arrow key, as a fraction of the eye-target distance
const kMaxDegrees = 360;            ///< the server allows one turn per move
const kMinFactor = 0.01, kMaxFactor = 100;

/// Merges two moves of one operation into one (angles and vectors add, factors multiply).
export function mergeCameraMoves(waiting, next) {
  const clampDegrees = (value) => Math.max(-kMaxDegrees, Math.min(kMaxDegrees, value));
  switch (next.operation) {
    case "orbit":
      return { ...next, degrees: clampDegrees(waiting.degrees + next.degrees), degrees2: clampDegrees(waiting.degrees2 + next.degrees2) };
    case "rotate_x":
    case "rotate_y":
    case "rotate_z":
      return { ...next, degrees: clampDegrees(waiting.degrees + next.degrees) };
    case "translate":
      return { ...next, vector: combine(waiting.vector, 1, next.vector, 1) };
    case "zoom":
    case "zoom_at":  // toward the newest pixel
      return { ...next, factor: Math.max(kMinFactor, Math.min(kMaxFactor, waiting.factor * next.factor)) };
    default:
      return next;  // absolute settings: the latest wins
  }
}

const kLeastPinchChange = 0.02;  ///< a pinch zooms once the fingers' spread changed by 2 %

/// Two fingers from `before` to `after` ([{x, y}, {x, y}] screen px): { factor, x, y }, the
/// spread's ratio (apart: above 1, in) and the point between them now; null while the spread has
/// changed by less than kLeastPinchChange (or a finger sits on the other).
export function pinchStep(before, after) {
  if (before?.length !== 2 || after?.length !== 2) return null;
  const spread = ([a, b]) => Math.hypot(a.x - b.x, a.y - b.y);
  const from = spread(before), to = spread(after);
  if (from < 1 || to < 1) return null;
  const factor = to / from;
  if (Math.abs(factor - 1) < kLeastPinchChange) return null;
  return { factor, x: (after[0].x + after[1].x) / 2, y: (after[0].y + after[1].y) / 2 };
}

export class CameraControls {
  /// `stage`: the element under the pointer; `frameView` gives the picture's on-screen scale;
  /// `getCamera()` the newest `/flag/camera`; `toast(text)` shows a reason briefly.
  constructor({ stage, frameView, connection, getCamera, toast }) {
    this.stage = stage;
    this.frameView = frameView;
    this.getCamera = getCamera;
    this.toast = toast;
    this.drag = null;  // { x, y, mode: "orbit" | "pan", pointerId }
    this.pointers = new Map();  // pointerId -> { x, y }: the fingers down, for a pinch
    this.pinch = null;          // two fingers down: their positions when last zoomed
    this.settledListeners = [];  // called after each answer (the camera panel shows what is in force)
    this.coalescer = new CallCoalescer({
      send: (request) => connection.call("/flag/camera", request),
      merge: mergeCameraMoves,
      onAnswer: (answer) => {
        if (answer?.accepted === false) this.toast(`Camera: ${answer.reason || "rejected"}`);
        this.settledListeners.forEach((listener) => listener());
      },
      onError: (error) => {
        this.toast(`Camera: ${error.message}`);
        this.settledListeners.forEach((listener) => listener());
      },
    });
    this.attachPointer();
    document.addEventListener("keydown", (event) => this.onKey(event));
  }

  /// `listener()` runs after each camera call's answer, accepted or not.
  onSettled(listener) {
    this.settledListeners.push(listener);
  }

  /// Sends one camera request (an absolute setting, or a move to merge with waiting ones).
  move(request) {
    if (request.operation === "reset") this.coalescer.clear();
    this.coalescer.push(request.operation, request);
  }

  attachPointer() {
    const stage = this.stage;
    stage.addEventListener("contextmenu", (event) => event.preventDefault());
    stage.addEventListener("pointerdown", (event) => this.onPointerDown(event));
    stage.addEventListener("pointermove", (event) => this.onPointerMove(event));
    stage.addEventListener("pointerup", (event) => this.onPointerUp(event));
    stage.addEventListener("pointercancel", (event) => this.onPointerUp(event));
    stage.addEventListener("wheel", (event) => this.onWheel(event), { passive: false });
  }

  onPointerDown(event) {
    this.pointers.set(event.pointerId, { x: event.clientX, y: event.clientY });
    if (this.pointers.size === 2) return this.startPinch(event);
    if (this.drag) return;
    const pan = event.button === 2 || event.button === 1 || event.shiftKey;
    this.drag = { x: event.clientX, y: event.clientY, mode: pan ? "pan" : "orbit", pointerId: event.pointerId };
    this.stage.setPointerCapture(event.pointerId);
    this.stage.classList.add(pan ? "panning" : "orbiting");
    this.stage.focus({ preventScroll: true });
    event.preventDefault();
  }

  /// pointer moved (dx, dy screen px) -> an orbit or a pan, merged while a call is in flight.
  onPointerMove(event) {
    if (this.pointers.has(event.pointerId)) this.pointers.set(event.pointerId, { x: event.clientX, y: event.clientY });
    if (this.pinch) return this.movePinch();
    if (!this.drag || event.pointerId !== this.drag.pointerId) return;
    const dx = event.clientX - this.drag.x;
    const dy = event.clientY - this.drag.y;
    if (dx === 0 && dy === 0) return;
    this.drag.x = event.clientX;
    this.drag.y = event.clientY;
    if (this.drag.mode === "orbit") {
      this.move({ operation: "orbit", degrees: -dx * kOrbitDegreesPerPixel, degrees2: dy * kOrbitDegreesPerPixel });
      return;
    }
    const displayHeight = this.frameView.canvas.height * this.frameView.displayScale;
    const vector = panVector(this.getCamera(), dx, dy, displayHeight);
    if (vector) this.move({ operation: "translate", vector });
  }

  /// A second finger: the drag ends, and the two fingers' spread zooms from here on.
  startPinch(event) {
    if (this.drag) this.endDrag();
    this.stage.setPointerCapture(event.pointerId);
    this.pinch = [...this.pointers.values()];
    event.preventDefault();
  }

  /// Fingers apart -> zoom in toward the point between them; together -> out.
  movePinch() {
    const now = [...this.pointers.values()];
    const step = pinchStep(this.pinch, now);
    if (!step) return;
    this.pinch = now;
    const pixel = this.frameView.imagePixelAt(step.x, step.y);
    this.move(pixel ? { operation: "zoom_at", factor: step.factor, pixel } : { operation: "zoom", factor: step.factor });
  }

  onPointerUp(event) {
    this.pointers.delete(event.pointerId);
    if (this.pinch && this.pointers.size < 2) {
      this.pinch = null;
      this.stage.releasePointerCapture?.(event.pointerId);
      return;
    }
    if (!this.drag || event.pointerId !== this.drag.pointerId) return;
    this.endDrag();
  }

  endDrag() {
    if (this.stage.hasPointerCapture?.(this.drag.pointerId)) this.stage.releasePointerCapture(this.drag.pointerId);
    this.stage.classList.remove("panning", "orbiting");
    this.drag = null;
  }

  /// wheel -> zoom: deltaY < 0 (away from the user) zooms in; 100 px of deltaY is one notch.
  onWheel(event) {
    event.preventDefault();
    const pixels = event.deltaMode === 1 ? event.deltaY * 33 : event.deltaMode === 2 ? event.deltaY * 500 : event.deltaY;
    if (pixels === 0) return;
    const factor = kWheelFactorPerNotch ** (-pixels / 100);
    const pixel = this.frameView.imagePixelAt(event.clientX, event.clientY);
    this.move(pixel ? { operation: "zoom_at", factor, pixel } : { operation: "zoom", factor });
  }

  /// Keys act unless the user is typing in a form field.
  onKey(event) {
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    if (event.target.closest?.("input, select, textarea, [contenteditable]")) return;
    const request = this.keyMove(event.key);
    if (!request) return;
    event.preventDefault();
    this.move(request);
  }

  /// A key -> its camera request, or null.
  keyMove(key) {
    const rotations = { x: "rotate_x", y: "rotate_y", z: "rotate_z" };
    const lower = key.length === 1 ? key.toLowerCase() : key;
    if (rotations[lower]) return { operation: rotations[lower], degrees: key === lower ? kKeyDegrees : -kKeyDegrees };
    if (key === "+" || key === "=") return { operation: "zoom", factor: kWheelFactorPerNotch };
    if (key === "-" || key === "_") return { operation: "zoom", factor: 1 / kWheelFactorPerNotch };
    if (lower === "r") return { operation: "reset" };
    if (lower === "f") return { operation: "frame" };
    return this.keyTranslate(key);
  }

  /// Arrow keys and PageUp/PageDown -> translate by a step proportional to the target distance.
  keyTranslate(key) {
    const directions = { ArrowRight: ["right", 1], ArrowLeft: ["right", -1], ArrowUp: ["up", 1], ArrowDown: ["up", -1], PageUp: ["forward", 1], PageDown: ["forward", -1] };
    const axes = cameraAxes(this.getCamera());
    if (!directions[key] || !axes) return null;
    const [axis, sign] = directions[key];
    const step = Math.max(0.01, axes.distance * kKeyStepFraction);
    return { operation: "translate", vector: axes[axis].map((value) => value * sign * step) };
  }
}
