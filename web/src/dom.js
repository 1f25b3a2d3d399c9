// Small helpers for building the page's elements and writing numbers the way people read them.

/// Creates an element: el("div", { class: "row", title: "..." }, child, "text", ...). Attributes
/// that start with "on" are event listeners; `null`/`undefined`/`false` children are skipped.
export function el(tag, attributes = {}, ...children) {
  const element = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (value === undefined || value === null || value === false) continue;
    if (name.startsWith("on")) element.addEventListener(name.slice(2), value);
    else if (name === "dataset") Object.assign(element.dataset, value);
    else element.setAttribute(name, value === true ? "" : String(value));
  }
  appendChildren(element, children);
  return element;
}

/// The same for SVG elements (the wind dial).
export function svg(tag, attributes = {}, ...children) {
  const element = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const [name, value] of Object.entries(attributes)) element.setAttribute(name, String(value));
  appendChildren(element, children);
  return element;
}

function appendChildren(element, children) {
  for (const child of children.flat()) {
    if (child === undefined || child === null || child === false) continue;
    element.append(child instanceof Node ? child : String(child));
  }
}

/// A number with `digits` significant digits, without trailing zeros: 0.0123, 1500, 2.5e+6.
export function formatNumber(value, digits = 4) {
  if (value === undefined || value === null || Number.isNaN(value)) return "–";
  if (!Number.isFinite(value)) return value > 0 ? "∞" : "-∞";
  if (value === 0) return "0";
  const magnitude = Math.abs(value);
  if (magnitude >= 1e6 || magnitude < 1e-4) return Number(value.toPrecision(digits)).toExponential();
  return String(Number(value.toPrecision(digits)));
}

/// Bytes as B, kB, MB (decimal units, as network rates are usually given).
export function formatBytes(bytes) {
  if (!Number.isFinite(bytes)) return "–";
  const units = ["B", "kB", "MB", "GB"];
  let index = 0;
  while (Math.abs(bytes) >= 1000 && index < units.length - 1) {
    bytes /= 1000;
    index += 1;
  }
  return `${formatNumber(bytes, 3)} ${units[index]}`;
}

/// A number box: <input type=number> with range and step. It notes when the user has typed into
/// it and not yet committed (Enter, or leaving it), for isEditing.
export function numberInput({ min, max, step = "any", value, title, className = "number" } = {}) {
  const input = el("input", { type: "number", class: className, min, max, step, title });
  if (value !== undefined) input.value = String(value);
  input.addEventListener("input", () => (input.dataset.typing = "1"));
  input.addEventListener("change", () => delete input.dataset.typing);
  input.addEventListener("blur", () => delete input.dataset.typing);
  return input;
}

/// True while the user is typing into `input` (focused, changed, not committed): live updates
/// must not overwrite it. Once committed, the value in force shows again.
export function isEditing(input) {
  return document.activeElement === input && input.dataset.typing === "1";
}

/// A <select> of `options` (strings, or [value, label] pairs).
export function selectInput(options, value) {
  const select = el("select");
  for (const option of options) {
    const [optionValue, label] = Array.isArray(option) ? option : [option, option];
    select.append(el("option", { value: optionValue }, label));
  }
  if (value !== undefined) select.value = value;
  return select;
}
