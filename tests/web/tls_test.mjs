// The gateway beyond loopback, over TLS: the page and the WebSocket over HTTPS and WSS for a
// client that trusts the gateway's certificate, a refusal from a client holding another one,
// and a clear answer to plain HTTP on the TLS port.
//   node tls_test.mjs PORT TOKEN CERT.pem OTHER_CERT.pem
import http from "node:http";
import https from "node:https";
import { readFileSync } from "node:fs";

import WebSocket from "ws";

import { check, run, section } from "./checks.mjs";

const [port, token, certificate, other] = process.argv.slice(2);
const ca = readFileSync(certificate);

/** GET over `module` (http or https) with `options`: { status, body } or { error }. */
function get(module, path, options = {}) {
  return new Promise((resolve) => {
    const request = module.get({ host: "127.0.0.1", port: Number(port), path, ...options }, (response) => {
      let body = "";
      response.on("data", (chunk) => (body += chunk));
      response.on("end", () => resolve({ status: response.statusCode, body }));
    });
    request.on("error", (error) => resolve({ error: error.message, code: error.code }));
  });
}

await run(async () => {
  section("TLS beyond loopback");
  const page = await get(https, `/?token=${token}`, { ca });
  check("the page over HTTPS, for a client that trusts the printed certificate", page.status === 200 && page.body.includes("flagsim"), page);
  const refused = await get(https, `/?token=${token}`, { ca: readFileSync(other) });
  check("a client that holds another certificate refuses the connection", Boolean(refused.error) && refused.status === undefined, refused);
  const plain = await get(http, `/?token=${token}`);
  check("plain HTTP on the TLS port gets a clear refusal naming https://", plain.status === 400 && /speaks HTTPS.*open https:\/\//.test(plain.body), plain);
  const info = await new Promise((resolve) => {
    const socket = new WebSocket(`wss://127.0.0.1:${port}/?token=${token}`, ["foxglove.websocket.v1"], { ca });
    socket.on("message", (data) => {
      resolve(JSON.parse(String(data)));
      socket.close();
    });
    socket.on("error", (error) => resolve({ error: error.message }));
  });
  check("the Foxglove WebSocket over WSS says who it is", info.op === "serverInfo", info);
});
