// `/flag/timeline` (flagsim.Timeline) read into one shape, and where its position is now.
//
//   { playing, position (s), speed, loop, lastKeyTime (s), gliding, keys: [{ time, law, wind?,
//     parameters?, camera? }] }  + the simulated time it arrived at
//   --positionAt(simTime)--> s of timeline time, moving between the 1 Hz messages
//
// Keys are read as `/flag/keyframe` takes them (law by name; wind { velocity, gust };
// parameters { NAME: value }; camera { eye, target, fov }), and from the LCM message's own
// field names (has_wind, wind_velocity, names/values, ...) too.

export const kLaws = ["step", "linear", "smooth", "cubic"];  ///< timeline_key_t's LAW_* in order

export function readTimeline(message, simTime) {
  const keys = (message?.keys ?? []).map(readKey).sort((a, b) => a.time - b.time);
  return {
    playing: Boolean(message?.playing),
    position: Number(message?.position ?? 0),
    speed: Number(message?.speed ?? 1),
    loop: Boolean(message?.loop),
    lastKeyTime: Number(message?.last_key_time ?? (keys.length ? keys[keys.length - 1].time : 0)),
    gliding: Boolean(message?.gliding),
    keys,
    simTimeAtMessage: simTime,  ///< s, the flag's time when the message came (null: unknown)
    receivedAt: performance.now(),
  };
}

function readKey(key) {
  const law = typeof key.law === "number" ? kLaws[key.law] ?? String(key.law) : String(key.law ?? "linear");
  const result = { time: Number(key.time ?? 0), law };
  const wind = key.wind ?? (key.has_wind ? { velocity: key.wind_velocity, gust: key.wind_gust } : null);
  if (wind) result.wind = { velocity: wind.velocity ?? [0, 0, 0], gust: wind.gust ?? 0 };
  const parameters = key.parameters ?? zipParameters(key.names, key.values);
  if (parameters && Object.keys(parameters).length > 0) result.parameters = parameters;
  const camera = key.camera ?? (key.has_camera ? { eye: key.camera_eye, target: key.camera_target, fov: key.camera_fov } : null);
  if (camera) result.camera = camera;
  return result;
}

function zipParameters(names, values) {
  if (!Array.isArray(names) || !Array.isArray(values)) return null;
  return Object.fromEntries(names.map((name, i) => [name, values[i]]));
}

/// The timeline's position now: the message's, moved on by speed times the simulated time
/// since (or the wall time, without states), wrapped or stopped at the last key.
export function positionAt(timeline, simTime) {
  if (!timeline) return 0;
  if (!timeline.playing) return timeline.position;
  const elapsed = timeline.simTimeAtMessage !== null && simTime !== null
    ? simTime - timeline.simTimeAtMessage
    : (performance.now() - timeline.receivedAt) / 1000;
  let position = timeline.position + Math.max(0, elapsed) * timeline.speed;
  if (timeline.lastKeyTime > 0 && position > timeline.lastKeyTime) {
    position = timeline.loop ? position % timeline.lastKeyTime : timeline.lastKeyTime;
  }
  return position;
}
