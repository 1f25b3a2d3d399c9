// The live view's figures, in one run against a running flagd and flagctl serve:
//   - frames a second one browser shows against the bus's frame rate (the server's STATUS);
//   - a command's round trip as a person sees it: the page sends a CAMERA move (a key press),
//     until the first frame drawn from the moved camera is on its canvas;
//   - the server's frame rate and real-time factor with 0, 1 and 8 browsers (headless
//     Chromium pages), and with 8 protocol clients that only read (Node), which leaves the
//     browsers' own CPU out;
//   - the gateway's CPU and resident memory, and bytes a second per client against the bus.
// Prints a table and writes it as JSON.
//   node measure.mjs PAGE_URL SECONDS OUT.json
import { createRequire } from "node:module";

const requireFromTests = createRequire(new URL("../../tests/web/package.json", import.meta.url));
const { chromium } = requireFromTests("playwright-core");
const { FoxgloveClient } = requireFromTests("@foxglove/ws-protocol");
const WebSocket = requireFromTests("ws");
const { writeFileSync } = await import("node:fs");

const [pageUrl, secondsText, outPath] = process.argv.slice(2);
const seconds = Number(secondsText);
const wsUrl = pageUrl.replace(/^http/, "ws");
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const mean = (values) => values.reduce((sum, v) => sum + v, 0) / Math.max(values.length, 1);

/** A protocol client following the given topics; `latest[topic]` is the newest JSON, `bytes` all it read. */
async function follower(topics) {
  const state = { latest: {}, history: {}, bytes: 0, channels: [] };
  const client = new FoxgloveClient({ ws: new WebSocket(wsUrl, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  client.on("advertise", (channels) => state.channels.push(...channels));
  while (state.channels.length === 0) await sleep(20);
  const topicOf = new Map();
  for (const topic of topics) {
    const channel = state.channels.find((c) => c.topic === topic);
    topicOf.set(client.subscribe(channel.id), topic);
  }
  client.on("message", ({ subscriptionId, data }) => {
    state.bytes += data.byteLength;
    const topic = topicOf.get(subscriptionId);
    if (topic === "/flag/tiles") return;
    const value = JSON.parse(new TextDecoder().decode(data));
    state.latest[topic] = value;
    (state.history[topic] ??= []).push(value);
  });
  state.close = () => client.close();
  return state;
}

/** Server and gateway over the next `seconds`: STATUS means, the gateway's CPU share and memory. */
async function window(monitor) {
  monitor.history["/flag/status"] = [];
  monitor.history["/gateway/status"] = [];
  const start = monitor.latest["/gateway/status"];
  await sleep(seconds * 1000);
  const statuses = monitor.history["/flag/status"];
  const end = monitor.latest["/gateway/status"];
  return {
    frame_rate: mean(statuses.map((s) => s.frame_rate_hz)),
    real_time_factor: mean(statuses.map((s) => s.real_time_factor)),
    bus_bytes_per_second: mean(statuses.map((s) => s.bytes_per_second)),
    gateway_cpu: (end.cpu_seconds - start.cpu_seconds) / (end.uptime - start.uptime),
    gateway_bytes_per_second: mean(monitor.history["/gateway/status"].slice(-seconds).map((g) => g.bytes_per_second)),
    gateway_resident_mb: end.resident_bytes / 1e6,
    clients_dropped: end.clients_dropped - start.clients_dropped,
    per_client_bytes: end.per_client.map((c) => c.bytes_per_second),
    per_client_skipped: end.per_client.map((c) => c.frames_skipped),
  };
}

async function openPage(browser) {
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  await page.goto(pageUrl);
  await page.waitForFunction(() => window.flagsim?.framesShown >= 3, null, { timeout: 30000 });
  return page;
}

/** Over the window, on the page's clock: frames it showed a second, and frames the server made
 *  a second (frame ids advance by one per frame drawn). */
async function shownRate(page) {
  const read = () => page.evaluate(() => [window.flagsim.framesShown, window.flagsim.frame.id, performance.now()]);
  const before = await read();
  await sleep(seconds * 1000);
  const after = await read();
  const elapsed = (after[2] - before[2]) / 1000;
  return { shown: (after[0] - before[0]) / elapsed, made: (after[1] - before[1]) / elapsed };
}

// In the page: a key press turns the camera (rotate_y); the time until a frame whose id is at
// least the first frame drawn with the new camera (/flag/camera's frame_id) has been shown.
async function roundTrips(page, trials) {
  const times = [];
  await page.locator("#stage").focus();
  for (let trial = 0; trial < trials; trial += 1) {
    const elapsed = await page.evaluate(async (key) => {
      const before = window.flagsim.camera.frame_id;
      const start = performance.now();
      document.dispatchEvent(new KeyboardEvent("keydown", { key, bubbles: true }));
      await window.flagsim.waitForFrame(
        (frame) => window.flagsim.camera.frame_id > before && frame.id >= window.flagsim.camera.frame_id, 5000);
      return performance.now() - start;
    }, trial % 2 ? "y" : "Y");
    times.push(elapsed);
    await sleep(150);
  }
  return times;
}

const results = {};
const monitor = await follower(["/flag/status", "/gateway/status"]);
await sleep(2500);

results.none = await window(monitor);
const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"],
});
const pages = [await openPage(browser)];
const [shown, one] = await Promise.all([shownRate(pages[0]), window(monitor)]);
results.one = { ...one, shown_frame_rate: shown.shown, made_frame_rate: shown.made };
const trips = await roundTrips(pages[0], 21);
results.round_trip_ms = { median: median(trips), p90: [...trips].sort((a, b) => a - b)[Math.floor(trips.length * 0.9)], all: trips };
for (let i = 1; i < 8; i += 1) pages.push(await openPage(browser));
const shownEach = [];
const [eight] = await Promise.all([window(monitor), ...pages.map(async (page) => shownEach.push(await shownRate(page)))]);
results.eight = { ...eight, shown_frame_rate: mean(shownEach.map((r) => r.shown)),
                  made_frame_rate: mean(shownEach.map((r) => r.made)) };
await browser.close();
await sleep(2000);
const readers = [];
for (let i = 0; i < 8; i += 1) readers.push(await follower(["/flag/tiles", "/flag/state", "/flag/status"]));
await sleep(2000);
results.eight_readers = await window(monitor);
for (const reader of readers) reader.close();
monitor.close();

const row = (name, r) => [name, r.frame_rate.toFixed(1), r.real_time_factor.toFixed(3), r.shown_frame_rate?.toFixed(1) ?? "-",
  (100 * r.gateway_cpu).toFixed(1), r.gateway_resident_mb.toFixed(1),
  (r.gateway_bytes_per_second / 1e6).toFixed(2), String(r.clients_dropped),
  (r.bus_bytes_per_second / 1e6).toFixed(2)];
const table = [["clients", "server fps", "rtf", "shown fps", "gateway cpu %", "gateway MB", "sent MB/s", "dropped", "bus MB/s"],
  row("none", results.none), row("1 browser", results.one), row("8 browsers", results.eight),
  row("8 readers", results.eight_readers)];
for (const line of table) console.log(line.map((cell, i) => String(cell).padEnd(i === 0 ? 12 : 16)).join(""));
console.log(`frames one browser showed / frames the server made meanwhile (by frame id): ` +
            `${results.one.shown_frame_rate.toFixed(1)} / ${results.one.made_frame_rate.toFixed(1)} a second = ` +
            `${(100 * results.one.shown_frame_rate / results.one.made_frame_rate).toFixed(1)} %`);
console.log(`round trip, key press to the moved camera's first frame on the canvas: median ${results.round_trip_ms.median.toFixed(1)} ms, ` +
            `90th percentile ${results.round_trip_ms.p90.toFixed(1)} ms (${trips.length} trials)`);
writeFileSync(outPath, JSON.stringify(results, null, 2));
process.exit(0);
