// A view as a link: the camera's eye, target and field of view in the page's address, so that a
// person can send the view they are looking at. Opening the link puts the (shared) camera there.
//
//   camera { eye, target, fov } --viewLinkFor--> https://host/?token=...&view=ex,ey,ez,tx,ty,tz,fov
//   ?view=... --readViewLink--> { eye, target, fov } or null (and why, for a toast)

const kDigits = 4;  ///< decimals kept: 0.1 mm, 0.0001 degrees

/// The page's address with `view` set to `camera` (the token and other parameters kept).
export function viewLinkFor(location, camera) {
  const url = new URL(location.href);
  const numbers = [...camera.eye, ...camera.target, camera.fov].map((value) => Number(value.toFixed(kDigits)));
  url.searchParams.set("view", numbers.join(","));
  url.hash = "";
  return url.toString();
}

/// The view in `search` (a location's query string): { view: { eye, target, fov } }, or
/// { problem } when `view` is there but not seven numbers, or {} when it is not there.
export function readViewLink(search) {
  const text = new URLSearchParams(search).get("view");
  if (text === null) return {};
  const numbers = text.split(",").map((part) => Number(part));
  if (numbers.length !== 7 || numbers.some((value, i) => text.split(",")[i].trim() === "" || !Number.isFinite(value))) {
    return { problem: `view: '${text}' is not seven numbers (eye x, y, z, target x, y, z in m, field of view in degrees)` };
  }
  const fov = numbers[6];
  if (fov < 10 || fov > 120) return { problem: `view: a field of view of ${fov} degrees is out of range; allowed 10 .. 120` };
  return { view: { eye: numbers.slice(0, 3), target: numbers.slice(3, 6), fov } };
}
