// The parameter panel, generated from `/flag/params`:
//
//   /flag/params (table) --update--> one ParamRow per parameter (rebuilt if the set changes)
//   row committed --setParameters([{name, value}], id)--> "pending"
//       parameterValues(id)          --> the values in force
//       status setParameters:id      --> rejected: the server's reason, the value in force again
//   parameterValues (any)            --> the values in force
//   Reset --/flag/set { reset: true }--> the scene's parameters, wind and timeline
import { el } from "./dom.js";
import { ParamRow } from "./param_row.js";
import { readValue } from "./params_table.js";

export class ParamPanel {
  constructor({ container, connection, toast }) {
    this.connection = connection;
    this.toast = toast;
    this.rows = new Map();  // name -> ParamRow
    this.signature = "";
    this.list = el("div", { class: "param-list" }, el("div", { class: "empty" }, "waiting for /flag/params …"));
    const reset = el("button", { type: "button", title: "the scene's parameters, wind and timeline, as at the start", onclick: () => this.reset() }, "Reset scene");
    container.append(el("div", { class: "button-row" }, reset), this.list);
  }

  /// The newest table: rows for new names, values in force for the others.
  update(parameters) {
    const signature = parameters.map((p) => `${p.name}:${p.kind}:${p.min}:${p.max}:${p.choices.join("|")}`).join(",");
    if (signature !== this.signature) this.rebuild(parameters, signature);
    for (const parameter of parameters) this.rows.get(parameter.name)?.setValueInForce(parameter.value);
  }

  rebuild(parameters, signature) {
    this.signature = signature;
    this.rows = new Map(parameters.map((parameter) => [parameter.name, new ParamRow(parameter, (row, value) => this.commit(row, value))]));
    this.list.replaceChildren(...[...this.rows.values()].map((row) => row.element));
  }

  /// Protocol parameter values (answers and updates) -> values in force.
  onParameterValues(values) {
    for (const { name, value } of values) {
      const row = this.rows.get(name);
      if (row && value !== undefined) row.setValueInForce(readValue(row.parameter, value));
    }
  }

  /// Sends one change with setParameters and shows it pending until its answer. Only the
  /// row's newest change settles it: an older change answered late (the gateway refuses a value
  /// out of range at once, the server accepts one a round trip later) neither hides the newer
  /// change's reason nor shows a value the newer change replaced.
  commit(row, value) {
    const { promise } = this.connection.setParameters([{ name: row.parameter.name, value }]);
    const change = row.beginChange();
    promise.then(
      (values) => {
        const answered = values?.find((each) => each.name === row.parameter.name);
        row.settle(change, answered ? readValue(row.parameter, answered.value) : row.valueInForce);
      },
      (error) => row.settle(change, row.valueInForce, error.message),
    );
  }

  reset() {
    this.connection.call("/flag/set", { parameters: {}, reset: true }).then(
      (answer) => this.toast(answer?.accepted === false ? `Reset: ${answer.reason}` : "Reset to the scene's values"),
      (error) => this.toast(`Reset: ${error.message}`),
    );
  }
}
