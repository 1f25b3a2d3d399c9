// The live view's wiring: one Connection to the gateway (the page's own host, its token passed
// on), and each channel to the parts that show it.
//
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
import { readViewLink } from "./view_link.js";
import { StatusBar } from "./status_bar.js";
import { installTestHooks } from "./test_hooks.js";
import { createHasher } from "./tile_decoder.js";
import { TimelinePanel } from "./timeline_panel.js";
import { readTimeline } from "./timeline_model.js";
import { createToaster } from "./toast.js";
import { el } from "./dom.js";
import { WindPanel } from "./wind_panel.js";

const kJsonTopics = ["/flag/state", "/flag/status", "/flag/params", "/flag/timeline", "/flag/camera", "/flag/acks", "/gateway/status"];
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
  const connection = new Connection(gatewayUrl(window.location, token));
  const toast = createToaster(byId("toasts"));
  const page = {
    connection, hasher, toast,
    image: new FrameImage(hasher),
    view: new FrameView({ stage: byId("stage"), canvas: byId("picture"), hud: byId("hud") }),
    params: [], timeline: null, camera: null, state: null, status: null, lastAck: null, lastError: "",
  };
  const parts = createParts(page);
  page.serverWatch = new ServerWatch({
    onRestart: () => toast("The server restarted: a new session, its frames and time from the start", "warning"),
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
  setInterval(() => {
    parts.statusBar.setFps(page.view.shownFps());
    page.view.updateHud();
    showConnection(page, parts);
  }, kStatusBarPeriod);
  connection.start();
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
    byId("stage-empty").textContent = connected ? "waiting for the first frame …" : `no connection to the gateway: ${text}`;
  });
  connection.on("serverInfo", (info) => {
    parts.statusBar.setServer(info.name);
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
      if (Number.isFinite(message.clients)) parts.cameraPanel.setViewers(message.clients);
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
