// Checks shared by the live view's tests, in the spirit of tests/integration/checks.sh: each
// prints "ok" or "FAIL" with what it checked, and finish() exits 1 if any failed.
let passes = 0;
let failures = 0;
const started = Date.now();

/** Counts one check; `detail` (anything printable) says why it failed. */
export function check(description, condition, detail = "") {
  if (condition) {
    passes += 1;
    console.log(`ok    ${description}`);
  } else {
    failures += 1;
    console.log(`FAIL  ${description}${detail === "" ? "" : `\n      ${typeof detail === "string" ? detail : JSON.stringify(detail)}`}`);
  }
  return condition;
}

/** Resolves with predicate()'s first truthy value, polling every 20 ms; rejects after `seconds`. */
export async function waitFor(predicate, seconds, what) {
  const end = Date.now() + seconds * 1000;
  for (;;) {
    const value = await predicate();
    if (value) return value;
    if (Date.now() > end) throw new Error(`no ${what} within ${seconds} s`);
    await new Promise((resolve) => setTimeout(resolve, 20));
  }
}

/** A section heading in the output, with the seconds since the test began. */
export function section(title) {
  console.log(`-- ${title} (at ${((Date.now() - started) / 1000).toFixed(1)} s)`);
}

export function finish() {
  console.log(`${passes} passed, ${failures} failed`);
  process.exit(failures === 0 ? 0 : 1);
}

/** Runs `body`; an exception counts as a failed check and ends the run. */
export async function run(body) {
  try {
    await body();
  } catch (error) {
    check(`no exception (${error.message})`, false, error.stack);
  }
  finish();
}
