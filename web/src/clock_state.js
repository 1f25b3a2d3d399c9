// The simulation's clock as `/flag/status` tells it (paused, steps owed, time_scale), in words,
// and the step count a person typed, checked as the server checks it. No DOM: node tests it.

export const kTimeScales = [0.1, 0.25, 0.5, 1, 2, 4];  ///< the speeds offered (time_scale: 0.1 .. 4)
export const kMaxSteps = 100000;                       ///< a TIME step's most steps

/// { paused, text }: "running · 1×", "paused · 0.5×", "stepping: 12 to go · 1×"; null before
/// the first STATUS.
export function readClock(status) {
  if (!status || typeof status.time_scale !== "number") return null;
  const scale = `${status.time_scale}×`;
  const owed = Number.isInteger(status.steps_owed) ? status.steps_owed : 0;
  if (status.paused && owed > 0) return { paused: true, text: `stepping: ${owed} to go · ${scale}` };
  if (status.paused) return { paused: true, text: `paused · ${scale}` };
  return { paused: false, text: `running · ${scale}` };
}

/// The step box's text as a TIME step's count: { steps } or { problem } (nothing is sent then).
export function readSteps(text) {
  const trimmed = String(text ?? "").trim();
  if (trimmed === "") return { problem: `steps: empty; allowed a whole number 1 .. ${kMaxSteps}` };
  const steps = Number(trimmed);
  if (!Number.isInteger(steps) || steps < 1 || steps > kMaxSteps) {
    return { problem: `steps: '${trimmed}' is not allowed; allowed a whole number 1 .. ${kMaxSteps}` };
  }
  return { steps };
}
