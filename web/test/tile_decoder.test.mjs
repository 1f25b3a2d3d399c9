import assert from "node:assert/strict";
import { test } from "node:test";
import { createHasher, decodeTile, parseTileUpdate } from "../src/tile_decoder.js";
import { checkTile, encodeUpdate } from "./tile_fixtures.mjs";

const hasher = await createHasher();

test("the hasher is XXH3-64 as libxxhash computes it", () => {
  assert.equal(hasher.hex(checkTile().pixels), checkTile().hash);
  assert.equal(hasher.hex(new Uint8Array(0)), "2d06800538d394c2");  // XXH3_64bits("", 0)
});

test("an update's header and tiles are read little-endian at the contract's offsets", () => {
  const tile = checkTile();
  const data = encodeUpdate({
    width: 16, height: 8, frameId: 2 ** 40 + 3, step: 77, simTime: 1.25, frameHash: "fedcba9876543210",
    tiles: [{ index: 0, x: 0, y: 0, width: 16, height: 8, encoding: 1, hash: tile.hash, bytes: tile.zstd }],
  });
  const { header, tiles } = parseTileUpdate(data);
  assert.deepEqual(header, { version: 1, keyframe: true, tileSize: 16, width: 16, height: 8, tileCount: 1, frameId: 2 ** 40 + 3, step: 77, simTime: 1.25, frameHash: "fedcba9876543210" });
  assert.equal(tiles[0].pixelHash, tile.hash);
  assert.deepEqual([...tiles[0].bytes], [...tile.zstd]);
});

test("zstd, zstd of row residuals and raw tiles decode to their pixels", () => {
  const tile = checkTile();
  const common = { index: 0, x: 0, y: 0, width: 16, height: 8, pixelHash: tile.hash };
  assert.deepEqual(decodeTile({ ...common, encoding: 1, bytes: tile.zstd }, hasher), tile.pixels);
  assert.deepEqual(decodeTile({ ...common, encoding: 2, bytes: tile.zstdUp }, hasher), tile.pixels);
  assert.deepEqual(decodeTile({ ...common, encoding: 0, bytes: tile.pixels }, hasher), tile.pixels);
});

test("a tile whose pixels differ from its hash, size or encoding is refused", () => {
  const tile = checkTile();
  const common = { index: 4, x: 0, y: 0, width: 16, height: 8, encoding: 0, pixelHash: tile.hash };
  const changed = tile.pixels.slice();
  changed[5] ^= 1;
  assert.throws(() => decodeTile({ ...common, bytes: changed }, hasher), /tile 4: pixel hash/);
  assert.throws(() => decodeTile({ ...common, bytes: tile.pixels.subarray(3) }, hasher), /bytes of pixels/);
  assert.throws(() => decodeTile({ ...common, encoding: 7, bytes: tile.pixels }, hasher), /encoding 7/);
  assert.throws(() => decodeTile({ ...common, encoding: 1, bytes: tile.zstd.subarray(0, 20) }, hasher), /zstd/);
});

test("zstd content of another size than the tile's is refused, in the tile's memory", () => {
  const tile = checkTile();
  const larger = { index: 1, x: 0, y: 0, width: 16, height: 16, encoding: 1, pixelHash: tile.hash, bytes: tile.zstd };
  assert.throws(() => decodeTile(larger, hasher), /tile 1: (pixel hash|zstd)/);
  const smaller = { ...larger, height: 4 };
  assert.throws(() => decodeTile(smaller, hasher), /tile 1: (pixel hash|zstd)/);
});

test("truncated or malformed updates are refused with what is wrong", () => {
  const tile = checkTile();
  const update = encodeUpdate({ width: 16, height: 8, frameHash: "00", tiles: [{ index: 0, x: 0, y: 0, width: 16, height: 8, encoding: 1, hash: tile.hash, bytes: tile.zstd }] });
  const cut = (length) => new DataView(update.buffer, 0, length);
  assert.throws(() => parseTileUpdate(cut(40)), /shorter than its header/);
  assert.throws(() => parseTileUpdate(cut(60)), /tile 0: truncated header/);
  assert.throws(() => parseTileUpdate(cut(update.byteLength - 1)), /truncated/);
  const longer = new Uint8Array(update.byteLength + 2);
  longer.set(new Uint8Array(update.buffer));
  assert.throws(() => parseTileUpdate(new DataView(longer.buffer)), /2 bytes after the last tile/);
  const wrongVersion = new Uint8Array(update.buffer.slice(0));
  wrongVersion[0] = 2;
  assert.throws(() => parseTileUpdate(new DataView(wrongVersion.buffer)), /version 2/);
});
