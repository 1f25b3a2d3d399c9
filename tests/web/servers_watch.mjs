// Watches one gateway of several servers (flagctl serve) as Foxglove clients would: CLIENTS
// connections, each subscribed to the pictures of the servers named (with --spread, connection k
// to the k-th server's only, round the list), for SECONDS; then one line of JSON: the servers the
// gateway listed, each connection's tile updates a second per server and their share of the
// frames drawn meanwhile (by the frame ids the updates carry), and, with --steer PREFIX, the
// answer to damping=0.07 set on that server only.
//   node servers_watch.mjs ws://127.0.0.1:PORT/ --servers ALPHA_,BETA_ [--clients 1]
//        [--seconds 4] [--steer ALPHA_] [--spread]
// Exit 0 with the line, 1 when the gateway did not offer every server named within 20 s.
import protocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

import { waitFor } from "./checks.mjs";

const { FoxgloveClient } = protocol;

function options(argv) {
  const named = { servers: "", clients: "1", seconds: "4", steer: "", spread: false };
  for (let i = 1; i < argv.length; i += 1) {
    const name = argv[i].replace(/^--/, "");
    named[name] = name === "spread" ? true : argv[++i];
  }
  return { url: argv[0], servers: named.servers.split(",").filter(Boolean), clients: Number(named.clients),
    seconds: Number(named.seconds), steer: named.steer, spread: named.spread };
}

/// One connection: the channels and services it was offered, and tile updates counted by server.
function connect(url) {
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  const link = { client, channels: new Map(), services: new Map(), updates: new Map(), bySubscription: new Map(),
    servers: null, frames: new Map(), answers: new Map() };
  client.on("advertise", (channels) => channels.forEach((channel) => link.channels.set(channel.topic, channel)));
  client.on("advertiseServices", (services) => services.forEach((service) => link.services.set(service.name, service)));
  client.on("message", ({ subscriptionId, data }) => {
    const topic = link.bySubscription.get(subscriptionId);
    if (topic === "/gateway/servers") link.servers = JSON.parse(new TextDecoder().decode(data)).servers;
    else if (topic) {
      link.updates.set(topic, (link.updates.get(topic) ?? 0) + 1);
      // The update's frame id (flagsim.TileUpdate, docs/live-view.md): the frames its server drew
      // from the first update taken to the last, skipped ones too.
      const frame = Number(data.getBigUint64(16, true));
      const span = link.frames.get(topic) ?? { first: frame, last: frame };
      link.frames.set(topic, { first: span.first, last: frame });
    }
  });
  client.on("serviceCallResponse", (answer) => link.answers.set(answer.callId, JSON.parse(new TextDecoder().decode(answer.data))));
  return link;
}

function subscribe(link, topic) {
  link.bySubscription.set(link.client.subscribe(link.channels.get(topic).id), topic);
}

const { url, servers, clients, seconds, steer, spread } = options(process.argv.slice(2));
try {
  const links = Array.from({ length: clients }, () => connect(url));
  const tiles = servers.map((prefix) => `/${prefix}/flag/tiles`);
  const watched = (k) => (spread ? [tiles[k % tiles.length]] : tiles);
  for (const [k, link] of links.entries()) {
    await waitFor(() => link.channels.has("/gateway/servers") && tiles.every((topic) => link.channels.has(topic)),
      20, `the gateway's offer of ${servers.join(", ")}`);
    subscribe(link, "/gateway/servers");
    watched(k).forEach((topic) => subscribe(link, topic));
  }
  const started = Date.now();
  let answer = null;
  if (steer) {
    const service = links[0].services.get(`/${steer}/flag/set`);
    links[0].client.sendServiceCallRequest({ serviceId: service.id, callId: 1, encoding: "json",
      data: new TextEncoder().encode(JSON.stringify({ parameters: { damping: 0.07 } })) });
    answer = await waitFor(() => links[0].answers.get(1), 20, `the answer of /${steer}/flag/set`);
  }
  await new Promise((resolve) => setTimeout(resolve, Math.max(0, seconds * 1000 - (Date.now() - started))));
  const elapsed = (Date.now() - started) / 1000;
  const rates = links.map((link, k) => Object.fromEntries(
    watched(k).map((topic) => [topic.split("/")[1], +((link.updates.get(topic) ?? 0) / elapsed).toFixed(2)])));
  // Of the frames each server drew while a connection watched it, the share it was sent.
  const shares = links.map((link, k) => Object.fromEntries(watched(k).map((topic) => {
    const span = link.frames.get(topic);
    return [topic.split("/")[1], span ? +((link.updates.get(topic) ?? 0) / (span.last - span.first + 1)).toFixed(3) : 0];
  })));
  console.log(JSON.stringify({ servers: links[0].servers, updates_per_second: rates,
    share_of_frames: shares, steer: answer }));
  links.forEach((link) => link.client.close());
  process.exit(0);
} catch (error) {
  console.error(`servers_watch: ${error.message}`);
  process.exit(1);
}
