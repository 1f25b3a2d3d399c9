// The gateway's doors and its robustness: requests without the token are refused (401) and
// counted, a foreign Origin is refused (403), and hostile WebSocket clients (random frames,
// an oversized message, a broken frame, one that never reads) leave the gateway serving a
// well-behaved client all along.
//   node access_test.mjs http://127.0.0.1:PORT TOKEN
import net from "node:net";

import protocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

import { check, run, section, waitFor } from "./checks.mjs";

const { FoxgloveClient } = protocol;
const [base, token] = process.argv.slice(2);
const wsBase = base.replace(/^http/, "ws");
const subprotocol = FoxgloveClient.SUPPORTED_SUBPROTOCOL;

/** The status of a WebSocket handshake (101 when it opens). */
function handshakeStatus(url, options = {}) {
  return new Promise((resolve) => {
    const socket = new WebSocket(url, [subprotocol], options);
    socket.on("open", () => {
      socket.close();
      resolve(101);
    });
    socket.on("unexpected-response", (_request, response) => resolve(response.statusCode));
    socket.on("error", () => resolve(0));
  });
}

/** A well-behaved client that follows /gateway/status and /flag/state and counts messages. */
async function watcher() {
  const heard = { channels: [], count: 0, gatewayStatus: null };
  const client = new FoxgloveClient({ ws: new WebSocket(`${wsBase}/?token=${token}`, [subprotocol]) });
  client.on("advertise", (channels) => heard.channels.push(...channels));
  await waitFor(() => heard.channels.length > 0, 10, "advertisements");
  const statusId = heard.channels.find((c) => c.topic === "/gateway/status").id;
  const stateId = heard.channels.find((c) => c.topic === "/flag/state").id;
  const statusSubscription = client.subscribe(statusId);
  client.subscribe(stateId);
  client.on("message", ({ subscriptionId, data }) => {
    heard.count += 1;
    if (subscriptionId === statusSubscription) heard.gatewayStatus = JSON.parse(new TextDecoder().decode(data));
  });
  return { client, heard };
}

/** Resolves once `heard` has counted `more` further messages. */
async function stillServed(heard, what) {
  const before = heard.count;
  await waitFor(() => heard.count >= before + 5, 20, `messages to the good client ${what}`);
  return true;
}

/** Opens a raw WebSocket (ws) that we can abuse; resolves once open. */
function rawSocket() {
  return new Promise((resolve, reject) => {
    const socket = new WebSocket(`${wsBase}/?token=${token}`, [subprotocol]);
    socket.on("open", () => resolve(socket));
    socket.on("error", reject);
  });
}

function closed(socket) {
  return new Promise((resolve) => {
    if (socket.readyState === WebSocket.CLOSED) resolve(true);
    socket.on("close", () => resolve(true));
  });
}

await run(async () => {
  section("the token");
  let response = await fetch(`${base}/`);
  check("the page without the token: 401", response.status === 401, response.status);
  response = await fetch(`${base}/?token=wrong-${token}`);
  check("the page with a wrong token: 401", response.status === 401, response.status);
  response = await fetch(`${base}/?token=${token}`);
  const cookie = response.headers.get("set-cookie") ?? "";
  check("the page with the token: 200, and a cookie for its own requests",
        response.status === 200 && cookie.includes(`flagsim_token=${token}`) && cookie.includes("HttpOnly"),
        { status: response.status, cookie });
  response = await fetch(`${base}/app.js`, { headers: { cookie: `flagsim_token=${token}` } });
  check("the script with the cookie: 200", response.status === 200, response.status);
  response = await fetch(`${base}/app.js`, { headers: { authorization: `Bearer ${token}` } });
  check("the script with a bearer header: 200", response.status === 200, response.status);
  response = await fetch(`${base}/recordings/none.lcmlog?token=${token}`);
  check("a recording that does not exist: 404", response.status === 404, response.status);
  check("a WebSocket without the token: 401", (await handshakeStatus(`${wsBase}/`)) === 401);
  check("a WebSocket with the token: open", (await handshakeStatus(`${wsBase}/?token=${token}`)) === 101);

  section("the origin");
  check("a page of another site may not connect: 403",
        (await handshakeStatus(`${wsBase}/?token=${token}`, { origin: "https://evil.example" })) === 403);
  check("the gateway's own page may",
        (await handshakeStatus(`${wsBase}/?token=${token}`, { origin: base })) === 101);
  check("a WebSocket without the subprotocol: 400", await new Promise((resolve) => {
    const socket = new WebSocket(`${wsBase}/?token=${token}`);
    socket.on("unexpected-response", (_request, r) => resolve(r.statusCode === 400));
    socket.on("open", () => resolve(false));
    socket.on("error", () => resolve(false));
  }));

  section("hostile clients beside a good one");
  const { client, heard } = await watcher();
  await stillServed(heard, "at first");

  const noisy = await rawSocket();
  for (let i = 0; i < 500; i += 1) {
    const bytes = new Uint8Array(1 + Math.floor(Math.random() * 200)).map(() => Math.floor(Math.random() * 256));
    noisy.send(bytes);
    noisy.send(i % 2 ? "{\"op\": \"subscribe\", \"subscriptions\": [{\"id\": 1, \"channelId\": 99}]}" : "}{ not json");
  }
  check("random binary and text messages", await stillServed(heard, "while one sends garbage"));
  check("  and that client is answered, not dropped", noisy.readyState === WebSocket.OPEN);

  const big = await rawSocket();
  big.send(new Uint8Array(1024 * 1024));
  check("a 1 MiB message closes its sender", await closed(big));
  check("  while the good client is served", await stillServed(heard, "after an oversized message"));

  const broken = net.connect(new URL(base).port, "127.0.0.1");
  await new Promise((resolve) => broken.on("connect", resolve));
  broken.write(`GET /?token=${token} HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n` +
               `Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n` +
               `Sec-WebSocket-Protocol: ${subprotocol}\r\n\r\n`);
  broken.write(Buffer.from([0x82, 0xff, 0, 0, 0, 0]));  // a frame header that claims 2^63 bytes, cut off
  broken.end();
  check("a truncated, lying frame", await stillServed(heard, "after a broken frame"));

  const sleeper = await rawSocket();
  sleeper.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 1, channelId: 1 }, { id: 2, channelId: 2 }] }));
  sleeper._socket.pause();  // stops reading: the gateway's writes to it stall
  await stillServed(heard, "beside a client that does not read");
  const dropped = await waitFor(() => heard.gatewayStatus?.clients_dropped >= 1 && heard.gatewayStatus, 60,
                                "the gateway dropping the client that does not read");
  check("a client that stops reading is dropped", dropped.clients_dropped >= 1, dropped);
  check("  and the good client is still served", await stillServed(heard, "after the drop"));
  // Three 401s above (the page without the token and with a wrong one, a WebSocket without it)
  // and a 403 (the foreign origin).
  const counted = await waitFor(() => heard.gatewayStatus?.unauthorized >= 3 && heard.gatewayStatus, 20, "counts");
  check("refusals are counted: 401s and 403s", counted.unauthorized === 3 && counted.forbidden === 1, counted);
  sleeper.terminate();
  noisy.close();
  client.close();
});
