// Reads the PNG files flagctl snapshot writes (8-bit RGB, not interlaced) into RGB8 pixels,
// with Node's zlib: so a test can compare a snapshot with what the page shows, byte for byte.
import { readFileSync } from "node:fs";
import { inflateSync } from "node:zlib";

/** The previous pixel's byte (a), the byte above (b) and above-left (c) => the Paeth predictor. */
function paeth(a, b, c) {
  const p = a + b - c;
  const pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

/** { width, height, rgb: Uint8Array } of an 8-bit RGB PNG; throws for any other kind. */
export function readPngRGB(path) {
  const file = readFileSync(path);
  let offset = 8, width = 0, height = 0;
  const idat = [];
  while (offset < file.length) {
    const length = file.readUInt32BE(offset);
    const type = file.toString("latin1", offset + 4, offset + 8);
    const data = file.subarray(offset + 8, offset + 8 + length);
    if (type === "IHDR") {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      if (data[8] !== 8 || data[9] !== 2 || data[12] !== 0) throw new Error(`${path}: not 8-bit RGB, not interlaced`);
    }
    if (type === "IDAT") idat.push(data);
    offset += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * 3;
  const rgb = new Uint8Array(stride * height);
  for (let y = 0; y < height; y += 1) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; x += 1) {
      const a = x >= 3 ? rgb[y * stride + x - 3] : 0;
      const b = y > 0 ? rgb[(y - 1) * stride + x] : 0;
      const c = x >= 3 && y > 0 ? rgb[(y - 1) * stride + x - 3] : 0;
      const predicted = [0, a, b, (a + b) >> 1, paeth(a, b, c)][filter];
      rgb[y * stride + x] = (line[x] + predicted) & 0xff;
    }
  }
  return { width, height, rgb };
}
