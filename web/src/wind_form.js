// The wind panel's boxes read as a `/flag/wind` request, checked as the server checks it, so
// that nothing invalid is ever sent as something else (an empty or mistyped speed used to go
// out as 0 and stop the wind):
//
//   { speed, direction, up, gust, ramp } (the boxes' texts)
//       --readWindForm--> { request: { velocity: [vx, vy, vz], gust, ramp } }
//                      or { problems: [{ field, message }] }, each in the units typed
//
// speed and direction are in the ground plane (degrees from +x toward +z), up is vy.

export const kMaxWindSpeed = 60;  ///< m/s, the server's limit on |velocity|
export const kMaxGust = 1;        ///< fraction of the speed
export const kMaxRamp = 60;       ///< s

const kFields = {
  speed: { label: "Speed", unit: "m/s", min: 0, max: kMaxWindSpeed },
  direction: { label: "Direction", unit: "°", min: -Infinity, max: Infinity },
  up: { label: "Up", unit: "m/s", min: -kMaxWindSpeed, max: kMaxWindSpeed },
  gust: { label: "Gust", unit: "", min: 0, max: kMaxGust },
  ramp: { label: "Ramp", unit: "s", min: 0, max: kMaxRamp },
};

/// The number in `text` for `field`, or the problem with it.
function readField(field, text) {
  const { label, unit, min, max } = kFields[field];
  const trimmed = String(text ?? "").trim();
  const value = Number(trimmed);
  const units = unit ? ` ${unit}` : "";
  if (trimmed === "") return { problem: `${label}: empty or not a number` };  // a number box holds "" for "abc"
  if (!Number.isFinite(value)) return { problem: `${label}: '${trimmed}' is not a number` };
  if (value < min || value > max) {
    const allowed = Number.isFinite(min) ? `${min} .. ${max}${units}` : `any angle`;
    return { problem: `${label}: ${trimmed}${units} is out of range; allowed ${allowed}` };
  }
  return { value };
}

/// To 1 mm/s, so a typed 6 m/s at 0 degrees sends exactly [6, vy, 0].
function round(value) {
  return Math.round(value * 1000) / 1000;
}

/// The boxes' texts -> { request } or { problems }.
export function readWindForm(texts) {
  const values = {};
  const problems = [];
  for (const field of Object.keys(kFields)) {
    const { value, problem } = readField(field, texts[field]);
    if (problem) problems.push({ field, message: problem });
    else values[field] = value;
  }
  if (problems.length > 0) return { problems };
  const angle = (values.direction * Math.PI) / 180;
  const velocity = [round(values.speed * Math.cos(angle)), values.up, round(values.speed * Math.sin(angle))];
  const magnitude = Math.hypot(...velocity);
  if (magnitude > kMaxWindSpeed) {
    return { problems: [{ field: "up", message: `Speed with Up: ${round(magnitude)} m/s is out of range; allowed 0 .. ${kMaxWindSpeed} m/s` }] };
  }
  return { request: { velocity, gust: values.gust, ramp: values.ramp } };
}
