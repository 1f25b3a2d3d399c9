// The live view of a gateway serving two servers (flagctl serve --servers all), in Debian's
// Chromium driven by playwright-core: the page steers ALPHA_ and watches BETA_ beside it. Both
// servers are listed; each picture is its own server's frame byte for byte and both advance,
// hash-checked; a parameter and a clock command from the page reach ALPHA_ only; the picture
// beside closes and opens again; BETA_ stopped is listed as gone and, started again, shows again;
// the server panel's link steers BETA_; a server the gateway does not serve is said on the page.
// Leaves OUT_DIR/servers.png.
//   node servers_test.mjs PAGE_URL FLAGCTL OUT_DIR FLAGD BETA_PID_FILE
// (LCM_DEFAULT_URL in the environment; BETA_PID_FILE holds BETA_'s flagd pid, and the new one's
// once this test has started it again.)
import { execFile, spawn } from "node:child_process";
import { createHash } from "node:crypto";
import { openSync, readFileSync, writeFileSync } from "node:fs";
import { promisify } from "node:util";

import { launchChromium } from "./browser.mjs";
import { check, run, section, waitFor } from "./checks.mjs";
import { readPngRGB } from "./png.mjs";

const [pageUrl, flagctl, outDir, flagd, betaPidFile] = process.argv.slice(2);
const execute = promisify(execFile);
/** BETA_'s command line, as the wrapper starts it: a design of its own tells the pictures apart. */
const kBetaArguments = ["--prefix", "BETA_", "--set", "frame_rate=10", "--set", "design=tricolour", "--log-level", "warn"];

/** flagctl --prefix PREFIX SUBCOMMAND...; its stdout. */
async function flagctlOn(prefix, ...args) {
  const { stdout } = await execute(flagctl, ["--prefix", prefix, "--timeout", "5", ...args]);
  return stdout;
}

/** The page's hooks, read in the page by `read(arg)`. */
const hooks = (page, read, arg) => page.evaluate(read, arg);

/** The page's address with these query parameters set (the token, if any, kept). */
function pageAddress(query) {
  const address = new URL(pageUrl);
  for (const [key, value] of Object.entries(query)) address.searchParams.set(key, value);
  return address.toString();
}

/** A server's entry in the page's newest /gateway/servers. */
const entryOf = (page, prefix) => hooks(page, (name) => window.flagsim.servers?.find((entry) => entry.prefix === name) ?? null, prefix);

/** SHA-256 of a picture of the page, RGB8 (`which`: "main" or "beside"), computed in the page. */
function pageDigest(page, which) {
  return page.evaluate(async (picture) => {
    const rgb = picture === "beside" ? window.flagsim.besideImageRGB() : window.flagsim.imageRGB();
    const digest = new Uint8Array(await crypto.subtle.digest("SHA-256", rgb));
    return Array.from(digest, (byte) => byte.toString(16).padStart(2, "0")).join("");
  }, which);
}

/** The frame a picture shows: { id, width, height, step, hash, hashOk }. */
const shownFrame = (page, which) => hooks(page, (picture) => (picture === "beside" ? window.flagsim.beside?.frame : window.flagsim.frame), which);

async function checkTheList(page) {
  section("the page, steering ALPHA_ with BETA_ beside");
  check("the page steers ALPHA_", (await hooks(page, () => window.flagsim.server)) === "ALPHA_");
  const servers = await hooks(page, () => window.flagsim.servers);
  const alpha = servers.find((entry) => entry.prefix === "ALPHA_");
  const beta = servers.find((entry) => entry.prefix === "BETA_");
  check("/gateway/servers lists both, live, each under its path", alpha?.live && beta?.live && alpha.path === "/ALPHA_" &&
        beta.path === "/BETA_", servers);
  const sized = await waitFor(async () => {
    const [a, b] = [await entryOf(page, "ALPHA_"), await entryOf(page, "BETA_")];
    return a.width === 320 && a.height === 180 && b.width === 320 && b.height === 180 && a.scene && b.scene && [a, b];
  }, 10, "both servers' size and scene in the list");
  check("  with their picture size (320 x 180) and scene", Boolean(sized), sized);
  const rows = await page.locator("#server-panel .server-row").evaluateAll((elements) =>
    elements.map((row) => ({ prefix: row.dataset.prefix, role: row.classList.contains("steered") ? "steered" : row.classList.contains("beside") ? "beside" : "" })));
  check("the server panel shows both: ALPHA_ steered, BETA_ beside",
        (await page.locator("#server-panel").isVisible()) && JSON.stringify(rows) === JSON.stringify([
          { prefix: "ALPHA_", role: "steered" }, { prefix: "BETA_", role: "beside" }]), rows);
  const captions = [await page.locator("#stage-caption").textContent(), await page.locator("#beside-stage .caption-name").textContent()];
  check("  and each picture's caption names its server", captions[0].includes("ALPHA_") && captions[1] === "BETA_", captions);
}

/** The frame a server draws on request, held (frame_rate 0), against what `which` picture shows. */
async function checkPictureIsTheServers(page, prefix, which) {
  await flagctlOn(prefix, "set", "frame_rate=0");  // frames only on request: the one compared stays the newest
  const file = `${outDir}/servers-${prefix.toLowerCase()}snapshot.png`;
  const snapshot = await flagctlOn(prefix, "snapshot", "-o", file);
  const frameId = Number(/frame (\d+)/.exec(snapshot)[1]);
  const shown = await waitFor(() => hooks(page, ([picture, id]) => {
    const frame = picture === "beside" ? window.flagsim.beside?.frame : window.flagsim.frame;
    return frame?.id === id && frame;
  }, [which, frameId]), 15, `${prefix}'s frame ${frameId} in the ${which} picture`);
  const png = readPngRGB(file);
  const digest = createHash("sha256").update(png.rgb).digest("hex");
  check(`the ${which} picture shows ${prefix}'s frame ${frameId}, hash-checked, equal to flagctl snapshot's PNG byte for byte`,
        shown.hashOk && shown.width === png.width && (await pageDigest(page, which)) === digest, shown);
  await flagctlOn(prefix, "set", "frame_rate=10");
  return digest;
}

async function checkBothAdvance(page) {
  section("both pictures advance");
  // Counted by frames shown, not by frame ids: a picture that is still decoding when the next
  // frame arrives skips to the newest, so ids may advance faster than frames are shown.
  const before = await hooks(page, () => ({ main: window.flagsim.frame, beside: window.flagsim.beside.frame,
                                            shown: [window.flagsim.framesShown, window.flagsim.beside.framesShown] }));
  const after = await waitFor(() => hooks(page, (start) => {
    const main = window.flagsim.frame;
    const beside = window.flagsim.beside?.frame;
    const shown = [window.flagsim.framesShown, window.flagsim.beside?.framesShown];
    return main.hashOk && beside?.hashOk && shown[0] >= start.shown[0] + 3 && shown[1] >= start.shown[1] + 3 &&
           { main, beside, shown };
  }, before), 15, "three more frames shown in each picture");
  check(`ALPHA_'s picture moves on (frame ${before.main.id} -> ${after.main.id}) and BETA_'s beside it ` +
        `(${before.beside.id} -> ${after.beside.id}), each hash-checked`,
        after.main.id > before.main.id && after.beside.id > before.beside.id, { before: before.shown, after: after.shown });
}

async function checkCommandsReachTheSteeredServer(page) {
  section("commands from the page reach ALPHA_ only");
  const stiffness = async (prefix) => Number(/^stiffness +([0-9.e+-]+) /m.exec(await flagctlOn(prefix, "params"))?.[1]);
  const betaBefore = await stiffness("BETA_");
  const value = betaBefore === 1500 ? 1600 : 1500;
  await waitFor(() => hooks(page, () => window.flagsim.params?.length > 0), 10, "ALPHA_'s parameter table");
  const box = page.locator('.param-row[data-name="stiffness"] input[type="number"]');
  await box.fill(String(value));
  await box.press("Enter");
  await waitFor(() => hooks(page, (wanted) => window.flagsim.params.find((p) => p.name === "stiffness")?.value === wanted, value),
                10, `PARAMS with stiffness ${value}`);
  const [alphaAfter, betaAfter] = [await stiffness("ALPHA_"), await stiffness("BETA_")];
  check(`a stiffness set on the page reaches ALPHA_ (flagctl --prefix ALPHA_ params: ${alphaAfter})`, alphaAfter === value);
  check(`  and not BETA_ (${betaAfter}, as before)`, betaAfter === betaBefore, { before: betaBefore, after: betaAfter });
  await page.locator("#clock-tools").getByRole("button", { name: "Pause" }).click();
  const paused = await waitFor(async () => {
    const [alpha, beta] = [await entryOf(page, "ALPHA_"), await entryOf(page, "BETA_")];
    return alpha.paused && { alpha: alpha.paused, beta: beta.paused };
  }, 10, "the list to say ALPHA_ is paused");
  check("Pause on the page pauses ALPHA_ (/gateway/servers says so) and not BETA_", paused.alpha && !paused.beta, paused);
  await page.locator("#clock-tools").getByRole("button", { name: "Resume" }).click();
  await waitFor(async () => !(await entryOf(page, "ALPHA_")).paused, 10, "ALPHA_ running again");
}

async function checkCloseAndOpenBeside(page) {
  section("the picture beside, closed and opened again");
  await page.locator("#beside-stage .caption-close").click();
  await waitFor(() => hooks(page, () => window.flagsim.beside === null), 5, "the picture beside closed");
  check("closing it hides it and drops beside from the address",
        (await page.locator("#beside-stage").isHidden()) && !new URL(page.url()).searchParams.has("beside"), page.url());
  await page.locator('#server-panel .server-row[data-prefix="BETA_"]').getByRole("button", { name: "Watch beside" }).click();
  await waitFor(() => hooks(page, () => window.flagsim.beside?.framesShown >= 2 && window.flagsim.beside.frame.hashOk),
                15, "BETA_'s frames beside again");
  check("Watch beside in the server panel shows BETA_'s frames again, hash-checked, and says so in the address",
        new URL(page.url()).searchParams.get("beside") === "BETA_", page.url());
}

async function checkServerGoneAndBack(page) {
  section("BETA_ stopped, then started again");
  process.kill(Number(readFileSync(betaPidFile, "utf8").trim()), "SIGTERM");
  const gone = await waitFor(async () => (await entryOf(page, "BETA_"))?.live === false, 15, "the list to say BETA_ is gone");
  const caption = await page.locator("#beside-stage .caption-state").textContent();
  check("the list says BETA_ is gone once it falls silent, and so does the caption beside", gone && caption.includes("gone"), caption);
  const mainBefore = await shownFrame(page, "main");
  const mainGoesOn = await hooks(page, (id) => window.flagsim.waitForFrame((frame) => frame.id >= id + 2 && frame.hashOk, 5000)
    .then(() => true, () => false), mainBefore.id);
  check("  ALPHA_'s picture goes on", mainGoesOn);
  const log = openSync(`${outDir}/servers-beta-restarted.log`, "w");
  const server = spawn(flagd, kBetaArguments, { detached: true, stdio: ["ignore", log, log] });
  server.unref();
  writeFileSync(betaPidFile, `${server.pid}\n`);
  await waitFor(async () => (await entryOf(page, "BETA_"))?.live === true, 30, "the list to say BETA_ is live again");
  await flagctlOn("BETA_", "camera", "size", "320", "180");
  const shownBefore = await hooks(page, () => window.flagsim.beside.framesShown);
  const back = await waitFor(() => hooks(page, (count) => {
    const beside = window.flagsim.beside;
    return beside.framesShown >= count + 3 && beside.frame.hashOk && beside.frame;
  }, shownBefore), 30, "BETA_'s frames beside again");
  check("BETA_ started again is live in the list, and its picture beside moves on, hash-checked", Boolean(back), back);
}

async function checkSteerAnother(page) {
  section("steering another server");
  await Promise.all([page.waitForURL(/[?&]server=BETA_/, { timeout: 10000 }),
                     page.locator('#server-panel .server-row[data-prefix="BETA_"] a.button').click()]);
  await page.waitForFunction(() => window.flagsim?.server === "BETA_" && window.flagsim.framesShown >= 2 && window.flagsim.frame.hashOk,
                             null, { timeout: 20000 });
  const address = new URL(page.url());
  check("Steer opens the page on BETA_: its frames, hash-checked; the picture beside (BETA_ itself) dropped",
        address.searchParams.get("server") === "BETA_" && !address.searchParams.has("beside") &&
        (await hooks(page, () => window.flagsim.beside)) === null, address.search);
  await page.goto(pageAddress({ server: "GAMMA_" }));
  const note = await waitFor(async () => {
    const text = await page.locator("#stage-empty").textContent();
    return text.includes("serves no server GAMMA_") && text;
  }, 10, "the page to say GAMMA_ is not served");
  check("a server the gateway does not serve is said on the page, with the list to choose from",
        (await page.locator("#server-panel").isVisible()) && note.includes("ALPHA_, BETA_"), note);
}

await run(async () => {
  const browser = await launchChromium();
  try {
    const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
    const errors = [];
    page.on("pageerror", (error) => errors.push(error.message));
    await page.goto(pageAddress({ server: "ALPHA_", beside: "BETA_" }));
    await page.waitForFunction(() => window.flagsim?.framesShown >= 3 && window.flagsim.frame.hashOk &&
                               window.flagsim.beside?.framesShown >= 3 && window.flagsim.beside.frame.hashOk, null, { timeout: 30000 });
    check("the page opens on ALPHA_ with BETA_ beside, both showing hash-checked frames", true);
    await checkTheList(page);
    section("each picture is its server's");
    const alphaDigest = await checkPictureIsTheServers(page, "ALPHA_", "main");
    const betaDigest = await checkPictureIsTheServers(page, "BETA_", "beside");
    check("  the two servers' pictures differ (their designs), so the comparison tells them apart", alphaDigest !== betaDigest);
    await checkBothAdvance(page);
    await checkCommandsReachTheSteeredServer(page);
    await page.waitForTimeout(1500);  // the plots fill a little
    await page.locator("#side").evaluate((side) => side.scrollTo(0, 0));  // the server panel in sight
    await page.screenshot({ path: `${outDir}/servers.png` });
    check(`a screenshot of the page: ${outDir}/servers.png`, true);
    await checkCloseAndOpenBeside(page);
    await checkServerGoneAndBack(page);
    await checkSteerAnother(page);
    check("no script errors on the page", errors.length === 0, errors);
  } finally {
    await browser.close();
  }
});
