// A Foxglove WebSocket client the project did not write (@foxglove/ws-protocol, the protocol's
// own) against flagctl serve: it reads the advertised channels, subscribes to the image and
// the status, calls a command service, and gets and sets a parameter.
//   node foxglove_client_test.mjs ws://127.0.0.1:PORT/?token=T
import protocol from "@foxglove/ws-protocol";
import WebSocket from "ws";

import { check, run, section, waitFor } from "./checks.mjs";

const { FoxgloveClient } = protocol;
const url = process.argv[2];

/** A connected client and everything it has heard, by kind. */
async function connect() {
  const heard = { channels: [], services: [], messages: new Map(), values: [], responses: new Map(), statuses: [] };
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  client.on("serverInfo", (info) => (heard.serverInfo = info));
  client.on("advertise", (channels) => heard.channels.push(...channels));
  client.on("advertiseServices", (services) => heard.services.push(...services));
  client.on("message", ({ subscriptionId, data }) => {
    const list = heard.messages.get(subscriptionId) ?? [];
    list.push(new TextDecoder().decode(data));
    heard.messages.set(subscriptionId, list);
  });
  client.on("parameterValues", (event) => heard.values.push(event));
  client.on("serviceCallResponse", (response) => heard.responses.set(response.callId, response));
  client.on("status", (status) => heard.statuses.push(status));
  client.on("error", (error) => heard.statuses.push({ level: 2, message: String(error) }));
  await waitFor(() => heard.serverInfo && heard.channels.length > 0 && heard.services.length > 0, 10, "greeting");
  return { client, heard };
}

const topic = (heard, name) => heard.channels.find((channel) => channel.topic === name);
const service = (heard, name) => heard.services.find((s) => s.name === name);

await run(async () => {
  section("connect and read the advertisements");
  const { client, heard } = await connect();
  const capabilities = heard.serverInfo.capabilities;
  check("serverInfo offers parameters, services and client publishing",
        ["parameters", "parametersSubscribe", "services", "clientPublish"].every((c) => capabilities.includes(c)),
        capabilities);
  const image = topic(heard, "/flag/image");
  check("the image is a foxglove.CompressedImage in JSON", image?.schemaName === "foxglove.CompressedImage" &&
        image?.encoding === "json", image);
  check("the 3D scene is a foxglove.SceneUpdate", topic(heard, "/flag/scene")?.schemaName === "foxglove.SceneUpdate");
  const status = topic(heard, "/flag/status");
  check("the status channel has a JSON schema", JSON.parse(status.schema).title === "flagsim.Status");

  section("subscribe to the image and the status");
  const imageSubscription = client.subscribe(image.id);
  const statusSubscription = client.subscribe(status.id);
  const frames = await waitFor(() => heard.messages.get(imageSubscription), 20, "image");
  const frame = JSON.parse(frames[0]);
  const jpeg = Buffer.from(frame.data, "base64");
  check("an image arrives as a JPEG", frame.format === "jpeg" && jpeg[0] === 0xff && jpeg[1] === 0xd8,
        { format: frame.format, bytes: jpeg.length });
  const statuses = await waitFor(() => heard.messages.get(statusSubscription), 20, "status");
  const health = JSON.parse(statuses[0]);
  check("the status carries the real-time factor and the integrator",
        typeof health.real_time_factor === "number" && typeof health.integrator === "string", health);
  client.unsubscribe(imageSubscription);

  section("parameters");
  client.getParameters([], "all");
  const all = await waitFor(() => heard.values.find((v) => v.id === "all"), 10, "parameter values");
  const stiffness = all.parameters.find((p) => p.name === "stiffness");
  check("getParameters lists stiffness with a number", typeof stiffness?.value === "number", stiffness);
  const integrator = all.parameters.find((p) => p.name === "integrator");
  check("a choice is its name", typeof integrator?.value === "string", integrator);
  client.setParameters([{ name: "stiffness", value: 2100 }], "set");
  const set = await waitFor(() => heard.values.find((v) => v.id === "set"), 10, "the answer to setParameters");
  check("setParameters answers with the new value", set.parameters[0]?.value === 2100, set);
  client.setParameters([{ name: "stiffness", value: -1 }], "bad");
  const bad = await waitFor(() => heard.values.find((v) => v.id === "bad"), 10, "the answer to a bad setParameters");
  const why = heard.statuses.find((s) => s.id === "setParameters:bad");
  check("a value out of range is refused with the server's reason",
        why?.level === 2 && why.message.startsWith("stiffness:"), why);
  check("  and nothing changes", bad.parameters[0]?.value === 2100, bad);

  section("a command through a service");
  const wind = service(heard, "/flag/wind");
  client.sendServiceCallRequest({
    serviceId: wind.id, callId: 1, encoding: "json",
    data: new TextEncoder().encode(JSON.stringify({ velocity: [7, 0, 2], gust: 0.2 })),
  });
  const response = await waitFor(() => heard.responses.get(1), 10, "the wind service's response");
  const result = JSON.parse(new TextDecoder().decode(response.data));
  check("the wind service answers with the server's ACK", result.accepted === true && result.channel === "WIND",
        result);
  client.close();
});
