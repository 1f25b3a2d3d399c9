import assert from "node:assert/strict";
import { test } from "node:test";
import { readViewLink, viewLinkFor } from "../src/view_link.js";

test("a view goes into the link and comes back, the token kept", () => {
  const camera = { eye: [2.6, 1.9, 4.4], target: [0.8, 2.2, 0], fov: 40.107 };
  const link = viewLinkFor({ href: "http://127.0.0.1:8080/?token=abc#x" }, camera);
  const url = new URL(link);
  assert.equal(url.searchParams.get("token"), "abc");
  assert.deepEqual(readViewLink(url.search), { view: camera });
});

test("no view in the address is nothing to do; a bad one says why", () => {
  assert.deepEqual(readViewLink("?token=abc"), {});
  assert.match(readViewLink("?view=1,2,3").problem, /not seven numbers/);
  assert.match(readViewLink("?view=1,2,3,4,5,6,").problem, /not seven numbers/);
  assert.match(readViewLink("?view=1,2,3,4,5,6,170").problem, /170 degrees is out of range; allowed 10 \.\. 120/);
});
