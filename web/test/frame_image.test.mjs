import assert from "node:assert/strict";
import { test } from "node:test";
import { FrameImage } from "../src/frame_image.js";
import { createHasher, parseTileUpdate } from "../src/tile_decoder.js";
import { checkTile, encodeUpdate } from "./tile_fixtures.mjs";

const hasher = await createHasher();
const tile = checkTile();

/// A 32 x 8 picture: two 16 x 8 tiles side by side, `left` and `right` RGB8.
function picture(left, right) {
  const rgb = new Uint8Array(32 * 8 * 3);
  for (let y = 0; y < 8; y += 1) {
    rgb.set(left.subarray(y * 48, (y + 1) * 48), y * 96);
    rgb.set(right.subarray(y * 48, (y + 1) * 48), y * 96 + 48);
  }
  return rgb;
}

function rawTile(index, pixels, hash = hasher.hex(pixels)) {
  return { index, x: index * 16, y: 0, width: 16, height: 8, encoding: 0, hash, bytes: pixels };
}

const grey = new Uint8Array(16 * 8 * 3).fill(128);

test("a keyframe, then an update of one tile, give the server's frame", () => {
  const image = new FrameImage(hasher);
  const first = picture(tile.pixels, grey);
  let result = image.apply(parseTileUpdate(encodeUpdate({
    width: 32, height: 8, frameId: 1, frameHash: hasher.hex(first),
    tiles: [{ ...rawTile(0, tile.pixels), encoding: 1, bytes: tile.zstd }, rawTile(1, grey)],
  })));
  assert.equal(result.hashOk, true);
  assert.deepEqual(image.rgb, first);
  assert.equal(result.rects.length, 2);

  const second = picture(tile.pixels, tile.pixels);
  result = image.apply(parseTileUpdate(encodeUpdate({ keyframe: false, width: 32, height: 8, frameId: 2, frameHash: hasher.hex(second), tiles: [rawTile(1, tile.pixels)] })));
  assert.deepEqual([result.hashOk, result.needKeyframe, image.frameId], [true, false, 2]);
  assert.deepEqual(result.rects, [{ x: 16, y: 0, width: 16, height: 8 }]);
  assert.deepEqual(image.rgb, second);
});

test("an update without a keyframe before it is not applied, and asks for one", () => {
  const image = new FrameImage(hasher);
  const result = image.apply(parseTileUpdate(encodeUpdate({ keyframe: false, width: 32, height: 8, frameHash: "00", tiles: [rawTile(1, grey)] })));
  assert.deepEqual([result.applied, result.needKeyframe, image.frameId], [false, true, -1]);
});

test("a tile that fails its hash is left out, and the frame asks for a keyframe", () => {
  const image = new FrameImage(hasher);
  const result = image.apply(parseTileUpdate(encodeUpdate({
    width: 32, height: 8, frameHash: hasher.hex(picture(tile.pixels, grey)),
    tiles: [rawTile(0, tile.pixels, "0123456789abcdef"), rawTile(1, grey)],
  })));
  assert.deepEqual([result.applied, result.hashOk, result.needKeyframe, result.rects.length], [true, false, true, 1]);
  assert.match(result.problems[0], /tile 0: pixel hash/);
});

test("tiles that all check but leave the picture unlike the frame's hash ask for a keyframe", () => {
  const image = new FrameImage(hasher);
  const result = image.apply(parseTileUpdate(encodeUpdate({ width: 32, height: 8, frameHash: "0000000000000001", tiles: [rawTile(0, grey), rawTile(1, grey)] })));
  assert.deepEqual([result.hashOk, result.needKeyframe], [false, true]);
  assert.match(result.problems[0], /whole image's hash/);
});

test("a tile outside the picture is refused", () => {
  const image = new FrameImage(hasher);
  const result = image.apply(parseTileUpdate(encodeUpdate({ width: 20, height: 8, frameHash: "00", tiles: [rawTile(1, grey)] })));
  assert.match(result.problems[0], /outside the picture/);
});
