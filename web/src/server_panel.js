// The gateway's servers, one row each: prefix, scene, picture size, and status (live or gone,
// real time, frames a second, paused), with a link that steers it and a button that watches it
// beside the steered one.
//
//   /gateway/servers --update(list, { steered, beside, wanted })--> rows, kept by prefix: their
//       texts change in place, so a click is never lost to a rebuild
//   Steer        --> the page again with `?server=P` (the token kept): every panel is that server's
//   Watch beside --> onBeside("P"); Close beside --> onBeside("")
//
// Shown while the gateway serves more than one server, or while the one asked for is not there
// (to choose another); a gateway serving one server leaves the page as it was.
import { el } from "./dom.js";
import { describePicture, describeScene, describeServer, steerLinkFor } from "./server_list.js";

export class ServerPanel {
  /// `section`: the panel (hidden or shown); `container`: where the rows go.
  constructor({ section, container, onBeside }) {
    this.section = section;
    this.onBeside = onBeside;
    this.rows = new Map();  // prefix -> ServerRow
    this.signature = "";
    this.list = el("div", { class: "server-list" });
    container.append(this.list);
  }

  /// The newest list; `steered` and `beside` the prefixes shown ("" for none), `wanted` the one
  /// asked for in the address.
  update(servers, { steered, beside, wanted }) {
    this.section.hidden = !(servers.length > 1 || (wanted && steered !== wanted));
    const signature = [servers.map((entry) => entry.prefix).join(","), steered, beside].join("|");
    if (signature !== this.signature) this.rebuild(servers, steered, beside, signature);
    for (const entry of servers) this.rows.get(entry.prefix)?.show(entry, beside);
  }

  rebuild(servers, steered, beside, signature) {
    this.signature = signature;
    this.rows = new Map(servers.map((entry) => [entry.prefix, new ServerRow(entry.prefix, steered, beside, this.onBeside)]));
    this.list.replaceChildren(...[...this.rows.values()].map((row) => row.element));
  }
}

/// One server's row: its words, and what may be done with it (steered: nothing; watched beside:
/// closed; another: steered or watched).
class ServerRow {
  constructor(prefix, steered, beside, onBeside) {
    const role = prefix === steered ? "steered" : prefix === beside ? "beside" : "";
    this.size = el("span", { class: "server-size muted" });
    this.scene = el("div", { class: "server-scene muted" });
    this.state = el("div", { class: "server-state" });
    this.steerLink = role === "steered" ? null : el("a", { class: "button", title: `this page steers ${prefix} instead: its picture and panels` }, "Steer");
    const besideButton = role === "steered" ? null : role === "beside"
      ? el("button", { type: "button", title: "stop watching it beside", onclick: () => onBeside("") }, "Close beside")
      : el("button", { type: "button", title: "its picture beside the steered one", onclick: () => onBeside(prefix) }, "Watch beside");
    const name = el("div", { class: "server-name" }, el("span", { class: "server-prefix" }, prefix),
                    role ? el("span", { class: "server-role" }, role) : null, this.size);
    this.element = el("div", { class: `server-row ${role}`, dataset: { prefix } },
                      el("div", { class: "server-text" }, name, this.scene, this.state),
                      el("div", { class: "server-actions" }, this.steerLink, besideButton));
  }

  show(entry, beside) {
    this.size.textContent = describePicture(entry);
    this.scene.textContent = describeScene(entry);
    this.scene.title = this.scene.textContent;
    this.state.textContent = describeServer(entry);
    this.state.className = `server-state ${entry.live ? "live" : "gone"}`;
    this.element.classList.toggle("gone", !entry.live);
    if (this.steerLink) this.steerLink.href = steerLinkFor(window.location, entry.prefix, beside);
  }
}
