// The page's one link to the gateway: a FoxgloveClient over a WebSocket, reconnected with
// backoff, with what the rest of the page needs by name rather than by protocol id.
//
//   gateway --advertise--> channels by topic --subscribe(topic)--> "message" (topic, DataView)
//   call(name, request) --serviceCallRequest(json)--> serviceCallResponse(json) --> promise
//   setParameters(values) --setParameters(id)--> parameterValues(id) | status(setParameters:id)
//
// Wanted topics and parameter subscriptions are kept across reconnects and renewed on each; a
// topic is wanted while any part of the page holds a subscription to it (server_scope.js, one per
// server shown, subscribes and unsubscribes through here).
// The client's own module: the package's index also brings the Node server and its `debug`.
import FoxgloveClient from "@foxglove/ws-protocol/dist/esm/src/FoxgloveClient.js";

const kReconnectDelays = [500, 1000, 2000, 4000, 8000];  ///< ms before each retry; the last repeats
const kCallTimeout = 15000;  ///< ms: a service call without an answer by then fails
const kStatusError = 2;      ///< the protocol's StatusLevel.ERROR

const textEncoder = new TextEncoder();
const textDecoder = new TextDecoder();

export class Connection {
  /// `url`: the gateway's WebSocket address (with the token, if any).
  constructor(url) {
    this.url = url;
    this.client = null;
    this.connected = false;
    this.serverInfo = null;
    this.listeners = new Map();        // event name -> Set of functions
    this.channelsByTopic = new Map();  // topic -> advertised channel
    this.topicsBySubscription = new Map();
    this.wantedTopics = new Map();     // topic -> how many subscriptions hold it
    this.servicesByName = new Map();   // name -> advertised service
    this.pendingCalls = new Map();     // callId -> { resolve, reject, timer }
    this.pendingParameters = new Map();  // request id -> { resolve, reject, timer }
    this.parameterNames = [];
    this.nextCallId = 1;
    this.nextParameterRequest = 1;
    this.attempt = 0;
  }

  /// Events: "state" (connected: bool, reason), "serverInfo", "message" (topic, DataView,
  /// channel), "parameterValues" (parameters, id), "status" (status message), "error" (text).
  on(event, listener) {
    if (!this.listeners.has(event)) this.listeners.set(event, new Set());
    this.listeners.get(event).add(listener);
  }

  off(event, listener) {
    this.listeners.get(event)?.delete(listener);
  }

  emit(event, ...args) {
    for (const listener of this.listeners.get(event) ?? []) {
      try {
        listener(...args);
      } catch (error) {
        console.error(`flagsim: a "${event}" listener failed`, error);
      }
    }
  }

  start() {
    const socket = new WebSocket(this.url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    const client = new FoxgloveClient({ ws: socket });
    this.client = client;
    // Events of a replaced client (after a reconnect) are ignored.
    const live = (handler) => (...args) => {
      if (this.client === client) handler(...args);
    };
    client.on("open", live(() => this.onOpen()));
    client.on("close", live((event) => this.onClose(event)));
    client.on("error", live((error) => this.emit("error", String(error?.message ?? error))));
    client.on("serverInfo", live((info) => this.onServerInfo(info)));
    client.on("advertise", live((channels) => this.onAdvertise(channels)));
    client.on("unadvertise", live((ids) => this.onUnadvertise(ids)));
    client.on("advertiseServices", live((services) => this.onAdvertiseServices(services)));
    client.on("unadvertiseServices", live((ids) => this.onUnadvertiseServices(ids)));
    client.on("message", live((message) => this.onMessage(message)));
    client.on("serviceCallResponse", live((response) => this.onServiceResponse(response)));
    client.on("serviceCallFailure", live((failure) => this.onServiceFailure(failure)));
    client.on("parameterValues", live((message) => this.onParameterValues(message)));
    client.on("status", live((status) => this.onStatus(status)));
  }

  onOpen() {
    this.connected = true;
    this.emit("state", true, "");
  }

  onServerInfo(info) {
    this.attempt = 0;  // a server answered: the next drop retries quickly again
    this.serverInfo = info;
    this.emit("serverInfo", info);
    if (this.parameterNames.length > 0) this.subscribeParameters(this.parameterNames);
  }

  /// The socket closed (or never opened): fail what waits on it, retry after a growing delay.
  onClose(event) {
    const wasConnected = this.connected;
    this.connected = false;
    this.channelsByTopic.clear();
    this.topicsBySubscription.clear();
    this.servicesByName.clear();
    this.failPending("the connection closed");
    const delay = kReconnectDelays[Math.min(this.attempt, kReconnectDelays.length - 1)];
    this.attempt += 1;
    const reason = event?.code ? `closed (${event.code}${event.reason ? `: ${event.reason}` : ""})` : "closed";
    this.emit("state", false, wasConnected ? reason : `no connection (${reason})`, delay);
    setTimeout(() => this.start(), delay);
  }

  failPending(reason) {
    for (const pending of [...this.pendingCalls.values(), ...this.pendingParameters.values()]) {
      clearTimeout(pending.timer);
      pending.reject(new Error(reason));
    }
    this.pendingCalls.clear();
    this.pendingParameters.clear();
  }

  // ---- Channels: advertised by the gateway, subscribed to by topic.

  onAdvertise(channels) {
    for (const channel of channels) {
      this.channelsByTopic.set(channel.topic, channel);
      if (this.wantedTopics.has(channel.topic)) this.subscribeChannel(channel);
    }
  }

  onUnadvertise(ids) {
    for (const [topic, channel] of this.channelsByTopic) {
      if (ids.includes(channel.id)) this.channelsByTopic.delete(topic);
    }
    for (const [subscriptionId, channel] of this.topicsBySubscription) {
      if (ids.includes(channel.id)) this.topicsBySubscription.delete(subscriptionId);
    }
  }

  /// Receives `topic` from now on, and again after every reconnect.
  subscribe(topic) {
    this.wantedTopics.set(topic, (this.wantedTopics.get(topic) ?? 0) + 1);
    const channel = this.channelsByTopic.get(topic);
    if (channel && this.connected) this.subscribeChannel(channel);
  }

  /// Takes back one subscribe(topic); the last one taken back ends the gateway's subscription.
  unsubscribe(topic) {
    const holders = (this.wantedTopics.get(topic) ?? 0) - 1;
    if (holders > 0) {
      this.wantedTopics.set(topic, holders);
      return;
    }
    this.wantedTopics.delete(topic);
    for (const [subscriptionId, channel] of this.topicsBySubscription) {
      if (channel.topic !== topic) continue;
      this.topicsBySubscription.delete(subscriptionId);
      if (this.connected) this.client.unsubscribe(subscriptionId);
    }
  }

  subscribeChannel(channel) {
    for (const subscribed of this.topicsBySubscription.values()) {
      if (subscribed.id === channel.id) return;  // a repeated advertisement: already subscribed
    }
    const subscriptionId = this.client.subscribe(channel.id);
    this.topicsBySubscription.set(subscriptionId, channel);
  }

  onMessage({ subscriptionId, data }) {
    const channel = this.topicsBySubscription.get(subscriptionId);
    if (channel) this.emit("message", channel.topic, data, channel);
  }

  // ---- Services: JSON requests by name, answered as promises.

  onAdvertiseServices(services) {
    for (const service of services) this.servicesByName.set(service.name, service);
  }

  onUnadvertiseServices(ids) {
    for (const [name, service] of this.servicesByName) {
      if (ids.includes(service.id)) this.servicesByName.delete(name);
    }
  }

  /// Calls service `name` with `request` (an object sent as JSON); resolves with the answer's
  /// JSON, rejects with the gateway's reason (serviceCallFailure), on timeout or on a close.
  call(name, request = {}) {
    const service = this.servicesByName.get(name);
    if (!this.connected || !service) {
      return Promise.reject(new Error(this.connected ? `the gateway offers no ${name}` : "not connected"));
    }
    const callId = this.nextCallId++;
    const data = textEncoder.encode(JSON.stringify(request));
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.pendingCalls.delete(callId);
        reject(new Error(`${name}: no answer within ${kCallTimeout / 1000} s`));
      }, kCallTimeout);
      this.pendingCalls.set(callId, { resolve, reject, timer, name });
      this.client.sendServiceCallRequest({ serviceId: service.id, callId, encoding: "json", data });
    });
  }

  onServiceResponse({ callId, data }) {
    const pending = this.takePending(this.pendingCalls, callId);
    if (!pending) return;
    try {
      pending.resolve(JSON.parse(textDecoder.decode(data)));
    } catch (error) {
      pending.reject(new Error(`${pending.name}: the answer is not JSON (${error.message})`));
    }
  }

  onServiceFailure({ callId, message }) {
    const pending = this.takePending(this.pendingCalls, callId);
    if (pending) pending.reject(new Error(message));
  }

  takePending(map, key) {
    const pending = map.get(key);
    if (!pending) return null;
    map.delete(key);
    clearTimeout(pending.timer);
    return pending;
  }

  // ---- Parameters: the protocol's setParameters with an id, and live updates.

  /// Asks for updates of `names` (renewed on reconnect) and their current values.
  subscribeParameters(names) {
    this.parameterNames = [...names];
    if (!this.connected || !this.serverInfo?.capabilities?.includes("parameters")) return;
    if (this.serverInfo.capabilities.includes("parametersSubscribe")) {
      this.client.subscribeParameterUpdates(this.parameterNames);
    }
    this.client.getParameters(this.parameterNames);
  }

  /// Sends `parameters` ([{ name, value }]) as one setParameters. Resolves with the
  /// parameterValues answer (the values in force) or rejects with the server's reason (the
  /// status `setParameters:ID`); the id is `request.id` for the caller to show.
  setParameters(parameters) {
    if (!this.connected) return { id: "", promise: Promise.reject(new Error("not connected")) };
    const id = `page-${this.nextParameterRequest++}`;
    const promise = new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.pendingParameters.delete(id);
        reject(new Error(`no answer within ${kCallTimeout / 1000} s`));
      }, kCallTimeout);
      this.pendingParameters.set(id, { resolve, reject, timer });
    });
    this.client.setParameters(parameters, id);
    return { id, promise };
  }

  onParameterValues({ parameters, id }) {
    if (id !== undefined) this.takePending(this.pendingParameters, id)?.resolve(parameters);
    this.emit("parameterValues", parameters, id);
  }

  /// A status of level error with id `setParameters:ID` rejects that request; every status is
  /// passed on for the page to show.
  onStatus(status) {
    const match = /^setParameters:(.*)$/.exec(status.id ?? "");
    if (match && status.level === kStatusError) {
      this.takePending(this.pendingParameters, match[1])?.reject(new Error(status.message));
      return;
    }
    this.emit("status", status);
  }
}

/// The gateway's WebSocket address: the page's own host, with the page's token passed on.
export function gatewayUrl(location, token) {
  const scheme = location.protocol === "https:" ? "wss:" : "ws:";
  const query = token ? `?token=${encodeURIComponent(token)}` : "";
  return `${scheme}//${location.host}/${query}`;
}
