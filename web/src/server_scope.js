// One server's view of the gateway's connection. A gateway may serve several flagd servers, each
// under its path (`/ALPHA_`); the panels speak the single server's names and the scope turns
// them into that server's:
//
//   subscribe("/flag/tiles")          --> Connection.subscribe("/ALPHA_/flag/tiles")
//   "message" ("/ALPHA_/flag/tiles")  --> "message" ("/flag/tiles"); other servers' dropped
//   call("/flag/wind", request)       --> Connection.call("/ALPHA_/flag/wind", request)
//   setParameters([{ name: "stiffness" }]), subscribeParameters(["stiffness"])
//                                     --> "/ALPHA_/stiffness"; parameterValues back to "stiffness"
//
// The gateway's own names (`/gateway/status`, `/gateway/servers`) pass unchanged. The path ""
// (a gateway serving one server) maps every name to itself. Until setPath the scope holds what
// is wanted and sends nothing of the server's: the page learns the path from `/gateway/servers`.
// close() takes back every subscription and listener the scope made.

/// A name of the gateway itself: `/gateway/NAME`, one word after it (a server's names under a
/// path have two or more: `/gateway/flag/tiles` is the server `gateway`'s).
export function isGatewayName(name) {
  return /^\/gateway\/[^/]+$/.test(name);
}

/// A topic or service of the server at `path`: `/flag/x` -> `${path}/flag/x`.
export function serverName(path, name) {
  return isGatewayName(name) ? name : `${path}${name}`;
}

/// The topic or service as the panels know it, or null when it is another server's.
export function relativeName(path, name) {
  if (isGatewayName(name) || path === "") return name;
  return name.startsWith(`${path}/`) ? name.slice(path.length) : null;
}

/// A parameter of the server at `path`: `stiffness` -> `${path}/stiffness`.
export function serverParameter(path, name) {
  return path === "" ? name : `${path}/${name}`;
}

/// The parameter as the panels know it, or null when it is another server's.
export function relativeParameter(path, name) {
  if (path === "") return name;
  return name.startsWith(`${path}/`) ? name.slice(path.length + 1) : null;
}

export class ServerScope {
  /// `connection`: the page's Connection; `path`: the server's, or null until known (setPath).
  constructor(connection, path = null) {
    this.connection = connection;
    this.path = null;
    this.wantedTopics = new Set();  ///< as the panels name them
    this.parameterNames = [];       ///< as the panels name them
    this.detachers = [];            ///< functions that take back a listener
    if (path !== null) this.setPath(path);
  }

  get connected() {
    return this.connection.connected;
  }

  get serverInfo() {
    return this.connection.serverInfo;
  }

  /// The server's path, once: what was wanted before is subscribed to now.
  setPath(path) {
    if (this.path !== null) throw new Error(`the scope already has the path '${this.path}'`);
    this.path = path;
    for (const topic of this.wantedTopics) {
      if (!isGatewayName(topic)) this.connection.subscribe(serverName(path, topic));
    }
    if (this.parameterNames.length > 0) this.subscribeParameters(this.parameterNames);
  }

  /// The Connection's events, with this server's names: "message" and "parameterValues" carry
  /// only this server's (and the gateway's own) names; the others pass as they are.
  on(event, listener) {
    const forward = this.forwarder(event, listener);
    this.connection.on(event, forward);
    this.detachers.push(() => this.connection.off(event, forward));
  }

  forwarder(event, listener) {
    if (event === "message") {
      return (topic, data, channel) => {
        const relative = this.relativeTopic(topic);
        if (relative !== null) listener(relative, data, channel);
      };
    }
    if (event === "parameterValues") {
      return (parameters, id) => {
        const own = this.ownParameters(parameters);
        if (own.length > 0) listener(own, id);
      };
    }
    return listener;
  }

  relativeTopic(topic) {
    if (this.path === null) return isGatewayName(topic) ? topic : null;
    return relativeName(this.path, topic);
  }

  /// Of protocol parameters ([{ name, value, type }]), this server's, named as the panels name them.
  ownParameters(parameters = []) {
    if (this.path === null) return [];
    return parameters.flatMap((parameter) => {
      const name = relativeParameter(this.path, parameter.name);
      return name === null ? [] : [{ ...parameter, name }];
    });
  }

  /// Receives `topic` (this server's, or the gateway's own) from now on.
  subscribe(topic) {
    this.wantedTopics.add(topic);
    if (isGatewayName(topic)) this.connection.subscribe(topic);
    else if (this.path !== null) this.connection.subscribe(serverName(this.path, topic));
  }

  /// Calls this server's service `name`; rejects while the server is not known.
  call(name, request = {}) {
    if (this.path === null && !isGatewayName(name)) return Promise.reject(new Error("no server chosen yet"));
    return this.connection.call(serverName(this.path ?? "", name), request);
  }

  /// Sets this server's parameters; resolves with the values in force, named as given.
  setParameters(parameters) {
    if (this.path === null) return { id: "", promise: Promise.reject(new Error("no server chosen yet")) };
    const named = parameters.map((parameter) => ({ ...parameter, name: serverParameter(this.path, parameter.name) }));
    const { id, promise } = this.connection.setParameters(named);
    return { id, promise: promise.then((values) => this.ownParameters(values)) };
  }

  /// Asks for updates of this server's parameters `names` (renewed on setPath and on reconnect).
  subscribeParameters(names) {
    this.parameterNames = [...names];
    if (this.path === null) return;
    this.connection.subscribeParameters(this.parameterNames.map((name) => serverParameter(this.path, name)));
  }

  /// Takes back the scope's topics and listeners: nothing of this server reaches the page.
  close() {
    for (const detach of this.detachers) detach();
    this.detachers = [];
    for (const topic of this.wantedTopics) {
      if (isGatewayName(topic)) this.connection.unsubscribe(topic);
      else if (this.path !== null) this.connection.unsubscribe(serverName(this.path, topic));
    }
    this.wantedTopics.clear();
  }
}
