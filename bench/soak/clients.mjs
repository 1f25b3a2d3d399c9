// The soak's protocol clients: COUNT Foxglove WebSocket clients (Foxglove's own client library)
// on the gateway, each subscribed to every channel it advertises and reading all it is sent, until
// SIGINT or SIGTERM (or SECONDS). Counts each client's messages, bytes and unexpected closes, and follows the server's
// real-time factor (/flag/status) and the gateway's own figures (/gateway/status) all along.
// Writes a JSON summary.
//   node clients.mjs WS_URL COUNT SECONDS OUT.json
import { createRequire } from "node:module";
import { writeFileSync } from "node:fs";

const requireFromTests = createRequire(new URL("../../tests/web/package.json", import.meta.url));
const { FoxgloveClient } = requireFromTests("@foxglove/ws-protocol");
const WebSocket = requireFromTests("ws");

const [wsUrl, countText, secondsText, outPath] = process.argv.slice(2);
const decoder = new TextDecoder();

/** A client that takes every channel; its counts, and the JSON of the topics in `follow`. */
async function reader(index, follow) {
  const state = { index, messages: 0, bytes: 0, closes: 0, errors: 0, channels: [], series: {} };
  const client = new FoxgloveClient({ ws: new WebSocket(wsUrl, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  const topicOf = new Map();
  client.on("advertise", (channels) => {
    for (const channel of channels) {
      state.channels.push(channel);
      topicOf.set(client.subscribe(channel.id), channel.topic);
    }
  });
  client.on("message", ({ subscriptionId, data }) => {
    state.messages += 1;
    state.bytes += data.byteLength;
    const topic = topicOf.get(subscriptionId);
    if (follow.includes(topic)) (state.series[topic] ??= []).push(JSON.parse(decoder.decode(data)));
  });
  client.on("close", () => { state.closes += 1; });
  client.on("error", () => { state.errors += 1; });
  state.close = () => client.close();
  return state;
}

const count = Number(countText);
const seconds = Number(secondsText);
const readers = [await reader(0, ["/flag/status", "/gateway/status"])];
for (let i = 1; i < count; i += 1) readers.push(await reader(i, []));
await new Promise((resolve) => {
  setTimeout(resolve, seconds * 1000);
  process.on("SIGINT", resolve);
  process.on("SIGTERM", resolve);
});
const closesBeforeEnd = readers.map((r) => r.closes);
for (const r of readers) r.close();

const statuses = readers[0].series["/flag/status"] ?? [];
const gateway = readers[0].series["/gateway/status"] ?? [];
const factors = statuses.map((s) => s.real_time_factor).filter((f) => Number.isFinite(f));
const sorted = [...factors].sort((a, b) => a - b);
const summary = {
  clients: readers.map((r) => ({ messages: r.messages, bytes: r.bytes, channels: r.channels.length,
                                 closed_early: closesBeforeEnd[r.index], errors: r.errors })),
  real_time_factor: {
    samples: factors.length,
    mean: factors.reduce((a, b) => a + b, 0) / Math.max(factors.length, 1),
    p5: sorted[Math.floor(sorted.length * 0.05)] ?? null,
    min: sorted[0] ?? null,
  },
  gateway_last: gateway.at(-1) ?? null,
};
writeFileSync(outPath, JSON.stringify(summary, null, 2) + "\n");
console.log(`${count} clients: ${summary.clients.map((c) => c.messages).join(" ")} messages; ` +
            `real-time factor mean ${summary.real_time_factor.mean.toFixed(3)}, p5 ${summary.real_time_factor.p5}, ` +
            `min ${summary.real_time_factor.min}; closed early: ${closesBeforeEnd.reduce((a, b) => a + b, 0)}`);
process.exit(0);
