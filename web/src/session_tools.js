// Snapshot, record, a link to the view, full screen.
//
//   Snapshot --(the picture's frame hash checked)--> the canvas as frame-ID.png, downloaded
//   Link     --> the address with this view (view_link.js), in the address bar and the clipboard
//   Full screen --> the picture alone on the screen (Esc leaves)
//   Record   --`/flag/record` start--> polled with status each second --stop--> download links,
//            with the page's token: the LCM log at once, then its MCAP (Foxglove, Lichtblick) and
//            MP4 as the gateway makes them (polled until each is ready or failed)
import { el, formatBytes, formatNumber } from "./dom.js";
import { viewLinkFor } from "./view_link.js";

const kPollPeriod = 1000;  ///< ms between record status polls

export class SessionTools {
  /// `frame()` returns { id, hashOk }; `pngBlob()` the picture as PNG; `withToken(url)`;
  /// `camera()` the newest `/flag/camera`; `stage` the element full screen shows.
  constructor({ container, connection, frame, pngBlob, withToken, toast, camera, stage }) {
    this.camera = camera;
    this.stage = stage;
    this.connection = connection;
    this.frame = frame;
    this.pngBlob = pngBlob;
    this.withToken = withToken;
    this.toast = toast;
    this.recording = false;
    this.pollTimer = null;
    this.snapshotButton = el("button", { type: "button", title: "download the picture as PNG (only a frame whose hash checked)", onclick: () => this.snapshot() }, "Snapshot");
    this.recordButton = el("button", { type: "button", class: "record", title: "record every channel of the server to an LCM log", onclick: () => this.toggleRecord() }, "Record");
    this.recordText = el("span", { class: "record-text" });
    this.downloads = el("span", { class: "downloads" });
    const link = el("button", { type: "button", title: "a link that opens this view (eye, target, field of view): in the address bar and copied", onclick: () => this.linkToView() }, "Link to view");
    const fullScreen = el("button", { type: "button", title: "the picture alone on the screen; Esc leaves", onclick: () => this.fullScreen() }, "Full screen");
    container.append(link, fullScreen, this.snapshotButton, this.recordButton, this.recordText, this.downloads);
    this.updateFrame();
  }

  /// Called on each frame shown: the snapshot is possible only with a checked frame.
  updateFrame() {
    const frame = this.frame();
    this.snapshotButton.disabled = !frame.hashOk;
  }

  /// The address of this view into the address bar, and the clipboard where the page may write.
  async linkToView() {
    const camera = this.camera();
    if (!camera?.eye) {
      this.toast("Link: no camera yet");
      return;
    }
    const link = viewLinkFor(window.location, camera);
    window.history.replaceState(null, "", link);
    try {
      await navigator.clipboard.writeText(link);
      this.toast("Link to this view copied (and in the address bar)");
    } catch {
      this.toast("Link to this view in the address bar (the clipboard is closed to this page)");
    }
  }

  fullScreen() {
    if (document.fullscreenElement) document.exitFullscreen();
    else this.stage.requestFullscreen?.().catch((error) => this.toast(`Full screen: ${error.message}`));
  }

  async snapshot() {
    const frame = this.frame();
    if (!frame.hashOk) {
      this.toast("Snapshot: the picture is not a checked frame yet");
      return;
    }
    const blob = await this.pngBlob();
    const url = URL.createObjectURL(blob);
    const link = el("a", { href: url, download: `flagsim-frame-${frame.id}.png` });
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
  }

  toggleRecord() {
    this.recordButton.disabled = true;
    this.connection.call("/flag/record", { action: this.recording ? "stop" : "start" }).then(
      (answer) => this.showRecord(answer),
      (error) => {
        this.recordText.textContent = `record: ${error.message}`;
        this.recordText.className = "record-text error";
      },
    ).finally(() => (this.recordButton.disabled = false));
  }

  /// A `/flag/record` answer: { recording, file, url, events, bytes, seconds, error, exports }.
  showRecord(answer) {
    this.recording = Boolean(answer?.recording);
    this.recordButton.textContent = this.recording ? "Stop" : "Record";
    this.recordButton.classList.toggle("active", this.recording);
    const figures = `${formatNumber(answer?.seconds ?? 0, 3)} s · ${answer?.events ?? 0} events · ${formatBytes(answer?.bytes ?? 0)}`;
    this.recordText.className = `record-text${answer?.error ? " error" : ""}`;
    this.recordText.textContent = answer?.error ? `record: ${answer.error}` : this.recording ? `● ${figures}` : answer?.url ? figures : "";
    const exports = this.recording ? {} : answer?.exports ?? {};
    this.showDownloads(this.recording ? "" : answer?.url, answer?.file, exports);
    clearTimeout(this.pollTimer);
    const making = Object.values(exports).some((entry) => entry.state === "waiting" || entry.state === "making");
    if (this.recording || making) this.pollTimer = setTimeout(() => this.poll(), kPollPeriod);
  }

  poll() {
    this.connection.call("/flag/record", { action: "status" }).then((answer) => this.showRecord(answer), () => {
      this.pollTimer = setTimeout(() => this.poll(), kPollPeriod);
    });
  }

  /// The log's link, and one per export: a link once ready, else what it is doing or why it failed.
  showDownloads(url, file, exports) {
    if (!url) {
      this.downloads.replaceChildren();
      return;
    }
    const link = (href, label) => el("a", { class: "download", href: this.withToken(href), download: href.split("/").pop() }, label);
    const parts = [link(url, `${String(file || url).split("/").pop()}`)];
    for (const [format, entry] of Object.entries(exports)) {
      const name = format.toUpperCase();
      if (entry.state === "ready") parts.push(link(entry.url, name));
      else if (entry.state === "failed") parts.push(el("span", { class: "export-state error", title: entry.error }, `${name} failed`));
      else parts.push(el("span", { class: "export-state" }, `${name} ${entry.state === "making" ? "being made" : "waiting"} …`));
    }
    this.downloads.replaceChildren(el("span", { class: "muted" }, "Download:"), ...parts);
  }
}
