// The flag's design: a built-in one from the list, or your own image (a PNG or JPEG), chosen
// with the button or dropped on the picture. Transparent pixels cut the flag's outline; the flag
// takes the image's aspect unless its width was set.
//
//   the list        --> /flag/design { name }                  (PARAM design)
//   a file, a drop  --> design_upload.js, in parts              (DESIGN, the server's answer)
//   /flag/params    --> the list shows the design in force ("your image" while one is shown)
import { el } from "./dom.js";
import { uploadDesign } from "./design_upload.js";

export class DesignPanel {
  /// `stage`: where a dropped file is taken.
  constructor({ container, connection, toast, stage }) {
    this.connection = connection;
    this.toast = toast;
    this.select = el("select", { title: "a built-in design", onchange: () => this.choose(this.select.value) });
    this.file = el("input", { type: "file", accept: "image/png,image/jpeg,.png,.jpg,.jpeg", hidden: true, onchange: () => this.takeFiles(this.file.files) });
    const pick = el("button", { type: "button", title: "a PNG or JPEG of your own: transparent pixels cut the flag's outline", onclick: () => this.file.click() }, "Your image…");
    this.progress = el("span", { class: "muted design-progress", "aria-live": "polite" });
    container.append(el("div", { class: "row design" }, this.select, pick, this.file), this.progress,
      el("p", { class: "muted hint" }, "or drop an image on the picture"));
    stage.addEventListener("dragover", (event) => {
      if (![...event.dataTransfer.types].includes("Files")) return;
      event.preventDefault();
      stage.classList.add("dropping");
    });
    stage.addEventListener("dragleave", () => stage.classList.remove("dropping"));
    stage.addEventListener("drop", (event) => {
      stage.classList.remove("dropping");
      if (event.dataTransfer.files.length === 0) return;
      event.preventDefault();
      this.takeFiles(event.dataTransfer.files);
    });
  }

  /// The parameter table: the design parameter's choices and value.
  update(params) {
    const design = params.find((p) => p.name === "design");
    if (!design) return;
    const names = design.choices.filter((choice) => choice !== "image");
    const value = typeof design.value === "number" ? design.choices[design.value] : String(design.value);
    const signature = names.join("|");
    if (this.select.dataset.choices !== signature) {
      this.select.replaceChildren(...names.map((name) => el("option", { value: name }, name.replace("_", " "))),
        el("option", { value: "image", disabled: true }, "your image"));
      this.select.dataset.choices = signature;
    }
    if (document.activeElement !== this.select) this.select.value = value;
  }

  choose(name) {
    this.connection.call("/flag/design", { name }).then(
      (answer) => { if (!answer?.accepted) this.toast(`Design: ${answer?.reason ?? "refused"}`, "warning"); },
      (error) => this.toast(`Design: ${error.message}`, "warning"));
  }

  async takeFiles(files) {
    const file = files?.[0];
    if (!file) return;
    this.progress.textContent = `${file.name}: sending …`;
    try {
      const answer = await uploadDesign(file, (service, request) => this.connection.call(service, request),
        (sent, total) => (this.progress.textContent = `${file.name}: ${Math.round((100 * sent) / total)} %`));
      this.progress.textContent = answer.reason || `${file.name} shown`;
    } catch (error) {
      this.progress.textContent = "";
      this.toast(`Design: ${error.message}`, "warning");
    } finally {
      this.file.value = "";
    }
  }
}
