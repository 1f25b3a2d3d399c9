// The live view's wiring: one Connection to the gateway (the page's own host, its token passed
// on), seen through a ServerScope of the server the page steers, and each channel to the parts
// that show it. A gateway may serve several servers, each under its path (`/ALPHA_/flag/tiles`);
// the scope gives the parts the single server's names (`/flag/tiles`) of the one steered.
//
//   /gateway/servers -> which server is steered (`?server=P`, else the first live one): the
//                       scope's path; ServerPanel; BesideView (`?beside=B`: B's picture too)
//   /flag/tiles    -> PictureStream -> FrameImage -> FrameView (canvas), status bar, hooks
//   /flag/camera   -> CameraControls (pixels -> metres), CameraPanel
//   /flag/params   -> ParamPanel (+ protocol parameters), timeline keys
//   /flag/state    -> WindPanel, Plots (tip, energy), TimelinePanel (playhead)
//   /flag/status   -> Plots, ClockControls (paused, time_scale)
//   /flag/timeline -> TimelinePanel
//   /flag/acks     -> status bar (last ACK)
//   /gateway/status -> the camera panel (how many viewers share the camera)
import "uplot/dist/uPlot.min.css";  // uPlot's own rules first, the page's after them
import "../style.css";
import { CameraControls } from "./camera_controls.js";
import { CameraPanel } from "./camera_panel.js";
import { ClockControls } from "./clock_controls.js";
import { Connection, gatewayUrl } from "./connection.js";
import { FrameImage } from "./frame_image.js";
import { FrameView } from "./frame_view.js";
import { ParamPanel } from "./param_panel.js";
import { readParamsTable, readValue } from "./params_table.js";
import { PictureStream } from "./picture_stream.js";
import { Plots } from "./plots.js";
import { DesignPanel } from "./design_panel.js";
import { SessionTools } from "./session_tools.js";
import { ServerWatch } from "./server_watch.js";
import { BesideView } from "./beside_view.js";
import { besideLinkFor, chooseServer, readServerChoice, readServerList, waitingForServer } from "./server_list.js";
import { ServerPanel } from "./server_panel.js";
import { ServerScope } from "./server_scope.js";
import { readViewLink } from "./view_link.js";
import { StatusBar } from "./status_bar.js";
import { installTestHooks } from "./test_hooks.js";
import { createHasher } from "./tile_decoder.js";
import { TimelinePanel } from "./timeline_panel.js";
import { readTimeline } from "./timeline_model.js";
import { createToaster } from "./toast.js";
import { el } from "./dom.js";
import { WindPanel } from "./wind_panel.js";

const kJsonTopics = ["/flag/state", "/flag/status", "/flag/params", "/flag/timeline", "/flag/camera", "/flag/acks", "/gateway/status",
                     "/gateway/servers"];
const kStatusBarPeriod = 500;  ///< ms between updates of the frames-shown rate
const textDecoder = new TextDecoder();
const byId = (id) => document.getElementById(id);

/// The page's token (`?token=`), passed on to the WebSocket and to download links.
const token = new URLSearchParams(window.location.search).get("token") ?? "";
function withToken(url) {
  if (!token) return url;
  return `${url}${url.includes("?") ? "&" : "?"}token=${encodeURIComponent(token)}`;
}

async function start() {
  const hasher = await createHasher();  // XXH3-64 (WASM) is ready before the first tile
  const gateway = new Connection(gatewayUrl(window.location, token));
  const connection = new ServerScope(gateway);  // its path once /gateway/servers names the server
  const toast = createToaster(byId("toasts"));
  const page = {
    gateway, connection, hasher, toast,
    choice: readServerChoice(window.location.search),  // { server, beside } asked for in the address
    servers: null,  // the newest /gateway/servers
    server: "",     // the prefix of the server steered, once chosen
    steeredWasGone: false,  // the newest list said the server steered was gone
    image: new FrameImage(hasher),
    view: new FrameView({ stage: byId("stage"), canvas: byId("picture"), hud: byId("hud") }),
    params: [], timeline: null, camera: null, state: null, status: null, lastAck: null, lastError: "",
  };
  const parts = createParts(page);
  page.serverWatch = new ServerWatch({
    onRestart: () => toast("The server restarted: a new session, its frames and time from the start", "warning"),
  });
  page.beside = new BesideView({
    connection: gateway, hasher, stage: byId("beside-stage"),
    onChange: (prefix) => onBesideChange(page, parts, prefix),
    onProblem: (text) => (page.lastError = text),
  });
  const frameShown = installTestHooks(page);
  page.stream = new PictureStream({
    connection, image: page.image, view: page.view,
    onFrame: (image) => {
      byId("stage").classList.add("has-frame");
      parts.statusBar.setFrame(image);
      parts.sessionTools.updateFrame();
      frameShown();
    },
    onProblem: (text) => (page.lastError = text),
  });
  wireConnection(page, parts);
  for (const problem of page.choice.problems) toast(problem, "error");
  if (page.choice.beside) page.beside.want(page.choice.beside, page.servers);
  setInterval(() => {
    parts.statusBar.setFps(page.view.shownFps());
    page.view.updateHud();
    page.beside.tick();
    showConnection(page, parts);
  }, kStatusBarPeriod);
  gateway.start();
}

/// The panels, each given what it reads and the connection it sends through.
function createParts(page) {
  const { connection, toast } = page;
  const windPanel = new WindPanel({ container: byId("wind-body"), connection });
  const cameraControls = new CameraControls({ stage: byId("stage"), frameView: page.view, connection, getCamera: () => page.camera, toast });
  return {
    statusBar: new StatusBar(byId("status-bar")),
    clock: new ClockControls({ container: byId("clock-tools"), connection, toast }),
    cameraControls,
    cameraPanel: new CameraPanel({ container: byId("camera-body"), cameraControls, getCamera: () => page.camera }),
    paramPanel: new ParamPanel({ container: byId("param-body"), connection, toast }),
    designPanel: new DesignPanel({ container: byId("design-body"), connection, toast, stage: byId("stage") }),
    windPanel,
    timelinePanel: new TimelinePanel({
      container: byId("timeline-body"), connection, toast,
      current: () => ({ wind: windPanel.chosenWind(), params: page.params, camera: page.camera }),
    }),
    plots: new Plots({ container: byId("plots") }),
    serverPanel: new ServerPanel({
      section: byId("server-panel"), container: byId("server-body"),
      onBeside: (prefix) => (prefix ? page.beside.want(prefix, page.servers) : page.beside.close()),
    }),
    sessionTools: new SessionTools({
      container: byId("session-tools"), connection, toast, withToken,
      frame: () => ({ id: page.image.frameId, hashOk: page.image.hashOk }),
      pngBlob: () => page.view.toPngBlob(),
      camera: () => page.camera,
      stage: byId("stage"),
    }),
  };
}

function wireConnection(page, parts) {
  const { connection } = page;
  for (const topic of kJsonTopics) connection.subscribe(topic);
  connection.on("state", (connected, reason, retryIn) => {
    const text = connected ? "connected" : `${reason}; retrying in ${((retryIn ?? 0) / 1000).toFixed(1)} s`;
    page.gatewayText = text;
    if (!connected) page.serverWatch.onDisconnect();
    showConnection(page, parts);
    byId("stage").classList.toggle("offline", !connected);
    showStageNote(page);
  });
  connection.on("serverInfo", () => {
    showServerName(page, parts);
    if (page.params.length > 0) connection.subscribeParameters(page.params.map((p) => p.name));
  });
  connection.on("message", (topic, data) => {
    if (topic === "/flag/tiles") return;
    let message;
    try {
      message = JSON.parse(textDecoder.decode(data));
    } catch (error) {
      page.lastError = `${topic}: not JSON (${error.message})`;
      return;
    }
    onJsonMessage(page, parts, topic, message);
  });
  connection.on("parameterValues", (values) => onParameterValues(page, parts, values));
  connection.on("status", (status) => {
    if (status.level >= 2) page.lastError = status.message;
    if (status.level >= 1) page.toast(status.message, status.level >= 2 ? "error" : "warning");
  });
  connection.on("error", (text) => (page.lastError = text));
}

/// A link's view (`?view=`, view_link.js), offered once the server's camera is first heard: the
/// camera is shared, so moving it moves it for every viewer, and the person opening the link
/// chooses to.
function openLinkedView(page, parts) {
  if (page.linkedViewDone) return;
  page.linkedViewDone = true;
  const { view, problem } = readViewLink(window.location.search);
  if (problem) page.toast(problem, "error");
  if (!view) return;
  const offer = byId("view-offer");
  for (const type of ["pointerdown", "wheel"]) offer.addEventListener(type, (event) => event.stopPropagation());
  const close = () => (offer.hidden = true);
  const apply = () => {
    close();
    for (const request of [{ operation: "eye", vector: view.eye }, { operation: "look_at", vector: view.target },
                           { operation: "fov", degrees: view.fov }]) {
      parts.cameraControls.move(request);
    }
  };
  offer.replaceChildren(
    el("span", {}, `This link carries a view (eye ${view.eye.join(", ")} m). The camera is shared: moving it moves it for every viewer.`),
    el("button", { type: "button", class: "primary", onclick: apply }, "Move the camera there"),
    el("button", { type: "button", onclick: close }, "Not now"));
  offer.hidden = false;
}

/// The gateway's servers, newest list: the one to steer chosen once (`?server=P`, else the first
/// live one), the panel and the picture beside follow.
function onServerList(page, parts, servers) {
  page.servers = servers;
  if (!page.server) steer(page, parts, chooseServer(servers, page.choice.server));
  followSteered(page, servers.find((server) => server.prefix === page.server));
  page.beside.follow(servers);
  showServers(page, parts);
  showStageNote(page);
}

/// The steered server's newest entry: under another path (a gateway started again in the other
/// mode) the page starts afresh; back after it was withdrawn, its parameters are asked for again.
function followSteered(page, entry) {
  if (!entry) return;
  if (entry.path !== page.connection.path) {
    window.location.reload();
    return;
  }
  if (entry.live && page.steeredWasGone && page.params.length > 0) {
    page.connection.subscribeParameters(page.params.map((p) => p.name));
  }
  page.steeredWasGone = !entry.live;
}

/// From now on the panels are `entry`'s: the scope takes its path and subscribes to its channels.
/// Another server is steered by opening the page again (the server panel's links).
function steer(page, parts, entry) {
  if (!entry) return;
  page.server = entry.prefix;
  page.connection.setPath(entry.path);
  if (entry.path !== "") {
    document.title = `flagsim · ${entry.prefix} · live view`;
    const caption = byId("stage-caption");
    caption.textContent = `${entry.prefix} · steered`;
    caption.hidden = false;
  }
  if (page.beside.prefix === entry.prefix) {
    page.toast(`beside: ${entry.prefix} is the server steered; it is shown once`, "warning");
    page.beside.close();
  }
  showServerName(page, parts);
}

/// The server panel's rows, with which server is steered and which watched beside (once the
/// gateway has said which servers it serves).
function showServers(page, parts) {
  if (page.servers === null) return;
  parts.serverPanel.update(page.servers, { steered: page.server, beside: page.beside.prefix, wanted: page.choice.server });
}

/// The picture beside now watches `prefix` ("" none): the address says so, the panel too.
function onBesideChange(page, parts, prefix) {
  window.history.replaceState(null, "", besideLinkFor(window.location, prefix));
  showServers(page, parts);
}

/// What the stage says while it has no picture: no gateway, no server (yet), or no frame yet.
function showStageNote(page) {
  const entry = page.servers?.find((server) => server.prefix === page.server);
  byId("stage-empty").textContent = !page.gateway.connected ? `no connection to the gateway: ${page.gatewayText ?? "connecting …"}`
    : !page.server ? waitingForServer(page.servers, page.choice.server)
    : entry && !entry.live ? `${page.server} is gone; waiting for it to come back …`
    : "waiting for the first frame …";
}

/// Whether the gateway serves several servers (each under a path of its own).
function severalServers(page) {
  return page.servers?.some((server) => server.path !== "") ?? false;
}

/// The status bar's server field: the gateway's name, and the server steered when it has several.
function showServerName(page, parts) {
  parts.statusBar.setServer(page.gateway.serverInfo?.name ?? "", severalServers(page) ? page.server : "");
}

/// The connection field: the gateway's connection, and whether a server is behind it.
function showConnection(page, parts) {
  if (!page.connection.connected) {
    parts.statusBar.setConnection("disconnected", page.gatewayText ?? "connecting …");
    return;
  }
  const server = page.serverWatch.state();
  parts.statusBar.setConnection(server === "alive" || server === "restarted" ? "connected" : "no-server",
                                `connected · ${page.serverWatch.describe()}`);
}

/// One message of a JSON channel, to the parts that show it.
function onJsonMessage(page, parts, topic, message) {
  switch (topic) {
    case "/flag/state":
      page.state = message;
      parts.windPanel.updateState(message);
      parts.plots.addState(message);
      parts.timelinePanel.tick(message.sim_time ?? null);
      break;
    case "/flag/status":
      page.serverWatch.onStatus(message);
      showConnection(page, parts);
      page.status = message;
      parts.statusBar.setModel(message);
      parts.clock.update(message);
      parts.plots.addStatus(message, page.view.shownFps());
      break;
    case "/flag/params":
      onParamsTable(page, parts, readParamsTable(message));
      break;
    case "/flag/timeline":
      page.timeline = readTimeline(message, page.state?.sim_time ?? null);
      parts.timelinePanel.update(page.timeline);
      break;
    case "/flag/camera":
      page.camera = message;
      parts.cameraPanel.update(message);
      openLinkedView(page, parts);
      break;
    case "/gateway/status":
      if (Number.isFinite(message.clients)) parts.cameraPanel.setViewers(message.clients, severalServers(page) ? page.server : "");
      break;
    case "/gateway/servers":
      onServerList(page, parts, readServerList(message));
      break;
    case "/flag/acks":
      page.lastAck = message;
      parts.statusBar.setAck(message);
      break;
  }
}

/// A new parameter table: the panel follows; a new set of names is subscribed to.
function onParamsTable(page, parts, params) {
  const names = params.map((p) => p.name).join(",");
  const known = page.params.map((p) => p.name).join(",");
  page.params = params;
  parts.paramPanel.update(params);
  parts.designPanel.update(params);
  if (names !== known) page.connection.subscribeParameters(params.map((p) => p.name));
}

/// Protocol parameter values: the panel and the page's table both take them.
function onParameterValues(page, parts, values) {
  for (const { name, value } of values) {
    const parameter = page.params.find((p) => p.name === name);
    if (parameter && value !== undefined) parameter.value = readValue(parameter, value);
  }
  parts.paramPanel.onParameterValues(values);
}

start().catch((error) => {
  console.error(error);
  document.body.prepend(Object.assign(document.createElement("pre"), { className: "fatal", textContent: `The page failed to start: ${error.message}` }));
});
