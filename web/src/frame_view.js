// The assembled picture on screen.
//
//   FrameImage.rgb + changed rects --show--> RGBA canvas at the picture's own size, drawn
//   scaled to fit the stage (aspect kept), frames shown per second, "hash ok"
//
// The canvas holds the server's pixels exactly (alpha 255), so a snapshot of it is the frame.
const kFpsWindow = 1000;      ///< ms over which frames shown per second are counted
const kMaxSeparateRects = 16;  ///< more changed tiles than this are drawn as their bounding box

export class FrameView {
  /// `stage`: the element the picture fills; `canvas` inside it; `hud`: the line over the
  /// picture's corner (frame, frames shown per second, hash).
  constructor({ stage, canvas, hud }) {
    this.stage = stage;
    this.canvas = canvas;
    this.hud = hud;
    this.context = canvas.getContext("2d", { alpha: false });
    this.imageData = null;
    this.framesShown = 0;
    this.shownTimes = [];  // ms of recent frames shown, oldest first
    this.displayScale = 1;  // CSS px per picture px
    this.lastImage = null;  // the FrameImage last shown
    new ResizeObserver(() => this.fit()).observe(stage);
  }

  /// Draws what `apply` changed: the whole picture after a size change, else the rects.
  show(image, rects) {
    if (!this.imageData || this.imageData.width !== image.width || this.imageData.height !== image.height) {
      this.canvas.width = image.width;
      this.canvas.height = image.height;
      this.imageData = this.context.createImageData(image.width, image.height);
      rects = [{ x: 0, y: 0, width: image.width, height: image.height }];
      this.fit();
    }
    for (const rect of rects) copyRgbToRgba(image.rgb, this.imageData.data, image.width, rect);
    // A few tiles go up one by one; many (a keyframe) as the one rectangle around them.
    for (const rect of rects.length > kMaxSeparateRects ? [boundingRect(rects)] : rects) {
      this.context.putImageData(this.imageData, 0, 0, rect.x, rect.y, rect.width, rect.height);
    }
    this.framesShown += 1;
    const now = performance.now();
    this.shownTimes.push(now);
    this.dropOldTimes(now);
    this.updateHud(image);
  }

  /// "frame 1234 · 30 fps · hash ok" over the picture's corner (again without a frame: the rate
  /// falls when frames stop).
  updateHud(image = this.lastImage) {
    this.lastImage = image;
    if (!this.hud || !image) return;
    this.hud.textContent = `frame ${image.frameId} · ${this.shownFps()} fps · ${image.hashOk ? "hash ok" : "hash mismatch"}`;
    this.hud.classList.toggle("bad", !image.hashOk);
  }

  /// Forgets the picture last shown (another server's comes next): the line over it empties.
  forget() {
    this.lastImage = null;
    this.shownTimes = [];
    if (this.hud) this.hud.textContent = "";
  }

  dropOldTimes(now) {
    while (this.shownTimes.length > 0 && now - this.shownTimes[0] > kFpsWindow) this.shownTimes.shift();
  }

  /// Frames shown in the last second.
  shownFps() {
    this.dropOldTimes(performance.now());
    return this.shownTimes.length;
  }

  /// Sizes the canvas on screen: as large as the stage allows, the picture's aspect kept; pixels
  /// stay square and sharp when scaled up.
  fit() {
    const width = this.canvas.width;
    const height = this.canvas.height;
    const box = this.stage.getBoundingClientRect();
    if (!width || !height || box.width <= 0 || box.height <= 0) return;
    this.displayScale = Math.min(box.width / width, box.height / height);
    this.canvas.style.width = `${Math.floor(width * this.displayScale)}px`;
    this.canvas.style.height = `${Math.floor(height * this.displayScale)}px`;
    const devicePixels = this.displayScale * (window.devicePixelRatio || 1);
    this.canvas.style.imageRendering = devicePixels >= 1.5 ? "pixelated" : "auto";
  }

  /// The picture's pixel (x right, y down, px of the server's image) under a point of the
  /// window (client px); null outside the picture or before the first frame.
  imagePixelAt(clientX, clientY) {
    const box = this.canvas.getBoundingClientRect();
    if (box.width === 0 || box.height === 0) return null;
    const x = ((clientX - box.left) / box.width) * this.canvas.width;
    const y = ((clientY - box.top) / box.height) * this.canvas.height;
    return x >= 0 && y >= 0 && x <= this.canvas.width && y <= this.canvas.height ? [x, y] : null;
  }

  /// The picture as a PNG blob (the canvas holds its exact pixels).
  toPngBlob() {
    return new Promise((resolve) => this.canvas.toBlob(resolve, "image/png"));
  }
}

function boundingRect(rects) {
  const left = Math.min(...rects.map((r) => r.x));
  const top = Math.min(...rects.map((r) => r.y));
  const right = Math.max(...rects.map((r) => r.x + r.width));
  const bottom = Math.max(...rects.map((r) => r.y + r.height));
  return { x: left, y: top, width: right - left, height: bottom - top };
}

/// RGB8 rows -> RGBA8 rows inside `rect` (alpha 255).
function copyRgbToRgba(rgb, rgba, width, rect) {
  for (let y = rect.y; y < rect.y + rect.height; y += 1) {
    let source = (y * width + rect.x) * 3;
    let target = (y * width + rect.x) * 4;
    for (let x = 0; x < rect.width; x += 1) {
      rgba[target] = rgb[source];
      rgba[target + 1] = rgb[source + 1];
      rgba[target + 2] = rgb[source + 2];
      rgba[target + 3] = 255;
      source += 3;
      target += 4;
    }
  }
}
