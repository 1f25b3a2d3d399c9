// `flagsim.TileUpdate` (docs/live-view.md), little-endian:
//
//   bytes --parseTileUpdate--> { header, tiles: [{ index, x, y, width, height, encoding,
//                                                  pixelHash, bytes }] }
//   tile --decodeTile--> RGB8 pixels, rows top to bottom, checked against the tile's XXH3-64
//
// Each tile decodes on its own: raw, one zstd frame of its RGB8 bytes, or one zstd frame of its
// row residuals (each byte minus the byte one row up; in the first row, one pixel left).
import { decompress } from "fzstd";
import { createXXHash3 } from "hash-wasm";

export const kVersion = 1;
export const kEncodingRaw = 0;
export const kEncodingZstd = 1;
export const kEncodingZstdUp = 2;
const kHeaderBytes = 48;
const kTileHeaderBytes = 4 + 4 * 2 + 1 + 8 + 4;  ///< index, x y w h, encoding, hash, byte count
const kMaxSide = 8192;  ///< px: a larger picture is refused (as flagctl's assembler does)

/// Returns the XXH3-64 (seed 0) hasher the page uses: hex(bytes) -> 16 hex digits, as the
/// canonical (big-endian) form of the uint64 the messages carry. Async: the WASM loads once.
export async function createHasher() {
  const hasher = await createXXHash3();
  return {
    hex(bytes) {
      hasher.init();
      hasher.update(bytes);
      return hasher.digest("hex");
    },
  };
}

/// A uint64 read little-endian at `offset` as 16 hex digits (how hash-wasm writes digests).
function readHashHex(view, offset) {
  return view.getBigUint64(offset, true).toString(16).padStart(16, "0");
}

/// Parses one update's bytes (a DataView over the message payload). Throws an Error naming
/// what is wrong with a truncated or malformed update; the pixel bytes are views, not copies.
export function parseTileUpdate(view) {
  if (view.byteLength < kHeaderBytes) throw new Error(`update of ${view.byteLength} bytes: shorter than its header`);
  const header = {
    version: view.getUint8(0),
    keyframe: view.getUint8(1) === 1,
    tileSize: view.getUint16(2, true),
    width: view.getUint32(4, true),
    height: view.getUint32(8, true),
    tileCount: view.getUint32(12, true),
    frameId: Number(view.getBigInt64(16, true)),
    step: Number(view.getBigInt64(24, true)),
    simTime: view.getFloat64(32, true),
    frameHash: readHashHex(view, 40),
  };
  if (header.version !== kVersion) throw new Error(`version ${header.version}; this page reads ${kVersion}`);
  if (header.width < 1 || header.height < 1 || header.width > kMaxSide || header.height > kMaxSide) {
    throw new Error(`picture ${header.width} x ${header.height} px: outside 1 .. ${kMaxSide}`);
  }
  const tiles = [];
  let offset = kHeaderBytes;
  for (let i = 0; i < header.tileCount; i += 1) {
    const tile = parseTile(view, offset, i);
    offset += kTileHeaderBytes + tile.bytes.byteLength;
    tiles.push(tile);
  }
  if (offset !== view.byteLength) throw new Error(`${view.byteLength - offset} bytes after the last tile`);
  return { header, tiles };
}

function parseTile(view, offset, number) {
  if (offset + kTileHeaderBytes > view.byteLength) throw new Error(`tile ${number}: truncated header`);
  const tile = {
    index: view.getUint32(offset, true),
    x: view.getUint16(offset + 4, true),
    y: view.getUint16(offset + 6, true),
    width: view.getUint16(offset + 8, true),
    height: view.getUint16(offset + 10, true),
    encoding: view.getUint8(offset + 12),
    pixelHash: readHashHex(view, offset + 13),
  };
  const byteCount = view.getUint32(offset + 21, true);
  const start = offset + kTileHeaderBytes;
  if (start + byteCount > view.byteLength) throw new Error(`tile ${number}: ${byteCount} bytes, truncated`);
  tile.bytes = new Uint8Array(view.buffer, view.byteOffset + start, byteCount);
  return tile;
}

/// tile -> its RGB8 pixels (width * height * 3 bytes), or throws why not: an unknown encoding,
/// raw bytes of the wrong size, zstd that does not decode, or a pixel hash that differs.
export function decodeTile(tile, hasher) {
  const size = tile.width * tile.height * 3;
  let pixels;
  if (tile.encoding === kEncodingRaw) {
    if (tile.bytes.byteLength !== size) {
      throw new Error(`tile ${tile.index}: ${tile.bytes.byteLength} bytes of pixels for ${tile.width} x ${tile.height} px`);
    }
    pixels = tile.bytes;
  } else if (tile.encoding === kEncodingZstd) {
    pixels = decompressTile(tile, size);
  } else if (tile.encoding === kEncodingZstdUp) {
    pixels = unpredictRows(decompressTile(tile, size), tile.width);
  } else {
    throw new Error(`tile ${tile.index}: encoding ${tile.encoding} is not 0 (raw), 1 (zstd) or 2 (zstd of row residuals)`);
  }
  const hash = hasher.hex(pixels);
  if (hash !== tile.pixelHash) throw new Error(`tile ${tile.index}: pixel hash ${hash}, expected ${tile.pixelHash}`);
  return pixels;
}

/// Row residuals -> RGB8 pixels, in place: each byte plus the byte one row up (the first row:
/// plus the byte one pixel left), modulo 256.
function unpredictRows(bytes, width) {
  const stride = width * 3;
  for (let i = 3; i < Math.min(stride, bytes.length); i += 1) bytes[i] = (bytes[i] + bytes[i - 3]) & 255;
  for (let i = stride; i < bytes.length; i += 1) bytes[i] = (bytes[i] + bytes[i - stride]) & 255;
  return bytes;
}

/// zstd -> `size` bytes. The output is the tile's size whatever the frame claims, so a bad
/// frame costs no more memory than a good one; too little or too much content then shows as a
/// pixel hash that differs (or a decoding error).
function decompressTile(tile, size) {
  try {
    return decompress(tile.bytes, new Uint8Array(size));
  } catch (error) {
    throw new Error(`tile ${tile.index}: zstd: ${error.message ?? error}`);
  }
}
