// Calls the gateway's recorder (the /flag/record service) once, with Foxglove's own protocol
// client, and prints its JSON answer on one line: the integration tests' way to start, stop and
// watch a recording of `flagctl serve` from a shell.
//   node record_call.mjs ws://127.0.0.1:PORT/?token=T start|stop|status
// Exit 0 with the answer, 1 when the gateway did not give one within 10 s.
import protocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

import { waitFor } from "./checks.mjs";

const { FoxgloveClient } = protocol;
const [url, action] = process.argv.slice(2);

try {
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  const services = [];
  let response;
  client.on("advertiseServices", (advertised) => services.push(...advertised));
  client.on("serviceCallResponse", (answer) => (response = answer));
  const record = await waitFor(() => services.find((service) => service.name === "/flag/record"), 10, "/flag/record");
  client.sendServiceCallRequest({
    serviceId: record.id, callId: 1, encoding: "json", data: new TextEncoder().encode(JSON.stringify({ action })),
  });
  await waitFor(() => response, 10, "answer from /flag/record");
  console.log(new TextDecoder().decode(response.data));
  client.close();
  process.exit(0);
} catch (error) {
  console.error(`record_call: ${error.message}`);
  process.exit(1);
}
