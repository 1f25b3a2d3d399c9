// The servers a gateway serves, and which of them the page steers and watches:
//
//   /gateway/servers (flagsim.Servers) --readServerList--> [{ prefix, path, live, scene, width,
//       height, real_time_factor, frame_rate_hz, paused, sim_time }], sorted by prefix
//   ?server=P&beside=B --readServerChoice--> { server: "P", beside: "B" } (and what was wrong)
//   the list, "P" --chooseServer--> P's entry (live or not); without P the first live one (or
//       the only one); or null
//   an entry --describeServer/describeScene/describePicture--> words for the server panel
//   steerLinkFor, besideLinkFor --> the page's address steering or watching another, token kept
//
// A gateway serving one server lists it with the path "": its names are the single server's.
import { formatNumber } from "./dom.js";

const kPrefixPattern = /^[A-Za-z0-9_]{1,52}$/;  ///< a channel prefix, as flagd takes it

/// A flagsim.Servers message as entries with every field, sorted by prefix; [] when unreadable.
export function readServerList(message) {
  const servers = Array.isArray(message?.servers) ? message.servers : [];
  return servers.filter((entry) => typeof entry?.prefix === "string").map(readEntry)
    .sort((a, b) => (a.prefix < b.prefix ? -1 : a.prefix > b.prefix ? 1 : 0));
}

function readEntry(entry) {
  const number = (value) => (Number.isFinite(value) ? value : 0);
  return {
    prefix: entry.prefix,
    path: typeof entry.path === "string" ? entry.path : `/${entry.prefix}`,
    live: entry.live !== false,
    scene: typeof entry.scene === "string" ? entry.scene : "",
    width: number(entry.width),
    height: number(entry.height),
    real_time_factor: number(entry.real_time_factor),
    frame_rate_hz: number(entry.frame_rate_hz),
    paused: entry.paused === true,
    sim_time: number(entry.sim_time),
  };
}

/// `?server=` and `?beside=` of a page's query string: { server, beside, problems: [text] }.
/// A value that is no prefix is dropped (and said), as is a beside equal to the server.
export function readServerChoice(search) {
  const query = new URLSearchParams(search);
  const problems = [];
  const read = (key) => {
    const value = query.get(key);
    if (value === null || value === "") return "";
    if (kPrefixPattern.test(value)) return value;
    problems.push(`${key}: '${value}' is not a server's prefix; allowed 1 .. 52 letters, digits and '_'`);
    return "";
  };
  const server = read("server");
  let beside = read("beside");
  if (beside && beside === server) {
    problems.push(`beside: ${beside} is the server steered; it is shown once`);
    beside = "";
  }
  return { server, beside, problems };
}

/// The entry to steer: `wanted`'s (even while it is gone: it may come back), else the first
/// live server, else the only one (a gateway serving one server, heard or not); null while there
/// is none such.
export function chooseServer(servers, wanted) {
  if (wanted) return servers.find((entry) => entry.prefix === wanted) ?? null;
  return servers.find((entry) => entry.live) ?? (servers.length === 1 ? servers[0] : null);
}

/// Why there is no picture while no server is chosen: for the stage.
export function waitingForServer(servers, wanted) {
  if (servers === null) return "waiting for the gateway's list of servers …";
  const names = servers.map((entry) => entry.prefix).join(", ");
  if (wanted) {
    return `The gateway serves no server ${wanted} (yet)${names ? `; it serves ${names}` : ""}. Waiting for it …`;
  }
  return names ? `No server of this gateway is live (${names} gone). Waiting for one …` : "The gateway hears no server yet. Waiting for one …";
}

/// "live · 0.99× real time · 30 fps · paused", or "gone".
export function describeServer(entry) {
  if (!entry.live) return "gone";
  const paused = entry.paused ? " · paused" : "";
  return `live · ${formatNumber(entry.real_time_factor, 2)}× real time · ${formatNumber(entry.frame_rate_hz, 3)} fps${paused}`;
}

export function describeScene(entry) {
  return entry.scene || "scene not known yet";
}

/// "640×480", or "no frame yet".
export function describePicture(entry) {
  return entry.width > 0 && entry.height > 0 ? `${entry.width}×${entry.height}` : "no frame yet";
}

/// The page's address steering `server`, still watching `beside` unless it is `server` now: the
/// other query parameters (the token) kept, but not a view (`?view=`), which is of another
/// server's camera.
export function steerLinkFor(location, server, beside) {
  const url = new URL(location.href);
  url.searchParams.set("server", server);
  url.searchParams.delete("view");
  url.hash = "";
  return setBeside(url, beside && beside !== server ? beside : "");
}

/// The page's address watching `beside` ("" for none), everything else kept.
export function besideLinkFor(location, beside) {
  return setBeside(new URL(location.href), beside);
}

function setBeside(url, beside) {
  if (beside) url.searchParams.set("beside", beside);
  else url.searchParams.delete("beside");
  return url.toString();
}
