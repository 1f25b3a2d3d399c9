// The picture as the server drew it: an RGB8 image assembled from tile updates.
//
//   update { header, tiles } --apply--> pixels written into `rgb`, the changed rectangles,
//                                       and whether the whole image now hashes to the frame's hash
//
// A keyframe (every tile) starts a picture afresh; any other update only makes sense on top of
// the previous one at the same size. When a frame cannot be completed (a tile that fails to
// decode or to match its hash, a missed keyframe, a whole-image hash that differs) the result
// says `needKeyframe`, and the caller asks for one (`/flag/refresh`).
import { decodeTile } from "./tile_decoder.js";

export class FrameImage {
  constructor(hasher) {
    this.hasher = hasher;
    this.width = 0;            ///< px
    this.height = 0;           ///< px
    this.rgb = new Uint8Array(0);  ///< RGB8, rows top to bottom, width * height * 3 bytes
    this.frameId = -1;         ///< the frame id of the newest update applied
    this.step = -1;            ///< the simulation step that frame drew
    this.simTime = 0;          ///< s
    this.frameHash = "";       ///< the newest update's frame hash, 16 hex digits
    this.hashOk = false;       ///< `rgb` hashes to `frameHash`: exactly the server's frame
    this.started = false;      ///< a keyframe has been applied since the last size change
  }

  /// Applies one parsed update. Returns { applied (false: it needs a keyframe first), rects:
  /// [{x, y, width, height}] written, hashOk, needKeyframe, problems: [text] }.
  apply({ header, tiles }) {
    const sameSize = header.width === this.width && header.height === this.height;
    if (!header.keyframe && (!this.started || !sameSize)) {
      return { applied: false, rects: [], hashOk: false, needKeyframe: true, problems: ["an update without the keyframe it builds on"] };
    }
    if (!sameSize) this.resize(header.width, header.height);
    this.started = true;
    const rects = [];
    const problems = [];
    for (const tile of tiles) {
      const problem = this.placeTile(tile);
      if (problem) problems.push(problem);
      else rects.push({ x: tile.x, y: tile.y, width: tile.width, height: tile.height });
    }
    this.frameId = header.frameId;
    this.step = header.step;
    this.simTime = header.simTime;
    this.frameHash = header.frameHash;
    this.hashOk = problems.length === 0 && this.hasher.hex(this.rgb) === header.frameHash;
    if (problems.length === 0 && !this.hashOk) problems.push("the whole image's hash differs from the frame's");
    return { applied: true, rects, hashOk: this.hashOk, needKeyframe: !this.hashOk, problems };
  }

  resize(width, height) {
    this.width = width;
    this.height = height;
    this.rgb = new Uint8Array(width * height * 3);
  }

  /// Decodes `tile` and copies its rows into the image; "" or why it was not placed.
  placeTile(tile) {
    if (tile.x + tile.width > this.width || tile.y + tile.height > this.height || tile.width === 0 || tile.height === 0) {
      return `tile ${tile.index}: ${tile.width} x ${tile.height} px at (${tile.x}, ${tile.y}) is outside the picture`;
    }
    let pixels;
    try {
      pixels = decodeTile(tile, this.hasher);
    } catch (error) {
      return error.message;
    }
    const rowBytes = tile.width * 3;
    for (let row = 0; row < tile.height; row += 1) {
      const source = pixels.subarray(row * rowBytes, (row + 1) * rowBytes);
      this.rgb.set(source, ((tile.y + row) * this.width + tile.x) * 3);
    }
    return "";
  }
}
