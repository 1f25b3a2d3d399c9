// Debian's Chromium, headless, as the browser tests drive it (playwright-core; no browser is
// downloaded): without the sandbox (the tests run as root in a private namespace), a GPU, or
// the background traffic a first run makes.
import { chromium } from "playwright-core";

export function launchChromium() {
  return chromium.launch({
    executablePath: "/usr/bin/chromium",
    args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
           "--disable-component-update", "--disable-sync"],
  });
}
