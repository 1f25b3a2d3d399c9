import assert from "node:assert/strict";
import { test } from "node:test";
import { cameraAxes, metresPerPixel, panVector } from "../src/camera_math.js";

const near = (a, b) => a.every((value, i) => Math.abs(value - b[i]) < 1e-9);
// Looking down -z from 5 m, y up: right is +x.
const camera = { eye: [0, 1, 5], target: [0, 1, 0], fov: 90, view: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, -5, 1] };

test("the axes follow from eye and target with y up", () => {
  const axes = cameraAxes(camera);
  assert.ok(near(axes.right, [1, 0, 0]) && near(axes.up, [0, 1, 0]) && near(axes.forward, [0, 0, -1]));
  assert.equal(axes.distance, 5);
});

test("without eye and target the view matrix's rows are the axes", () => {
  const axes = cameraAxes({ view: camera.view });
  assert.ok(near(axes.right, [1, 0, 0]) && near(axes.up, [0, 1, 0]) && near(axes.forward, [0, 0, -1]));
});

test("a pan moves the camera against the drag, by the metres a pixel spans at the target", () => {
  // fov 90 degrees at 5 m: 10 m over 500 px, 0.02 m a pixel.
  assert.ok(Math.abs(metresPerPixel(camera, 500) - 0.02) < 1e-12);
  assert.ok(near(panVector(camera, 10, 0, 500), [-0.2, 0, 0]));  // drag right: camera left
  assert.ok(near(panVector(camera, 0, 10, 500), [0, 0.2, 0]));   // drag down: camera up
  assert.equal(panVector(null, 1, 1, 500), null);
});
