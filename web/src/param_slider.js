// A slider's position (0..kSteps) <-> a parameter's value over its range.
//
// Ranges that span decades (stiffness 1 .. 100000 N/m) are logarithmic, so every decade gets
// the same travel; such ranges from 0 use expm1, which is linear near 0 and logarithmic above.
// Integers round; reals keep 3 significant digits (the number box takes exact values).

export const kSteps = 1000;
const kDecadesFromZero = 4;  ///< a 0-based wide range: the first 1/kSteps of travel covers max * 1e-4

export function sliderScale(parameter) {
  const { min, max, kind } = parameter;
  const wide = spansDecades(parameter);
  const round = kind === "integer" ? Math.round : (value) => Number(value.toPrecision(3));
  if (!wide) return linearScale(min, max, kind === "integer" ? Math.round : (value) => value);
  return min > 0 ? logScale(min, max, round) : expm1Scale(max, round);
}

/// True when a linear slider would crowd the useful values into its first few steps: the range
/// spans 3 decades (1 .. 100000), or from 0 it reaches 1000 or 100 times the default (damping
/// 0 .. 100 N s/m, default 0.05).
function spansDecades({ min, max, defaultValue }) {
  if (!(max > 0) || min < 0) return false;
  if (min > 0) return max / min >= 1000;
  return max >= 1000 || (defaultValue > 0 && max / defaultValue >= 100);
}

function clampPosition(position) {
  return Math.max(0, Math.min(kSteps, position));
}

function linearScale(min, max, round) {
  const span = max - min || 1;
  return {
    toValue: (position) => round(min + (span * position) / kSteps),
    toPosition: (value) => clampPosition(((value - min) / span) * kSteps),
  };
}

function logScale(min, max, round) {
  const ratio = Math.log(max / min);
  return {
    toValue: (position) => Math.min(max, Math.max(min, round(min * Math.exp((ratio * position) / kSteps)))),
    toPosition: (value) => clampPosition((Math.log(Math.max(value, min) / min) / ratio) * kSteps),
  };
}

function expm1Scale(max, round) {
  const k = kDecadesFromZero * Math.LN10;
  return {
    toValue: (position) => (position <= 0 ? 0 : Math.min(max, round((max * Math.expm1((k * position) / kSteps)) / Math.expm1(k)))),
    toPosition: (value) => clampPosition((Math.log1p((Math.max(value, 0) * Math.expm1(k)) / max) / k) * kSteps),
  };
}
