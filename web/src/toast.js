// Brief messages on the picture: a rejected move's reason, a failed call. Each shows for a few
// seconds; at most a handful are on screen, the oldest leaving first.
import { el } from "./dom.js";

const kShowFor = 4000;  ///< ms a message stays
const kMaxShown = 4;

export function createToaster(container) {
  return function toast(text, kind = "info") {
    const message = el("div", { class: `toast ${kind}`, role: "status" }, text);
    container.append(message);
    while (container.children.length > kMaxShown) container.firstElementChild.remove();
    setTimeout(() => message.classList.add("leaving"), kShowFor - 300);
    setTimeout(() => message.remove(), kShowFor);
  };
}
