import assert from "node:assert/strict";
import { test } from "node:test";
import { CallCoalescer } from "../src/call_coalescer.js";
import { mergeCameraMoves } from "../src/camera_controls.js";

/// A send whose calls are answered when the test says so.
function manualSend() {
  const calls = [];
  const send = (request) => new Promise((resolve) => calls.push({ request, resolve }));
  return { calls, send };
}
const settle = () => new Promise((resolve) => setTimeout(resolve, 0));

test("moves made while a call is in flight go as one merged call when it returns", async () => {
  const { calls, send } = manualSend();
  const coalescer = new CallCoalescer({ send, merge: mergeCameraMoves });
  coalescer.push("orbit", { operation: "orbit", degrees: 1, degrees2: 0 });
  await settle();
  for (let i = 0; i < 10; i += 1) coalescer.push("orbit", { operation: "orbit", degrees: 2, degrees2: -1 });
  coalescer.push("zoom", { operation: "zoom", factor: 1.1 });
  coalescer.push("zoom", { operation: "zoom", factor: 1.1 });
  await settle();
  assert.equal(calls.length, 1);
  calls[0].resolve({ accepted: true });
  await settle();
  assert.deepEqual(calls[1].request, { operation: "orbit", degrees: 20, degrees2: -10 });
  calls[1].resolve({ accepted: true });
  await settle();
  assert.equal(calls[2].request.operation, "zoom");
  assert.ok(Math.abs(calls[2].request.factor - 1.21) < 1e-12);
  calls[2].resolve({ accepted: true });
  await settle();
  assert.equal(calls.length, 3);
});

test("a failed call does not stop the next", async () => {
  const seen = [];
  let first = true;
  const coalescer = new CallCoalescer({
    send: () => (first ? ((first = false), Promise.reject(new Error("no"))) : Promise.resolve("yes")),
    onError: (error) => seen.push(error.message),
    onAnswer: (answer) => seen.push(answer),
  });
  coalescer.push("a", {});
  coalescer.push("a", {});
  await settle();
  await settle();
  assert.deepEqual(seen, ["no", "yes"]);
});

test("merged moves stay within what the server allows", () => {
  assert.equal(mergeCameraMoves({ operation: "orbit", degrees: 300, degrees2: 0 }, { operation: "orbit", degrees: 100, degrees2: 0 }).degrees, 360);
  assert.equal(mergeCameraMoves({ operation: "zoom", factor: 50 }, { operation: "zoom", factor: 50 }).factor, 100);
  assert.deepEqual(mergeCameraMoves({ operation: "translate", vector: [1, 2, 3] }, { operation: "translate", vector: [1, 1, 1] }).vector, [2, 3, 4]);
  assert.deepEqual(mergeCameraMoves({ operation: "fov", degrees: 30 }, { operation: "fov", degrees: 50 }), { operation: "fov", degrees: 50 });
});
