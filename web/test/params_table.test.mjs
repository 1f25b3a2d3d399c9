import assert from "node:assert/strict";
import { test } from "node:test";
import { readParamsTable, readValue } from "../src/params_table.js";

test("the gateway's table: kinds by name, choices by name", () => {
  const [stiffness, integrator, relative] = readParamsTable({ parameters: [
    { name: "stiffness", unit: "N/m", kind: "real", min: 1, max: 100000, default: 2000, value: 3000, value_text: "3000", choices: [], description: "stretch" },
    { name: "integrator", unit: "", kind: "choice", min: 0, max: 1, default: "symplectic_euler", value: "xpbd", choices: ["symplectic_euler", "xpbd"], description: "" },
    { name: "relative_wind", unit: "", kind: "boolean", min: 0, max: 1, default: false, value: true, choices: [], description: "" },
  ] });
  assert.deepEqual([stiffness.kind, stiffness.min, stiffness.max, stiffness.defaultValue, stiffness.value, stiffness.animatable], ["real", 1, 100000, 2000, 3000, true]);
  assert.deepEqual([integrator.kind, integrator.value, integrator.defaultValue, integrator.animatable], ["choice", "xpbd", "symplectic_euler", false]);
  assert.deepEqual([relative.kind, relative.value, relative.defaultValue], ["boolean", true, false]);
});

test("the LCM message's field names and numeric kinds read the same", () => {
  const [integrator] = readParamsTable({ parameters: [{ name: "integrator", kind: 3, min_value: 0, max_value: 1, default_value: 0, value: 1, choices: ["a", "b"] }] });
  assert.deepEqual([integrator.kind, integrator.value, integrator.defaultValue, integrator.max], ["choice", "b", "a", 1]);
});

test("protocol values (strings for choices, numbers, booleans) read by kind", () => {
  assert.equal(readValue({ kind: "real" }, "2.5"), 2.5);
  assert.equal(readValue({ kind: "boolean" }, "true"), true);
  assert.equal(readValue({ kind: "choice", choices: ["a", "b"] }, 1), "b");
});
