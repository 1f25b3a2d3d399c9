import assert from "node:assert/strict";
import { test } from "node:test";
import { positionAt, readTimeline } from "../src/timeline_model.js";

test("keys are read with laws by name, sorted by time", () => {
  const timeline = readTimeline({ playing: true, position: 1, speed: 2, loop: true, last_key_time: 4, keys: [
    { time: 4, law: "cubic", wind: { velocity: [1, 0, 0], gust: 0.1 } },
    { time: 0, law: 1, has_camera: true, camera_eye: [0, 1, 2], camera_target: [0, 0, 0], camera_fov: 40 },
  ] }, 10);
  assert.deepEqual(timeline.keys.map((key) => [key.time, key.law]), [[0, "linear"], [4, "cubic"]]);
  assert.deepEqual(timeline.keys[0].camera, { eye: [0, 1, 2], target: [0, 0, 0], fov: 40 });
  assert.deepEqual(timeline.keys[1].wind, { velocity: [1, 0, 0], gust: 0.1 });
});

test("the position moves on with simulated time, and wraps or stops at the end", () => {
  const looping = readTimeline({ playing: true, position: 1, speed: 2, loop: true, last_key_time: 4, keys: [] }, 10);
  assert.equal(positionAt(looping, 10.5), 2);
  assert.equal(positionAt(looping, 12), 1);  // 1 + 4 = 5 -> 1
  const stopping = readTimeline({ playing: true, position: 1, speed: 2, loop: false, last_key_time: 4, keys: [] }, 10);
  assert.equal(positionAt(stopping, 12), 4);
  const paused = readTimeline({ playing: false, position: 3, speed: 1, loop: false, last_key_time: 4, keys: [] }, 10);
  assert.equal(positionAt(paused, 20), 3);
});
