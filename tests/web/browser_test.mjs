// The live view in a real browser (Debian's Chromium, headless, driven by playwright-core):
// the picture is the server's frame byte for byte, dragging orbits the camera, the parameter
// panel sets a value and shows a rejection's reason, the keyboard resets the view, a timeline
// key is added and played, the clock pauses and steps, a design is chosen, uploaded and dropped,
// a recording downloads as MCAP and MP4,
// the page fits a phone and a pinch zooms, a linked view is offered, and the page follows flagd
// stopped and started again. Leaves screenshots of the page in OUT_DIR.
//   node browser_test.mjs PAGE_URL FLAGCTL PREFIX OUT_DIR FLAGD PID_FILE
// (LCM_DEFAULT_URL in the environment; PID_FILE holds the running flagd's pid, and the new
// one's once this test has started it again.)
import { execFile, spawn } from "node:child_process";
import { openSync, readFileSync, writeFileSync } from "node:fs";
import { createHash } from "node:crypto";
import { promisify } from "node:util";

import { launchChromium } from "./browser.mjs";
import { check, run, section, waitFor } from "./checks.mjs";
import { encodePngRGBA, readPngRGB } from "./png.mjs";

const [pageUrl, flagctl, prefix, outDir, flagd, pidFile] = process.argv.slice(2);
const execute = promisify(execFile);
const mcapCheck = new URL("./mcap_check.mjs", import.meta.url).pathname;

/** flagctl SUBCOMMAND... on the test's server; its stdout. */
async function flagctlRun(...args) {
  const { stdout } = await execute(flagctl, ["--prefix", prefix, "--timeout", "5", ...args]);
  return stdout;
}

/** The page's hooks, read in the page by `read(arg)`. */
const hooks = (page, read, arg) => page.evaluate(read, arg);

/** SHA-256 of the page's RGB8 image (`source` "image": the assembled frame; "canvas": what the
 *  canvas holds, alpha dropped), computed in the page: a 1280 x 720 frame is 2.7 MB, too much to
 *  carry out of it as numbers. */
function pageDigest(page, source) {
  return page.evaluate(async (from) => {
    let rgb = window.flagsim.imageRGB();
    if (from === "canvas") {
      const picture = document.querySelector("#picture");
      const rgba = picture.getContext("2d").getImageData(0, 0, picture.width, picture.height).data;
      rgb = new Uint8Array((rgba.length / 4) * 3);
      for (let i = 0, j = 0; i < rgba.length; i += 4, j += 3) rgb.set(rgba.subarray(i, i + 3), j);
    }
    const digest = new Uint8Array(await crypto.subtle.digest("SHA-256", rgb));
    return Array.from(digest, (byte) => byte.toString(16).padStart(2, "0")).join("");
  }, source);
}

async function checkPictureIsTheServersFrame(page) {
  section("the picture is the server's frame");
  await flagctlRun("set", "frame_rate=0");  // frames only on request: the one compared stays the newest
  const snapshot = await flagctlRun("snapshot", "-o", `${outDir}/snapshot.png`);
  const frameId = Number(/frame (\d+)/.exec(snapshot)[1]);
  await page.waitForFunction((id) => window.flagsim.frame.id === id, frameId, { timeout: 15000 });
  const png = readPngRGB(`${outDir}/snapshot.png`);
  const pngDigest = createHash("sha256").update(png.rgb).digest("hex");
  const shown = await hooks(page, () => window.flagsim.frame);
  check(`the page shows frame ${frameId}, hash-checked`, shown.hashOk, shown.hash);
  check("  its image equals flagctl snapshot's PNG of that frame, byte for byte",
        shown.width === png.width && shown.height === png.height && (await pageDigest(page, "image")) === pngDigest,
        { width: shown.width, png: png.width });
  check("  and so does the canvas it is drawn on", (await pageDigest(page, "canvas")) === pngDigest);
  await flagctlRun("set", "frame_rate=30");
}

async function checkDragOrbits(page) {
  section("drag to orbit");
  const before = await hooks(page, () => window.flagsim.camera);
  const box = await page.locator("#picture").boundingBox();
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + box.width / 2, y);
  await page.mouse.down();
  for (let step = 1; step <= 10; step += 1) await page.mouse.move(box.x + box.width / 2 + 15 * step, y);
  await page.mouse.up();
  const ack = await waitFor(() => hooks(page, () => window.flagsim.lastAck?.channel === "CAMERA" && window.flagsim.lastAck),
                            10, "the CAMERA ACK");
  check("the drag goes out as CAMERA and the server accepts it", ack.accepted === true, ack);
  const after = await waitFor(() => hooks(page, (eye) => {
    const camera = window.flagsim.camera;
    return camera && camera.eye.some((value, k) => Math.abs(value - eye[k]) > 1e-6) && camera;
  }, before.eye), 10, "a camera with a new eye");
  const radius = (camera) => Math.hypot(...camera.eye.map((value, k) => value - camera.target[k]));
  check("  the eye went round the target, at the same distance", Math.abs(radius(after) - radius(before)) < 1e-6,
        { before: before.eye, after: after.eye });
  const frame = await page.evaluate((view) => window.flagsim.waitForFrame(() => true, 10000).then(() => view), after.view);
  check("  and frames keep coming, hash-checked, from the new view", (await hooks(page, () => window.flagsim.frame.hashOk)) && frame);
  await page.screenshot({ path: `${outDir}/after-orbit.png` });
}

async function checkParameterPanel(page) {
  section("the parameter panel");
  const row = page.locator('.param-row[data-name="stiffness"]');
  const box = row.locator('input[type="number"]');
  // Two changes back to back: the second is refused, and the first's answer, whenever it
  // arrives, must not hide the refusal.
  await box.fill("1500");
  await box.press("Enter");
  await box.fill("-5");
  await box.press("Enter");
  await waitFor(() => hooks(page, () => window.flagsim.params?.find((p) => p.name === "stiffness")?.value === 1500),
                10, "PARAMS with stiffness 1500");
  check("a value typed in the panel reaches the server (PARAMS shows it)", true);
  const params = await flagctlRun("params");
  check("  flagctl params agrees", /^stiffness +1500 /m.test(params), params.split("\n").find((l) => l.startsWith("stiffness")));
  const error = row.locator(".param-error");
  await error.waitFor({ state: "visible", timeout: 10000 });
  await waitFor(() => hooks(page, () => !document.querySelector('.param-row[data-name="stiffness"]').classList.contains("pending")),
                10, "both changes answered");
  await page.waitForTimeout(500);
  const reason = (await error.isVisible()) ? await error.textContent() : "(hidden)";
  check("a value out of range then shows the server's reason, and keeps it", reason.includes("stiffness: -5 is out of range"), reason);
  const value = await hooks(page, () => window.flagsim.params.find((p) => p.name === "stiffness").value);
  check("  and changes nothing", value === 1500 && /^stiffness +1500 /m.test(await flagctlRun("params")), value);
  check("  the box shows the value in force again", Number(await box.inputValue()) === 1500);
  await box.fill("");
  await box.pressSequentially("abc");  // a number box takes none of it: its value is ""
  await box.press("Enter");
  await error.waitFor({ state: "visible", timeout: 10000 });
  const text = await error.textContent();
  check("text in the box is refused on the page, with the range", text.includes("stiffness: empty or not a number; allowed 1 .."), text);
  await box.pressSequentially("1");
  check("  and the message goes as the box is typed in again", await error.isHidden());
  await box.fill("1500");
  await box.press("Enter");
}

async function checkWindPanel(page) {
  section("the wind panel");
  const panel = page.locator("#wind-body");
  const speed = panel.locator('input[title^="ground-plane speed"]');
  const apply = panel.locator("button.primary");
  const result = panel.locator(".result");
  const windAcks = () => hooks(page, () => window.flagsim.lastAck?.channel === "WIND");
  await speed.fill("");
  await speed.pressSequentially("abc");  // a number box takes none of it: its value is ""
  await apply.click();
  await page.waitForTimeout(500);
  const refused = await result.textContent();
  check("a speed typed as text is named and not sent", refused.includes("Speed: empty or not a number"), refused);
  check("  the box is marked", await speed.evaluate((box) => box.classList.contains("invalid")));
  check("  and no WIND went to the server", !(await windAcks()), await hooks(page, () => window.flagsim.lastAck));
  await speed.fill("6");
  check("  typing in the box clears the mark and the message",
        !(await speed.evaluate((box) => box.classList.contains("invalid"))) && (await result.textContent()) === "");
  await apply.click();
  const ack = await waitFor(() => hooks(page, () => window.flagsim.lastAck?.channel === "WIND" && window.flagsim.lastAck),
                            10, "the WIND ACK");
  check("a valid wind is sent and accepted", ack.accepted === true, ack);
}

async function checkKeyboardReset(page) {
  section("the keyboard");
  await page.locator("#stage").focus();
  await page.keyboard.press("y");
  const turned = await waitFor(() => hooks(page, () => window.flagsim.camera.eye[0] !== 2.6 && window.flagsim.camera), 10, "y to turn");
  const boxes = async () => ({
    eye: await page.locator("#camera-body .triple").nth(0).locator("input").evaluateAll((inputs) => inputs.map((i) => Number(i.value))),
    target: await page.locator("#camera-body .triple").nth(1).locator("input").evaluateAll((inputs) => inputs.map((i) => Number(i.value))),
  });
  await page.waitForTimeout(300);
  const shown = await boxes();
  const camera = await hooks(page, () => window.flagsim.camera);
  const near = (a, b) => a.every((value, k) => Math.abs(value - b[k]) < 1e-3);
  check("y turns the view, and the Eye and Target boxes show it", near(shown.eye, camera.eye) && near(shown.target, camera.target),
        { shown, camera: { eye: camera.eye, target: camera.target }, turned: turned.eye });
  await page.keyboard.press("r");
  const reset = await waitFor(() => hooks(page, () => {
    const eye = window.flagsim.camera.eye;
    return Math.abs(eye[0] - 2.6) < 1e-9 && Math.abs(eye[1] - 1.9) < 1e-9 && Math.abs(eye[2] - 4.4) < 1e-9 && eye;
  }), 10, "the scene's camera after r");
  check("r puts the camera back where the scene has it", Boolean(reset), reset);
}

/** The share of the picture that is the flag's cloth (its blue and yellow; the sky's blue is
 *  lighter, the ground green, the pole grey), and the centre of those pixels in image px. */
function flagInPicture(page) {
  return page.evaluate(() => {
    const rgb = window.flagsim.imageRGB();
    const { width, height } = window.flagsim.frame;
    const cloth = (p) => {
      const [r, g, b] = [rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]];
      return (r > 150 && g > 110 && b < 90) || (b > 70 && r < 45 && g < 120);  // yellow or blue
    };
    let count = 0, sx = 0, sy = 0;
    for (let p = 0; p < width * height; p += 1) {
      if (!cloth(p)) continue;
      count += 1;
      sx += p % width;
      sy += Math.floor(p / width);
    }
    // The cloth's pixel nearest the centre of them all (the centre itself may fall on a fold's gap).
    const [cx, cy] = [sx / Math.max(count, 1), sy / Math.max(count, 1)];
    let x = cx, y = cy, best = Infinity;
    for (let p = 0; p < width * height; p += 1) {
      const d = (p % width - cx) ** 2 + (Math.floor(p / width) - cy) ** 2;
      if (cloth(p) && d < best) [best, x, y] = [d, p % width, Math.floor(p / width)];
    }
    return { share: count / (width * height), x, y, width, height };
  });
}

async function checkZoomAndFrame(page) {
  section("zoom at the cursor, frame the flag");
  const span = (camera) => Math.hypot(...camera.eye.map((value, k) => value - camera.target[k]));
  await flagctlRun("time", "pause");  // the flag holds still under the cursor while the wheel turns
  await waitFor(() => hooks(page, () => window.flagsim.status?.paused === true), 10, "STATUS to say paused");
  const before = await hooks(page, () => window.flagsim.camera);
  const flag = await flagInPicture(page);
  const box = await page.locator("#picture").boundingBox();
  await page.mouse.move(box.x + (flag.x / flag.width) * box.width, box.y + (flag.y / flag.height) * box.height);
  for (let notch = 0; notch < 30; notch += 1) {
    await page.mouse.wheel(0, -100);
    await page.waitForTimeout(20);
  }
  const zoomed = await waitFor(() => hooks(page, (start) => {
    const camera = window.flagsim.camera;
    const ack = window.flagsim.lastAck;
    return ack?.channel === "CAMERA" && camera.eye.some((value, k) => value !== start.eye[k]) && { camera, ack };
  }, before), 10, "the camera after the wheel");
  await page.waitForTimeout(1000);  // the merged moves settle
  const after = await hooks(page, () => ({ camera: window.flagsim.camera, ack: window.flagsim.lastAck }));
  check("30 wheel clicks over the flag zoom in toward it, accepted", after.ack.accepted && span(after.camera) < span(before),
        { before: span(before), after: span(after.camera), ack: after.ack, first: zoomed.ack });
  const frameId = await hooks(page, () => window.flagsim.frame.id);
  await hooks(page, (id) => window.flagsim.waitForFrame((frame) => frame.id > id + 2 && frame.hashOk, 5000), frameId);
  const close = await flagInPicture(page);
  check(`  and stop short of it: the cloth fills the picture (${(100 * close.share).toFixed(0)} % of it, ` +
        `${(100 * flag.share).toFixed(0)} % before), not sky and ground`, close.share > 0.3 && close.share > 3 * flag.share,
        { before: flag.share, after: close.share });
  await flagctlRun("time", "resume");
  await page.locator("#stage").focus();
  await page.keyboard.press("f");
  const framed = await waitFor(() => hooks(page, (near) => {
    const camera = window.flagsim.camera;
    return camera.target.some((value, k) => Math.abs(value - near.target[k]) > 1e-6) && camera;
  }, after.camera), 10, "the camera after f");
  check("f frames the flag: the target moves to its centre, the eye back from it",
        span(framed) > span(after.camera), { before: span(after.camera), after: span(framed), target: framed.target });
  await page.keyboard.press("r");
}

async function checkTimeline(page) {
  section("the timeline");
  const wind = page.locator("#wind-body");
  await wind.locator('input[title^="ground-plane speed"]').fill("4");  // typed, not applied
  await wind.locator('input[title^="direction"]').fill("90");
  await wind.locator('input[title^="vertical"]').fill("0.5");
  const pictureBefore = await page.locator("#picture").boundingBox();
  await page.locator("#timeline-body button.primary").click();  // a key at the position now
  const keys = await waitFor(() => hooks(page, () => window.flagsim.timeline?.keys.length >= 1 && window.flagsim.timeline.keys),
                             10, "TIMELINE with a key");
  check("a key added from the page is on TIMELINE", keys.length === 1 && keys[0].wind !== undefined, keys);
  const velocity = keys[0].wind?.velocity ?? [];
  check("  with the wind the panel shows (typed, not yet applied), not the server's",
        Math.abs(velocity[0]) < 1e-9 && velocity[1] === 0.5 && velocity[2] === 4, velocity);
  await page.waitForTimeout(300);
  const pictureAfter = await page.locator("#picture").boundingBox();
  check("  selecting it moves nothing on the page (the picture keeps its size)",
        Math.abs(pictureAfter.height - pictureBefore.height) < 0.5 && Math.abs(pictureAfter.y - pictureBefore.y) < 0.5,
        { before: pictureBefore, after: pictureAfter });
  check("  flagctl keyframe list shows it", /1 key/.test(await flagctlRun("keyframe", "list")));
  // A second key an hour on: a timeline of one key ends as soon as it has glided there, so the
  // page might never see it playing on a slow machine; this one plays until paused.
  await flagctlRun("keyframe", "add", "3600", "--wind", "5", "0", "1");
  await waitFor(() => hooks(page, () => window.flagsim.timeline?.keys.length === 2), 10, "TIMELINE with two keys");
  await page.locator("#timeline-body button.play").click();
  const playing = await waitFor(() => hooks(page, () => window.flagsim.timeline?.playing && window.flagsim.timeline),
                                10, "TIMELINE playing");
  check("Play plays it", playing.playing === true, playing);
  await page.locator("#timeline-body button.play").click();
  await waitFor(() => hooks(page, () => window.flagsim.timeline?.playing === false), 10, "TIMELINE paused");
  check("  and Pause pauses it", true);
  // Scrubbing while paused: a click on the bar past the last key seeks there, and the wind follows
  // the keys at once (the last key's: 5, 0, 1 m/s), though the timeline does not play.
  const bar = await page.locator("#timeline-body .timeline-bar").boundingBox();
  await page.mouse.click(bar.x + bar.width * 0.9, bar.y + bar.height / 2);
  await waitFor(() => hooks(page, () => window.flagsim.timeline?.position >= 3600), 10, "TIMELINE past its last key");
  const previewed = await waitFor(() => hooks(page, () => {
    const wind = window.flagsim.state?.wind;
    return wind && Math.abs(wind.x - 5) < 1e-6 && Math.abs(wind.y) < 1e-6 && Math.abs(wind.z - 1) < 1e-6 && wind;
  }), 10, "the wind of the last key in STATE");
  check("scrubbing while paused previews what the keys set there (the wind follows)", Boolean(previewed), previewed);
  await page.locator("#timeline-body button.play").click();
  const again = await waitFor(() => hooks(page, () => {
    const timeline = window.flagsim.timeline;
    return timeline?.playing && timeline.position < 3600 && timeline;
  }), 10, "TIMELINE playing from the start");
  check("Play at the end plays it again from the start", again.position < 60, again.position);
  await page.locator("#timeline-body button.play").click();
}


async function checkClock(page) {
  section("the simulation's clock");
  const clock = page.locator("#clock-tools");
  await clock.getByRole("button", { name: "Pause" }).click();
  await waitFor(() => hooks(page, () => window.flagsim.status?.paused === true), 10, "STATUS to say paused");
  const held = await waitFor(() => hooks(page, () => window.flagsim.state), 5, "a STATE");
  const framesBefore = await hooks(page, () => window.flagsim.framesShown);
  const later = await waitFor(() => hooks(page, (from) => {  // a second of frames at 30 a second
    const frames = window.flagsim.framesShown;
    return frames >= from + 30 && { state: window.flagsim.state, frames };
  }, framesBefore), 15, "30 frames while paused");
  check("Pause holds the state still (its hash the same across 30 frames)",
        later.state.state_hash === held.state_hash && later.state.step === held.step, { held: held.step, later: later.state.step });
  check("  while frames keep coming", later.frames - framesBefore >= 10, later.frames - framesBefore);
  check("  and the clock says so", (await clock.locator(".clock-readout").textContent()).startsWith("paused"));
  await clock.locator("input.steps").fill("5");
  await clock.getByRole("button", { name: "Step" }).click();
  const stepped = await waitFor(() => hooks(page, (from) => {
    const state = window.flagsim.state;
    return window.flagsim.status?.steps_owed === 0 && state.step === from + 5 && state;
  }, held.step), 10, "five steps taken");
  check("Step 5 takes exactly five steps and holds again", stepped.step === held.step + 5, stepped.step);
  await clock.locator("input.steps").fill("");
  await clock.locator("input.steps").pressSequentially("abc");  // a number box takes none of it: its value is ""
  const stepBefore = await hooks(page, () => window.flagsim.state.step);
  await clock.getByRole("button", { name: "Step" }).click();
  const frameAfterClick = await hooks(page, () => window.flagsim.frame.id);  // time for a stray command to show
  await hooks(page, (id) => window.flagsim.waitForFrame((frame) => frame.id >= id + 10, 10000), frameAfterClick);
  check("  a step count that is not one is refused on the page, and nothing is sent",
        await clock.locator("input.steps.invalid").count() === 1 && await hooks(page, () => window.flagsim.state.step) === stepBefore);
  await clock.locator("input.steps").pressSequentially("1");
  check("  and the mark goes as the box is typed in again", await clock.locator("input.steps.invalid").count() === 0);
  await clock.locator("select").selectOption("0.5");
  await waitFor(() => hooks(page, () => window.flagsim.status?.time_scale === 0.5), 10, "time_scale 0.5");
  await clock.getByRole("button", { name: "Resume" }).click();
  const running = await waitFor(() => hooks(page, () => {
    const status = window.flagsim.status;
    return status?.paused === false && status.real_time_factor > 0.3 && status.real_time_factor < 0.7 && status;
  }), 10, "running at half speed");
  check("Speed 0.5× runs at half real time", Boolean(running), running.real_time_factor);
  await clock.locator("select").selectOption("1");
  await waitFor(() => hooks(page, () => window.flagsim.status?.time_scale === 1), 10, "time_scale 1");
}

/** A swallowtail pennant, 300 x 150: a blue hoist, red and white stripes, a notch cut from the fly. */
function pennantPng() {
  return encodePngRGBA(300, 150, (x, y) => {
    const notch = x > 300 - 1.1 * (75 - Math.abs(y - 75)) && x > 200;
    const colour = x < 90 ? [20, 50, 150] : Math.floor(y / 30) % 2 ? [240, 240, 235] : [200, 25, 35];
    return [...colour, notch ? 0 : 255];
  });
}

async function checkDesign(page) {
  section("the flag's design: a built-in one, your own image, a bad file dropped");
  const panel = page.locator("#design-body");
  await panel.locator("select").selectOption("checker");
  await waitFor(() => hooks(page, () => window.flagsim.params?.find((p) => p.name === "design")?.value === "checker"),
                10, "design=checker in PARAMS");
  check("the list sets a built-in design", true);
  const pennant = `${outDir}/pennant.png`;
  writeFileSync(pennant, pennantPng());
  await panel.locator("input[type=file]").setInputFiles(pennant);
  const shown = await waitFor(async () => {
    const text = await panel.locator(".design-progress").textContent();
    return text.startsWith("design pennant.png") && text;
  }, 20, "the server's answer to the upload");
  check("an image chosen with the button is sent and shown, the flag at its aspect", shown.includes("the flag 2 m wide"), shown);
  const params = await waitFor(() => hooks(page, () => {
    const design = window.flagsim.params?.find((p) => p.name === "design")?.value;
    const width = window.flagsim.params?.find((p) => p.name === "width")?.value;
    return design === "image" && width === 2 && { design, width };
  }), 10, "design=image, width 2 in PARAMS");
  check("  PARAMS say design image and width 2 m", Boolean(params), params);
  check("  the list says \"your image\"", (await panel.locator("select").inputValue()) === "image");
  const frame = await hooks(page, () => window.flagsim.frame.id);
  await hooks(page, (id) => window.flagsim.waitForFrame((f) => f.id >= id + 15 && f.hashOk, 10000), frame);
  await page.locator("#stage").screenshot({ path: `${outDir}/design-pennant.png` });
  check(`  a screenshot of the pennant: ${outDir}/design-pennant.png`, true);
  const dropped = await page.evaluateHandle(() => {
    const transfer = new DataTransfer();
    const truncated = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 0x49, 0x48];  // a signature, half a header
    transfer.items.add(new File([new Uint8Array(truncated)], "broken.png", { type: "image/png" }));
    return transfer;
  });
  await page.locator("#stage").dispatchEvent("drop", { dataTransfer: dropped });
  const refused = await waitFor(() => hooks(page, () => {
    const toast = [...document.querySelectorAll("#toasts *")].map((t) => t.textContent).find((t) => t.includes("broken.png"));
    return toast;
  }), 10, "a toast naming the dropped file's fault");
  check("a bad file dropped on the picture is refused with its reason, and nothing changes",
        refused.includes("the PNG's header cannot be read") &&
          (await hooks(page, () => window.flagsim.params?.find((p) => p.name === "design")?.value)) === "image", refused);
  await panel.locator("select").selectOption("nordic_cross");
  const back = await waitFor(() => hooks(page, () => {
    const width = window.flagsim.params?.find((p) => p.name === "width")?.value;
    return window.flagsim.params?.find((p) => p.name === "design")?.value === "nordic_cross" && width === 1.5 && width;
  }), 10, "design=nordic_cross, width 1.5 in PARAMS");
  check("back to a built-in design, the flag goes back to 3 : 2", Boolean(back), back);
}

async function checkRecordingDownloads(page) {
  section("a recording, downloaded as MCAP and MP4");
  const tools = page.locator("#session-tools");
  await tools.getByRole("button", { name: "Record" }).click();
  await waitFor(() => hooks(page, () => {  // the recorder's own count, polled by the page each second
    const seconds = Number(/([0-9.]+) s ·/.exec(document.querySelector(".record-text")?.textContent ?? "")?.[1]);
    return seconds >= 2;
  }), 20, "two seconds recorded");
  await tools.getByRole("button", { name: "Stop" }).click();
  const mcap = tools.locator(".downloads a", { hasText: "MCAP" });
  const mp4 = tools.locator(".downloads a", { hasText: "MP4" });
  await mcap.waitFor({ state: "visible", timeout: 60000 });
  await mp4.waitFor({ state: "visible", timeout: 60000 });
  check("Stop offers the log, then its MCAP and MP4 as the gateway makes them",
        await tools.locator(".downloads a").count() === 3);
  const [download] = await Promise.all([page.waitForEvent("download"), mcap.click()]);
  const file = `${outDir}/recording.mcap`;
  await download.saveAs(file);
  try {
    const { stdout } = await execute("node", [mcapCheck, file, "/flag/image", "/flag/scene", "/flag/state", "/flag/status"]);
    check("  the MCAP from the page reads in @mcap/core, every message with its schema", true, stdout);
  } catch (error) {
    check("  the MCAP from the page reads in @mcap/core, every message with its schema", false, error.stdout ?? error.message);
  }
  const response = await page.evaluate(async (href) => {
    const got = await fetch(href);
    const bytes = new Uint8Array(await got.arrayBuffer());
    return { status: got.status, type: String.fromCharCode(...bytes.subarray(4, 8)), size: bytes.length };
  }, await mp4.getAttribute("href"));
  check("  the MP4 downloads (an ISO media file)", response.status === 200 && response.type === "ftyp" && response.size > 1000, response);
}

async function checkPhone(browser) {
  section("a phone");
  const context = await browser.newContext({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true, deviceScaleFactor: 2 });
  const phone = await context.newPage();
  await phone.goto(pageUrl);
  await phone.waitForFunction(() => window.flagsim?.framesShown >= 2, null, { timeout: 20000 });
  const widths = await phone.evaluate(() => {
    const cut = [...document.querySelectorAll("#app button, #app input, #app select, #app label, #app h2")]
      .filter((element) => element.getClientRects().length > 0 && element.getBoundingClientRect().right > window.innerWidth + 0.5)
      .map((element) => element.textContent.trim() || element.outerHTML.slice(0, 60));
    return { page: document.documentElement.scrollWidth, screen: window.innerWidth, cut };
  });
  check("the page fits a phone's width: nothing overflows sideways, no control is cut off",
        widths.page <= widths.screen && widths.cut.length === 0, widths);
  await phone.screenshot({ path: `${outDir}/phone.png`, fullPage: false });
  const before = await hooks(phone, () => window.flagsim.camera);
  const box = await phone.locator("#picture").boundingBox();
  const cdp = await context.newCDPSession(phone);
  const [cx, cy] = [box.x + box.width / 2, box.y + box.height / 2];
  const fingers = (spread) => [{ x: cx - spread, y: cy, id: 1 }, { x: cx + spread, y: cy, id: 2 }];
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: fingers(20) });
  for (let spread = 25; spread <= 80; spread += 5) {
    await cdp.send("Input.dispatchTouchEvent", { type: "touchMove", touchPoints: fingers(spread) });
  }
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
  const span = (camera) => Math.hypot(...camera.eye.map((value, k) => value - camera.target[k]));
  const pinched = await waitFor(() => hooks(phone, (start) => {
    const camera = window.flagsim.camera;
    return camera.eye.some((value, k) => value !== start.eye[k]) && camera;
  }, before), 10, "the camera after a pinch");
  check("two fingers spread apart zoom in", span(pinched) < span(before), { before: span(before), after: span(pinched) });
  await context.close();
  await flagctlRun("camera", "reset");
}

async function checkTokenForm(browser) {
  section("the token, given on the 401 page");
  const context = await browser.newContext();
  const page = await context.newPage();
  const address = new URL(pageUrl);
  const token = address.searchParams.get("token");
  address.search = "";
  const refused = await page.goto(address.toString());
  check("without the token: 401, a page that says where it is", refused.status() === 401 &&
        (await page.locator("h1").textContent()).includes("A token is needed"));
  await page.locator('input[name="token"]').fill(token);
  await page.getByRole("button", { name: "Open the live view" }).click();
  await page.waitForFunction(() => window.flagsim?.framesShown >= 2, null, { timeout: 20000 });
  check("  its form takes the token, and the live view opens", true);
  await context.close();
}

/** The test's flagd, by the pid in PID_FILE. */
function serverPid() {
  return Number(readFileSync(pidFile, "utf8").trim());
}

async function checkServerStopAndRestart(page) {
  section("flagd stopped, then started again");
  process.kill(serverPid(), "SIGTERM");
  const stoppedAt = Date.now();
  const gone = await waitFor(() => hooks(page, () => {
    const text = document.querySelector("#status-bar .connection")?.textContent ?? "";
    return text.includes("server gone") && text;
  }), 10, "the page to say the server is gone");
  const goneAfter = (Date.now() - stoppedAt) / 1000;
  check(`the page says the server is gone within 3 s (${goneAfter.toFixed(1)} s)`, goneAfter <= 3, gone);
  const frameBefore = await hooks(page, () => window.flagsim.frame);
  const log = openSync(`${outDir}/flagd-restarted.log`, "w");
  const server = spawn(flagd, ["--prefix", prefix, "--log-level", "warn"], { detached: true, stdio: ["ignore", log, log] });
  server.unref();
  writeFileSync(pidFile, `${server.pid}\n`);
  const startedAt = Date.now();
  const said = await waitFor(() => hooks(page, () => {
    const text = document.querySelector("#status-bar .connection")?.textContent ?? "";
    return text.includes("server restarted") && text;
  }), 30, "the page to say the server restarted");
  const moving = await waitFor(() => hooks(page, (old) => {
    const frame = window.flagsim.frame;
    return frame.hashOk && frame.step !== old.step && frame.id < old.id && frame;
  }, frameBefore), 30, "the new server's frames");
  const firstStatus = await hooks(page, () => window.flagsim.status?.uptime ?? 0);
  check("the page says \"server restarted\"", Boolean(said), said);
  check(`  and shows the new server's frames (${((Date.now() - startedAt) / 1000).toFixed(1)} s after its start, ` +
        `its uptime ${firstStatus.toFixed(1)} s)`, Boolean(moving), moving);
  const movesOn = await hooks(page, (id) => window.flagsim.waitForFrame((frame) => frame.id >= id + 2 && frame.hashOk, 2000)
    .then(() => true, () => false), moving.id);
  check("  the picture moves on, frame after frame, within 2 s", movesOn);
}

await run(async () => {
  const browser = await launchChromium();
  try {
    const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
    const errors = [];
    page.on("pageerror", (error) => errors.push(error.message));
    section("the page");
    await page.goto(pageUrl);
    await page.waitForFunction(() => window.flagsim?.framesShown >= 3 && window.flagsim.frame.hashOk, null, { timeout: 20000 });
    check("the page loads, connects and shows hash-checked frames", true);
    const connection = await waitFor(() => hooks(page, () => {
      const field = document.querySelector("#status-bar .connection");
      return field?.textContent.includes("server alive") && field.textContent;
    }), 10, "the status bar to say the server is alive");
    check("  the status bar says the server behind the gateway is alive", Boolean(connection), connection);
    await checkPictureIsTheServersFrame(page);
    await checkDragOrbits(page);
    await checkParameterPanel(page);
    await checkWindPanel(page);
    await checkKeyboardReset(page);
    await checkZoomAndFrame(page);
    await checkTimeline(page);
    await checkClock(page);
    await checkDesign(page);
    await checkRecordingDownloads(page);
    await checkPhone(browser);
    await checkTokenForm(browser);
    section("the shared camera, and a view as a link");
    const second = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const linked = new URL(pageUrl);
    linked.searchParams.set("view", "3,2.5,5,0.75,2,0,50");
    await second.goto(linked.toString());
    const offer = second.locator("#view-offer");
    await offer.waitFor({ state: "visible", timeout: 15000 });
    const untouched = await hooks(page, () => window.flagsim.camera.eye[0] !== 3);
    check("a linked view is offered, not forced on every viewer", untouched, await offer.textContent());
    await offer.getByRole("button", { name: "Move the camera there" }).click();
    const shared = await waitFor(() => hooks(page, () => {
      const text = document.querySelector(".shared-camera")?.textContent ?? "";
      return text.includes("1 other viewer sees") && text;
    }), 15, "the camera panel to count the second viewer");
    check("a second viewer is told on the first page: the camera is shared", Boolean(shared), shared);
    const view = await waitFor(() => hooks(page, () => {
      const camera = window.flagsim.camera;
      return camera.eye[0] === 3 && camera.eye[1] === 2.5 && camera.eye[2] === 5 && camera.target[0] === 0.75 &&
             Math.abs(camera.fov - 50) < 1e-9 && camera;
    }), 15, "the linked view in force");
    check("  taken, the view in the link is the one every viewer sees", Boolean(view), view);
    await page.getByRole("button", { name: "Link to view" }).click();
    await page.waitForTimeout(300);
    const address = new URL(page.url());
    check("  Link to view puts this view in the address", address.searchParams.get("view") === "3,2.5,5,0.75,2,0,50",
          address.search);
    await second.close();
    await page.waitForTimeout(1500);  // the plots fill a little
    await page.screenshot({ path: `${outDir}/live-view.png` });
    check(`a screenshot of the page: ${outDir}/live-view.png`, true);
    await checkServerStopAndRestart(page);
    check("no script errors on the page", errors.length === 0, errors);
  } finally {
    await browser.close();
  }
});
