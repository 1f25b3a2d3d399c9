// From the picture's pixels to the camera's metres, using `/flag/camera` (flagsim.Camera:
// eye, target, fov in degrees, view as a column-major 4x4).
//
//   camera --cameraAxes--> right, up, forward (unit vectors), eye-target distance
//   drag (dx, dy px on screen) --panVector--> translate vector (m) in the camera's right/up plane

function subtract(a, b) {
  return [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
}

function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

function length(a) {
  return Math.hypot(a[0], a[1], a[2]);
}

function normalize(a) {
  const norm = length(a);
  return norm > 0 ? [a[0] / norm, a[1] / norm, a[2] / norm] : [0, 0, 0];
}

/// The view matrix's row `row` (of its rotation part), as a unit vector: in camera space x is
/// right, y up, z backwards.
function viewRow(view, row) {
  return normalize([view[row], view[row + 4], view[row + 8]]);
}

/// camera -> { right, up, forward (unit vectors), distance (m, eye to target) }, or null.
/// TRANSLATE moves eye and target, which the server's LookAt turns into the view with y up, so
/// the axes follow from them; they equal the view matrix's rows (what the picture shows as right
/// and up) until a rotate_x/y/z turns the scene, after which the view's rows would send the
/// camera askew. Without eye and target, the view's rows are all there is.
export function cameraAxes(camera) {
  if (!camera) return null;
  if (Array.isArray(camera.eye) && Array.isArray(camera.target)) {
    const toTarget = subtract(camera.target, camera.eye);
    const forward = normalize(toTarget);
    const right = normalize(cross(forward, [0, 1, 0]));
    if (length(right) > 0) return { right, up: cross(right, forward), forward, distance: length(toTarget) };
  }
  if (Array.isArray(camera.view) && camera.view.length === 16) {
    const back = viewRow(camera.view, 2);
    const distance = Array.isArray(camera.eye) && Array.isArray(camera.target)
      ? length(subtract(camera.target, camera.eye)) : 1;
    return { right: viewRow(camera.view, 0), up: viewRow(camera.view, 1), forward: back.map((v) => -v), distance };
  }
  return null;
}

/// Metres at the target's distance per screen pixel, for a picture `displayHeight` px tall.
export function metresPerPixel(camera, displayHeight) {
  const axes = cameraAxes(camera);
  if (!axes || !(displayHeight > 0) || !(camera.fov > 0)) return 0;
  const fovRadians = (camera.fov * Math.PI) / 180;
  return (2 * axes.distance * Math.tan(fovRadians / 2)) / displayHeight;
}

/// The camera's move for a pan by (dx, dy) screen px: the scene follows the pointer, so the
/// camera moves the other way (left for a drag to the right, up for a drag down).
export function panVector(camera, dx, dy, displayHeight) {
  const axes = cameraAxes(camera);
  const scale = metresPerPixel(camera, displayHeight);
  if (!axes || scale === 0) return null;
  return combine(axes.right, -dx * scale, axes.up, dy * scale);
}

/// a * s + b * t
export function combine(a, s, b, t) {
  return [a[0] * s + b[0] * t, a[1] * s + b[1] * t, a[2] * s + b[2] * t];
}
