import assert from "node:assert/strict";
import { test } from "node:test";
import { isGatewayName, relativeName, relativeParameter, serverName, serverParameter, ServerScope } from "../src/server_scope.js";

/// What the scope needs of a Connection, recording what it is asked.
class FakeConnection {
  constructor() {
    this.connected = true;
    this.serverInfo = { name: "gateway" };
    this.listeners = new Map();
    this.subscribed = [];
    this.unsubscribed = [];
    this.calls = [];
    this.parameterSets = [];
    this.parameterSubscriptions = [];
  }

  on(event, listener) {
    if (!this.listeners.has(event)) this.listeners.set(event, new Set());
    this.listeners.get(event).add(listener);
  }

  off(event, listener) {
    this.listeners.get(event)?.delete(listener);
  }

  emit(event, ...args) {
    for (const listener of this.listeners.get(event) ?? []) listener(...args);
  }

  subscribe(topic) {
    this.subscribed.push(topic);
  }

  unsubscribe(topic) {
    this.unsubscribed.push(topic);
  }

  call(name, request) {
    this.calls.push([name, request]);
    return Promise.resolve({ accepted: true });
  }

  setParameters(parameters) {
    this.parameterSets.push(parameters);
    return { id: "page-1", promise: Promise.resolve([...parameters, { name: "/BETA_/stiffness", value: 9 }]) };
  }

  subscribeParameters(names) {
    this.parameterSubscriptions.push(names);
  }
}

/// Messages a scope passes on, as [topic, data].
function heard(scope) {
  const messages = [];
  scope.on("message", (topic, data) => messages.push([topic, data]));
  return messages;
}

test("names: a server's under its path, the gateway's own unchanged, the empty path the identity", () => {
  assert.equal(serverName("/ALPHA_", "/flag/tiles"), "/ALPHA_/flag/tiles");
  assert.equal(serverName("/ALPHA_", "/gateway/status"), "/gateway/status");
  assert.equal(serverName("", "/flag/wind"), "/flag/wind");
  assert.equal(relativeName("/ALPHA_", "/ALPHA_/flag/status"), "/flag/status");
  assert.equal(relativeName("/ALPHA_", "/BETA_/flag/status"), null);
  assert.equal(relativeName("/ALPHA_", "/ALPHA_X/flag/status"), null, "a prefix that starts the same is another server");
  assert.equal(relativeName("/ALPHA_", "/gateway/servers"), "/gateway/servers");
  assert.equal(relativeName("", "/flag/status"), "/flag/status");
  assert.equal(serverParameter("/ALPHA_", "stiffness"), "/ALPHA_/stiffness");
  assert.equal(serverParameter("", "stiffness"), "stiffness");
  assert.equal(relativeParameter("/ALPHA_", "/ALPHA_/stiffness"), "stiffness");
  assert.equal(relativeParameter("/ALPHA_", "/BETA_/stiffness"), null);
  assert.equal(relativeParameter("", "stiffness"), "stiffness");
  assert.ok(isGatewayName("/gateway/status"));
  assert.ok(!isGatewayName("/gateway/flag/tiles"), "the names of a server whose prefix is 'gateway'");
  assert.equal(relativeName("/gateway", "/gateway/flag/tiles"), "/flag/tiles");
});

test("with a path, topics go out under it and only that server's messages come back, named as the panels name them", () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection, "/ALPHA_");
  const messages = heard(scope);
  scope.subscribe("/flag/tiles");
  scope.subscribe("/gateway/status");
  assert.deepEqual(connection.subscribed, ["/ALPHA_/flag/tiles", "/gateway/status"]);
  connection.emit("message", "/ALPHA_/flag/tiles", "alpha's tiles");
  connection.emit("message", "/BETA_/flag/tiles", "beta's tiles");
  connection.emit("message", "/gateway/status", "the gateway's");
  assert.deepEqual(messages, [["/flag/tiles", "alpha's tiles"], ["/gateway/status", "the gateway's"]]);
});

test("services are called under the path", async () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection, "/BETA_");
  assert.deepEqual(await scope.call("/flag/wind", { velocity: [1, 0, 0] }), { accepted: true });
  await scope.call("/flag/refresh");
  assert.deepEqual(connection.calls, [["/BETA_/flag/wind", { velocity: [1, 0, 0] }], ["/BETA_/flag/refresh", {}]]);
});

test("parameters go out as path/name and come back by their own name, other servers' dropped", async () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection, "/ALPHA_");
  const updates = [];
  scope.on("parameterValues", (values, id) => updates.push([values, id]));
  scope.subscribeParameters(["stiffness", "design"]);
  assert.deepEqual(connection.parameterSubscriptions, [["/ALPHA_/stiffness", "/ALPHA_/design"]]);
  const { id, promise } = scope.setParameters([{ name: "stiffness", value: 1500 }]);
  assert.equal(id, "page-1");
  assert.deepEqual(connection.parameterSets, [[{ name: "/ALPHA_/stiffness", value: 1500 }]]);
  assert.deepEqual(await promise, [{ name: "stiffness", value: 1500 }], "the answer holds this server's values only");
  connection.emit("parameterValues", [{ name: "/ALPHA_/damping", value: 0.1 }, { name: "/BETA_/damping", value: 0.2 }], "x");
  connection.emit("parameterValues", [{ name: "/BETA_/damping", value: 0.3 }]);
  assert.deepEqual(updates, [[[{ name: "damping", value: 0.1 }], "x"]], "values of another server alone are not passed on");
});

test("the empty path (a gateway serving one server) changes nothing", async () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection, "");
  const messages = heard(scope);
  scope.subscribe("/flag/status");
  await scope.call("/flag/set", { reset: true });
  scope.subscribeParameters(["stiffness"]);
  connection.emit("message", "/flag/status", 1);
  connection.emit("message", "/gateway/status", 2);
  assert.deepEqual(connection.subscribed, ["/flag/status"]);
  assert.deepEqual(connection.calls, [["/flag/set", { reset: true }]]);
  assert.deepEqual(connection.parameterSubscriptions, [["stiffness"]]);
  assert.deepEqual(messages, [["/flag/status", 1], ["/gateway/status", 2]]);
  assert.equal(scope.connected, true);
  assert.equal(scope.serverInfo.name, "gateway");
});

test("before its path is known a scope holds what is wanted and passes on the gateway's own names only", async () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection);
  const messages = heard(scope);
  scope.subscribe("/flag/tiles");
  scope.subscribe("/gateway/servers");
  scope.subscribeParameters(["stiffness"]);
  assert.deepEqual(connection.subscribed, ["/gateway/servers"]);
  assert.deepEqual(connection.parameterSubscriptions, []);
  await assert.rejects(scope.call("/flag/wind", {}), /no server chosen yet/);
  await assert.rejects(scope.setParameters([{ name: "stiffness", value: 1 }]).promise, /no server chosen yet/);
  connection.emit("message", "/flag/tiles", "a single server's");
  connection.emit("message", "/gateway/servers", "the list");
  assert.deepEqual(messages, [["/gateway/servers", "the list"]]);
  scope.setPath("/ALPHA_");
  assert.deepEqual(connection.subscribed, ["/gateway/servers", "/ALPHA_/flag/tiles"]);
  assert.deepEqual(connection.parameterSubscriptions, [["/ALPHA_/stiffness"]]);
  assert.throws(() => scope.setPath("/BETA_"), /already has the path/);
});

test("close takes back the scope's subscriptions and listeners", () => {
  const connection = new FakeConnection();
  const scope = new ServerScope(connection, "/BETA_");
  const messages = heard(scope);
  const states = [];
  scope.on("state", (connected) => states.push(connected));
  scope.subscribe("/flag/tiles");
  scope.close();
  assert.deepEqual(connection.unsubscribed, ["/BETA_/flag/tiles"]);
  connection.emit("message", "/BETA_/flag/tiles", "late");
  connection.emit("state", false);
  assert.deepEqual(messages, []);
  assert.deepEqual(states, []);
  assert.equal([...connection.listeners.values()].reduce((sum, set) => sum + set.size, 0), 0);
});
