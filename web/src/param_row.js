// One parameter's control: a slider and a number box (real, integer), a checkbox (boolean) or a
// select (choice), with its unit, range, default and description, and the state of a change:
//
//   user edits --onCommit(value)--> pending ... --settle(valueInForce, reason)--> shown or
//                                                 reverted, with the server's reason
import { el, formatNumber, isEditing, numberInput, selectInput } from "./dom.js";
import { kSteps, sliderScale } from "./param_slider.js";

export class ParamRow {
  /// `parameter` as params_table.js reads it; `onCommit(row, value)` sends a change.
  constructor(parameter, onCommit) {
    this.parameter = parameter;
    this.onCommit = onCommit;
    this.valueInForce = parameter.value;
    this.pending = false;
    this.changes = 0;  // changes committed; the newest one's answer settles the row
    this.state = el("span", { class: "param-state" });
    this.error = el("div", { class: "param-error", hidden: true });
    this.element = el("div", { class: "param-row", title: tooltip(parameter), dataset: { name: parameter.name } },
      el("div", { class: "param-label" },
        el("span", { class: "param-name" }, parameter.name),
        parameter.unit ? el("span", { class: "unit" }, parameter.unit) : null,
        this.state,
        el("div", { class: "param-meta" }, metaText(parameter))),
      el("div", { class: "param-control" }, this.buildControl()),
      this.error);
    this.show(parameter.value);
  }

  /// Builds the control for the parameter's kind; `this.read()` and `this.show(v)` use it.
  buildControl() {
    const { kind, choices, min, max } = this.parameter;
    if (kind === "boolean") {
      this.checkbox = el("input", { type: "checkbox", onchange: () => this.commit(this.checkbox.checked) });
      return [this.checkbox];
    }
    if (kind === "choice") {
      this.select = selectInput(choices);
      this.select.addEventListener("change", () => this.commit(this.select.value));
      return [this.select];
    }
    this.scale = sliderScale(this.parameter);
    this.slider = el("input", { type: "range", min: 0, max: kSteps, step: 1 });
    this.sliding = false;  // the user holds the slider: live values wait
    this.slider.addEventListener("pointerdown", () => (this.sliding = true));
    this.slider.addEventListener("pointerup", () => (this.sliding = false));
    this.slider.addEventListener("pointercancel", () => (this.sliding = false));
    this.number = numberInput({ min, max, step: kind === "integer" ? 1 : "any" });
    this.slider.addEventListener("input", () => (this.number.value = String(this.scale.toValue(Number(this.slider.value)))));
    this.slider.addEventListener("change", () => this.commit(this.scale.toValue(Number(this.slider.value))));
    this.number.addEventListener("change", () => this.commitNumber());
    this.number.addEventListener("input", () => this.hideError());  // the refused value is being replaced
    return [this.slider, this.number];
  }

  commitNumber() {
    const value = Number(this.number.value);
    if (this.number.value.trim() === "" || !Number.isFinite(value)) {  // a number box holds "" for text
      const { name, min, max, unit } = this.parameter;
      this.settle(this.beginChange(), this.valueInForce,
                  `${name}: empty or not a number; allowed ${formatNumber(min)} .. ${formatNumber(max)}${unit ? ` ${unit}` : ""}`);
      return;
    }
    this.commit(value);
  }

  commit(value) {
    this.hideError();
    this.onCommit(this, value);
  }

  hideError() {
    this.error.hidden = true;
    this.element.classList.remove("rejected");
  }

  /// Shows `value` in the control, but not in a box the user is typing into or under a slider
  /// the user holds.
  show(value) {
    if (this.checkbox) this.checkbox.checked = Boolean(value);
    else if (this.select) this.select.value = value;
    else {
      if (!isEditing(this.number) && !this.sliding) this.number.value = formatNumber(value, 6);
      if (!this.sliding) this.slider.value = String(this.scale.toPosition(value));
    }
  }

  /// A new change: pending, its predecessors' answers ignored. Returns its number for settle.
  beginChange() {
    this.changes += 1;
    this.setPending(true);
    return this.changes;
  }

  setPending(pending) {
    this.pending = pending;
    this.element.classList.toggle("pending", pending);
    this.state.textContent = pending ? "pending" : "";
  }

  /// The value in force, from the table or the protocol: shown unless a change is pending.
  setValueInForce(value) {
    this.valueInForce = value;
    if (!this.pending) this.show(value);
  }

  /// Change `change`'s outcome: the value then in force and, when rejected, the server's
  /// reason. An answer to a change older than the newest is ignored.
  settle(change, valueInForce, reason = "") {
    if (change !== this.changes) return;
    this.setPending(false);
    this.valueInForce = valueInForce;
    this.show(valueInForce);
    this.error.textContent = reason;
    this.error.hidden = !reason;
    this.element.classList.toggle("rejected", Boolean(reason));
  }
}

function metaText({ kind, min, max, unit, defaultValue, choices }) {
  if (kind === "boolean") return `default ${defaultValue ? "on" : "off"}`;
  if (kind === "choice") return `${choices.length} choices · default ${defaultValue}`;
  return `${formatNumber(min)} .. ${formatNumber(max)}${unit ? ` ${unit}` : ""} · default ${formatNumber(defaultValue)}`;
}

function tooltip(parameter) {
  return `${parameter.name}${parameter.unit ? ` (${parameter.unit})` : ""}: ${parameter.description}\n${metaText(parameter)}`;
}
