import assert from "node:assert/strict";
import { test } from "node:test";
import { readWindForm } from "../src/wind_form.js";

const good = { speed: "6", direction: "0", up: "1.5", gust: "0.2", ramp: "1" };

test("valid boxes make the request the server takes", () => {
  assert.deepEqual(readWindForm(good), { request: { velocity: [6, 1.5, 0], gust: 0.2, ramp: 1 } });
  assert.deepEqual(readWindForm({ ...good, direction: "90" }).request.velocity, [0, 1.5, 6]);
});

test("an empty or mistyped box is refused, never sent as 0", () => {
  const { request, problems } = readWindForm({ ...good, speed: "abc", ramp: " " });
  assert.equal(request, undefined);
  assert.deepEqual(problems, [
    { field: "speed", message: "Speed: 'abc' is not a number" },
    { field: "ramp", message: "Ramp: empty or not a number" },
  ]);
});

test("a value out of range names the range in the units typed", () => {
  assert.deepEqual(readWindForm({ ...good, speed: "75" }).problems,
                   [{ field: "speed", message: "Speed: 75 m/s is out of range; allowed 0 .. 60 m/s" }]);
  assert.deepEqual(readWindForm({ ...good, gust: "1.5" }).problems,
                   [{ field: "gust", message: "Gust: 1.5 is out of range; allowed 0 .. 1" }]);
  assert.match(readWindForm({ ...good, speed: "59", up: "20" }).problems[0].message, /62\.2.* m\/s is out of range; allowed 0 \.\. 60 m\/s/);
});
