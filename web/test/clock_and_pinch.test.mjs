import assert from "node:assert/strict";
import { test } from "node:test";
import { pinchStep } from "../src/camera_controls.js";
import { readClock, readSteps } from "../src/clock_state.js";

test("the clock in words, from STATUS", () => {
  assert.equal(readClock(null), null);
  assert.equal(readClock({ uptime: 1 }), null);  // a server without time control
  assert.deepEqual(readClock({ paused: false, steps_owed: 0, time_scale: 1 }), { paused: false, text: "running · 1×" });
  assert.deepEqual(readClock({ paused: true, steps_owed: 0, time_scale: 0.5 }), { paused: true, text: "paused · 0.5×" });
  assert.deepEqual(readClock({ paused: true, steps_owed: 12, time_scale: 2 }), { paused: true, text: "stepping: 12 to go · 2×" });
});

test("a step count is a whole number 1 .. 100000, or nothing is sent", () => {
  assert.deepEqual(readSteps("7"), { steps: 7 });
  assert.deepEqual(readSteps(" 100000 "), { steps: 100000 });
  for (const text of ["", "abc", "0", "-3", "2.5", "100001", "1e9"]) {
    const { steps, problem } = readSteps(text);
    assert.equal(steps, undefined, text);
    assert.match(problem, /^steps: .*allowed a whole number 1 \.\. 100000$/, text);
  }
});

test("fingers apart zoom in toward the point between them, together zoom out", () => {
  const apart = pinchStep([{ x: 100, y: 100 }, { x: 200, y: 100 }], [{ x: 50, y: 100 }, { x: 250, y: 100 }]);
  assert.deepEqual(apart, { factor: 2, x: 150, y: 100 });
  const together = pinchStep([{ x: 0, y: 0 }, { x: 0, y: 200 }], [{ x: 0, y: 50 }, { x: 0, y: 150 }]);
  assert.equal(together.factor, 0.5);
  assert.equal(pinchStep([{ x: 0, y: 0 }, { x: 100, y: 0 }], [{ x: 0, y: 0 }, { x: 101, y: 0 }]), null);  // under 2 %
  assert.equal(pinchStep([{ x: 0, y: 0 }], [{ x: 0, y: 0 }, { x: 1, y: 0 }]), null);
  assert.equal(pinchStep([{ x: 5, y: 5 }, { x: 5, y: 5 }], [{ x: 0, y: 0 }, { x: 9, y: 0 }]), null);
});
