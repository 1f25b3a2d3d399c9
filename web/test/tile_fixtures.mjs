// Builds `flagsim.TileUpdate` bytes for the tests, as the gateway writes them (docs/live-view.md),
// and small fixed tiles: zstd frames made with the zstd tool (--no-check, as the server's
// ZSTD_compress), hashes checked against libxxhash's XXH3_64bits.

const hex = (text) => Uint8Array.from(text.match(/../g), (pair) => parseInt(pair, 16));

/// A 16 x 8 px tile of 4 x 2 px checks: its RGB8 bytes, its zstd frame, the zstd frame of its row
/// residuals (each byte minus the byte one row up; in the first row, one pixel left) and its XXH3-64.
export function checkTile() {
  const pixels = new Uint8Array(16 * 8 * 3);
  for (let y = 0; y < 8; y += 1) {
    for (let x = 0; x < 16; x += 1) {
      pixels.set((Math.floor(x / 4) + Math.floor(y / 2)) % 2 ? [30, 60, 200] : [240, 200, 20], (y * 16 + x) * 3);
    }
  }
  return {
    width: 16, height: 8, pixels,
    zstd: hex("28b52ffd60800005010030f0c8141e3cc80a000109011204240448109090af24e04e09380b006558b821"),
    zstdUp: hex("28b52ffd608000f5010090f0c814002e74b400d28c4c002e74b4d28c4c130080838004c0414002e020206187830b83f09583c610c1ce0e380b0065e88a0944b09303400820840044"),
    hash: "8ee3560fd16da9d8",
  };
}

/// Encodes an update: header fields and tiles [{ index, x, y, width, height, encoding, hash
/// (hex), bytes }]; `frameHash` hex.
export function encodeUpdate({ keyframe = true, tileSize = 16, width, height, frameId = 1, step = 10, simTime = 0.5, frameHash, tiles }) {
  const size = 48 + tiles.reduce((sum, tile) => sum + 25 + tile.bytes.length, 0);
  const bytes = new Uint8Array(size);
  const view = new DataView(bytes.buffer);
  view.setUint8(0, 1);
  view.setUint8(1, keyframe ? 1 : 0);
  view.setUint16(2, tileSize, true);
  view.setUint32(4, width, true);
  view.setUint32(8, height, true);
  view.setUint32(12, tiles.length, true);
  view.setBigInt64(16, BigInt(frameId), true);
  view.setBigInt64(24, BigInt(step), true);
  view.setFloat64(32, simTime, true);
  view.setBigUint64(40, BigInt(`0x${frameHash}`), true);
  let offset = 48;
  for (const tile of tiles) {
    view.setUint32(offset, tile.index, true);
    [tile.x, tile.y, tile.width, tile.height].forEach((value, i) => view.setUint16(offset + 4 + 2 * i, value, true));
    view.setUint8(offset + 12, tile.encoding);
    view.setBigUint64(offset + 13, BigInt(`0x${tile.hash}`), true);
    view.setUint32(offset + 21, tile.bytes.length, true);
    bytes.set(tile.bytes, offset + 25);
    offset += 25 + tile.bytes.length;
  }
  return new DataView(bytes.buffer);
}
