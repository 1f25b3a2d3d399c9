// The page's upload of a design image: which files it sends, the parts, and base64.
import assert from "node:assert/strict";
import { test } from "node:test";

import { base64Of, checkDesignFile, kMaxFileBytes, kPartBytes, partsOf, uploadDesign } from "../src/design_upload.js";

test("a PNG or JPEG within 4 MiB is sent; anything else is refused here with its reason", () => {
  assert.equal(checkDesignFile({ name: "flag.png", size: 10, type: "image/png" }), "");
  assert.equal(checkDesignFile({ name: "FLAG.JPG", size: 10, type: "" }), "");
  assert.equal(checkDesignFile({ name: "flag.gif", size: 10, type: "image/gif" }), "flag.gif: not a PNG or JPEG file");
  assert.equal(checkDesignFile({ name: "e.png", size: 0, type: "image/png" }), "e.png: the file is empty");
  assert.equal(checkDesignFile({ name: "big.png", size: kMaxFileBytes + 1, type: "image/png" }),
    "big.png: 4194305 bytes; allowed up to 4 MiB");
});

test("parts cover the file in order, the last one short", () => {
  assert.deepEqual(partsOf(10, 4), [{ offset: 0, length: 4 }, { offset: 4, length: 4 }, { offset: 8, length: 2 }]);
  assert.deepEqual(partsOf(kPartBytes), [{ offset: 0, length: kPartBytes }]);
  assert.deepEqual(partsOf(0), []);
});

test("base64 matches RFC 4648's vectors", () => {
  const bytes = (text) => new TextEncoder().encode(text);
  for (const [plain, coded] of [["", ""], ["f", "Zg=="], ["fo", "Zm8="], ["foo", "Zm9v"], ["foobar", "Zm9vYmFy"]])
    assert.equal(base64Of(bytes(plain)), coded);
  const large = new Uint8Array(100000).map((_, i) => i * 7);
  assert.equal(base64Of(large), Buffer.from(large).toString("base64"));
});

test("an upload sends each part after the last is answered, and stops at a refusal", async () => {
  const data = new Uint8Array(kPartBytes * 2 + 5).map((_, i) => i);
  const file = new Blob([data], { type: "image/png" });
  file.name = "flag.png";
  const sent = [];
  const answer = await uploadDesign(file, async (service, request) => {
    sent.push({ service, offset: request.offset, size: request.size, length: Buffer.from(request.data, "base64").length });
    return { accepted: true, reason: request.offset === kPartBytes * 2 ? "design flag.png" : "held" };
  });
  assert.equal(answer.reason, "design flag.png");
  assert.deepEqual(sent.map((s) => [s.service, s.offset, s.length]),
    [["/flag/design", 0, kPartBytes], ["/flag/design", kPartBytes, kPartBytes], ["/flag/design", kPartBytes * 2, 5]]);
  await assert.rejects(uploadDesign(file, async () => ({ accepted: false, reason: "cut.png: the PNG cannot be decoded" })),
    /cut.png: the PNG cannot be decoded/);
});
