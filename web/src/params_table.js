// `/flag/params` (flagsim.Params) read into one shape the page uses:
//
//   { name, unit, kind: "real" | "integer" | "boolean" | "choice", min, max, defaultValue,
//     value, choices, description, animatable }
//
// `value` and `defaultValue` are numbers (real, integer), booleans, or the choice's name, as
// the protocol's parameters carry them. The reader accepts the table's field names as the LCM
// PARAMS message spells them (min_value, default_value, kind as a number) and the short ones.

const kKinds = ["real", "integer", "boolean", "choice"];  ///< parameter_t's REAL, INTEGER, BOOLEAN, CHOICE
/// The forces' coefficients a timeline key may set, when the table does not say.
export const kAnimatableNames = ["stiffness", "shear_stiffness", "bending_stiffness", "damping", "friction", "wind_coefficient", "gravity"];

/// flagsim.Params JSON -> [parameter], in the table's order.
export function readParamsTable(message) {
  const rows = Array.isArray(message) ? message : message?.parameters ?? [];
  return rows.map(readParameter).filter((parameter) => parameter.name);
}

function readParameter(row) {
  const kind = readKind(row.kind);
  const choices = Array.isArray(row.choices) ? row.choices.map(String) : [];
  const range = Array.isArray(row.range) ? row.range : [];
  const parameter = {
    name: String(row.name ?? ""),
    unit: String(row.unit ?? ""),
    kind,
    min: Number(row.min ?? row.min_value ?? range[0]),
    max: Number(row.max ?? row.max_value ?? range[1]),
    choices,
    description: String(row.description ?? ""),
    animatable: row.animatable ?? kAnimatableNames.includes(row.name),
  };
  parameter.defaultValue = readValue(parameter, row.default ?? row.default_value);
  parameter.value = readValue(parameter, row.value ?? row.value_text);
  return parameter;
}

function readKind(kind) {
  if (typeof kind === "number") return kKinds[kind] ?? "real";
  const name = String(kind ?? "real").toLowerCase();
  return kKinds.includes(name) ? name : "real";
}

/// A value as the table or the protocol gives it -> the page's form of it for `parameter`.
export function readValue(parameter, value) {
  switch (parameter.kind) {
    case "boolean":
      return value === true || value === 1 || value === "true" || value === "1" || value === "on";
    case "choice":
      return typeof value === "number" ? parameter.choices[value] ?? String(value) : String(value ?? "");
    default:
      return typeof value === "number" ? value : Number(value);
  }
}
