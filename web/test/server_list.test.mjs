import assert from "node:assert/strict";
import { test } from "node:test";
import {
  besideLinkFor, chooseServer, describePicture, describeScene, describeServer, readServerChoice, readServerList,
  steerLinkFor, waitingForServer,
} from "../src/server_list.js";

const alpha = { prefix: "ALPHA_", path: "/ALPHA_", live: true, scene: "32 x 24 nodes, 1.5 x 1 m, nordic_cross", width: 640, height: 480,
                real_time_factor: 0.99, frame_rate_hz: 30.0, paused: false, sim_time: 12.3 };
const beta = { ...alpha, prefix: "BETA_", path: "/BETA_", live: false, scene: "", width: 0, height: 0 };

test("the list is read sorted by prefix, every field there", () => {
  const servers = readServerList({ servers: [beta, alpha, { prefix: "GAMMA_", path: "/GAMMA_" }, { path: "/nameless" }] });
  assert.deepEqual(servers.map((entry) => entry.prefix), ["ALPHA_", "BETA_", "GAMMA_"]);
  assert.deepEqual(servers[0], alpha);
  assert.deepEqual(servers[2], { prefix: "GAMMA_", path: "/GAMMA_", live: true, scene: "", width: 0, height: 0,
                                 real_time_factor: 0, frame_rate_hz: 0, paused: false, sim_time: 0 });
  assert.deepEqual(readServerList({}), []);
  assert.deepEqual(readServerList(null), []);
});

test("one server (a gateway in single mode) keeps its empty path", () => {
  const [only] = readServerList({ servers: [{ ...alpha, prefix: "LIVE_", path: "" }] });
  assert.equal(only.path, "");
  assert.equal(chooseServer([only], ""), only);
  assert.equal(chooseServer([only], "LIVE_"), only);
});

test("the server steered: the one asked for (live or gone), else the first live one", () => {
  const servers = readServerList({ servers: [alpha, beta] });
  assert.equal(chooseServer(servers, "").prefix, "ALPHA_");
  assert.equal(chooseServer(servers, "BETA_").prefix, "BETA_", "a server gone may come back");
  assert.equal(chooseServer(servers, "GAMMA_"), null);
  assert.equal(chooseServer([{ ...alpha, live: false }, beta], ""), null);
  assert.equal(chooseServer([beta], "").prefix, "BETA_", "the only server, not heard yet: there is no other to wait for");
  assert.equal(chooseServer([], ""), null);
});

test("the stage says why there is no picture yet", () => {
  assert.match(waitingForServer(null, ""), /waiting for the gateway's list of servers/);
  assert.match(waitingForServer([alpha, beta], "GAMMA_"), /serves no server GAMMA_ \(yet\); it serves ALPHA_, BETA_/);
  assert.match(waitingForServer([], "GAMMA_"), /serves no server GAMMA_ \(yet\)\. Waiting/);
  assert.match(waitingForServer([beta, { ...beta, prefix: "GAMMA_" }], ""), /No server of this gateway is live \(BETA_, GAMMA_ gone\)/);
  assert.match(waitingForServer([], ""), /hears no server yet/);
});

test("?server= and ?beside= are prefixes; anything else is said and dropped", () => {
  assert.deepEqual(readServerChoice("?token=abc&server=ALPHA_&beside=BETA_"), { server: "ALPHA_", beside: "BETA_", problems: [] });
  assert.deepEqual(readServerChoice(""), { server: "", beside: "", problems: [] });
  const bad = readServerChoice("?server=al%2Fpha&beside=");
  assert.equal(bad.server, "");
  assert.match(bad.problems[0], /server: 'al\/pha' is not a server's prefix/);
  const same = readServerChoice("?server=ALPHA_&beside=ALPHA_");
  assert.deepEqual([same.server, same.beside], ["ALPHA_", ""]);
  assert.match(same.problems[0], /ALPHA_ is the server steered/);
});

test("a server in words", () => {
  assert.equal(describeServer(alpha), "live · 0.99× real time · 30 fps");
  assert.equal(describeServer({ ...alpha, paused: true }), "live · 0.99× real time · 30 fps · paused");
  assert.equal(describeServer(beta), "gone");
  assert.equal(describePicture(alpha), "640×480");
  assert.equal(describePicture(beta), "no frame yet");
  assert.equal(describeScene(alpha), alpha.scene);
  assert.equal(describeScene(beta), "scene not known yet");
});

test("links to steer or watch another server keep the token", () => {
  const location = { href: "http://127.0.0.1:8080/?token=t0k&server=ALPHA_&beside=BETA_&view=1,2,3,0,0,0,40#x" };
  assert.equal(steerLinkFor(location, "GAMMA_", "BETA_"), "http://127.0.0.1:8080/?token=t0k&server=GAMMA_&beside=BETA_");
  assert.equal(steerLinkFor(location, "BETA_", "BETA_"), "http://127.0.0.1:8080/?token=t0k&server=BETA_",
               "steering the server watched beside shows it once");
  assert.equal(besideLinkFor(location, ""), "http://127.0.0.1:8080/?token=t0k&server=ALPHA_&view=1%2C2%2C3%2C0%2C0%2C0%2C40#x");
  assert.equal(besideLinkFor({ href: "http://h/?token=t0k" }, "GAMMA_"), "http://h/?token=t0k&beside=GAMMA_");
});
