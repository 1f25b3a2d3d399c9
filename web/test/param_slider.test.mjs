import assert from "node:assert/strict";
import { test } from "node:test";
import { kSteps, sliderScale } from "../src/param_slider.js";

test("a range over decades is logarithmic: each decade gets the same travel", () => {
  const scale = sliderScale({ kind: "real", min: 1, max: 100000 });
  assert.equal(scale.toValue(0), 1);
  assert.equal(scale.toValue(kSteps), 100000);
  assert.equal(scale.toValue(kSteps * 0.6), 1000);
  assert.ok(Math.abs(scale.toPosition(1000) - kSteps * 0.6) < 1e-9);
});

test("a wide range from 0 starts at 0 and reaches the top", () => {
  const scale = sliderScale({ kind: "real", min: 0, max: 100000 });
  assert.equal(scale.toValue(0), 0);
  assert.equal(scale.toValue(kSteps), 100000);
  const position = scale.toPosition(2000);
  assert.ok(Math.abs(scale.toValue(Math.round(position)) - 2000) / 2000 < 0.02);
});

test("a range from 0 is logarithmic only past 1000 or 100 times its default", () => {
  assert.equal(sliderScale({ kind: "real", min: 0, max: 100, defaultValue: 9.81 }).toValue(kSteps / 2), 50);
  assert.ok(sliderScale({ kind: "real", min: 0, max: 100, defaultValue: 0.05 }).toValue(kSteps / 2) < 1);
});

test("narrow ranges are linear; integers round", () => {
  const real = sliderScale({ kind: "real", min: 0, max: 10 });
  assert.equal(real.toValue(kSteps / 4), 2.5);
  const integer = sliderScale({ kind: "integer", min: 2, max: 512 });
  assert.equal(integer.toValue(kSteps / 2), 257);
  assert.equal(integer.toPosition(2), 0);
});
