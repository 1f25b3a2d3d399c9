// Live plots (uPlot), a rolling window of the last 30 s:
//
//   /flag/status --addStatus--> real-time factor, step and render time, frame rate, bytes/s
//   /flag/state  --addState---> the tip's position, the kinetic energy (at most 20 points/s)
//   every 250 ms --> old points dropped, charts redrawn, the newest values in each header
import uPlot from "uplot";
import { el, formatBytes, formatNumber } from "./dom.js";

const kWindow = 30;          ///< s of history shown
const kRedrawPeriod = 250;   ///< ms between redraws
const kMinStateGap = 0.05;   ///< s between two state points kept
const kColours = ["#2f7fd8", "#d9822b", "#3aa676", "#b04fc5"];

/// Each chart: a title, its series (label, unit, formatter) and where its values come from.
const kCharts = [
  { id: "rtf", title: "Real-time factor", series: [{ label: "", unit: "×" }] },
  { id: "step", title: "Step time", series: [{ label: "", unit: "µs" }] },
  { id: "fps", title: "Frames per second", series: [{ label: "server" }, { label: "shown" }] },
  { id: "bytes", title: "Bus bytes per second", series: [{ label: "", format: (v) => `${formatBytes(v)}/s` }], axis: (v) => formatBytes(v) },
  { id: "tip", title: "Tip position (m)", series: [{ label: "x" }, { label: "y" }, { label: "z" }] },
  { id: "energy", title: "Kinetic energy", series: [{ label: "", unit: "J" }] },
];

export class Plots {
  constructor({ container }) {
    this.charts = new Map();
    this.lastStateTime = 0;
    for (const spec of kCharts) this.charts.set(spec.id, this.makeChart(container, spec));
    const observer = new ResizeObserver(() => this.resize());
    for (const chart of this.charts.values()) observer.observe(chart.host);
    setInterval(() => this.redraw(), kRedrawPeriod);
  }

  makeChart(container, spec) {
    const values = spec.series.map((series, i) => el("span", { class: "plot-value", style: `--series:${kColours[i]}` }, valueText(series, null)));
    const host = el("div", { class: "plot-canvas" });
    const box = el("div", { class: "plot" }, el("div", { class: "plot-title" }, spec.title), el("div", { class: "plot-values" }, values), host);
    container.append(box);
    const data = [[], ...spec.series.map(() => [])];
    const plot = new uPlot(chartOptions(spec, 240, 110), data, host);
    return { spec, data, plot, host, values, dirty: true };
  }

  /// Appends one sample (time in s since the epoch) to chart `id`.
  add(id, time, samples) {
    const chart = this.charts.get(id);
    chart.data[0].push(time);
    samples.forEach((value, i) => chart.data[i + 1].push(Number.isFinite(value) ? value : null));
    chart.dirty = true;
  }

  /// `/flag/status`, with the page's own frames shown per second.
  addStatus(status, shownFps) {
    const time = Date.now() / 1000;
    this.add("rtf", time, [status.real_time_factor]);
    this.add("step", time, [status.step_time_us]);
    this.add("fps", time, [status.frame_rate_hz, shownFps]);
    this.add("bytes", time, [status.bytes_per_second]);
  }

  /// `/flag/state`: the tip and the kinetic energy, thinned to kMinStateGap.
  addState(state) {
    const time = Date.now() / 1000;
    if (time - this.lastStateTime < kMinStateGap) return;
    this.lastStateTime = time;
    this.add("tip", time, [state.tip?.x, state.tip?.y, state.tip?.z]);
    this.add("energy", time, [state.kinetic_energy]);
  }

  /// Drops points older than the window; redraws the charts that changed.
  redraw() {
    const now = Date.now() / 1000;
    for (const chart of this.charts.values()) {
      const first = chart.data[0].findIndex((time) => time >= now - kWindow);
      const old = first === -1 ? chart.data[0].length : first;
      if (old > 0) {
        chart.data.forEach((column) => column.splice(0, old));
        chart.dirty = true;
      }
      if (chart.dirty) {
        chart.dirty = false;
        chart.plot.setData(chart.data, false);  // the x range is set next, which redraws
        this.showLatest(chart);
      }
      chart.plot.setScale("x", { min: now - kWindow, max: now });
    }
  }

  showLatest(chart) {
    chart.spec.series.forEach((series, i) => {
      const column = chart.data[i + 1];
      chart.values[i].textContent = valueText(series, column.length ? column[column.length - 1] : null);
    });
  }

  /// Fits the charts to their boxes.
  resize() {
    for (const chart of this.charts.values()) {
      const box = chart.host.getBoundingClientRect();
      if (box.width > 0 && box.height > 0) chart.plot.setSize({ width: Math.floor(box.width), height: Math.floor(box.height) });
    }
  }
}

/// "x 1.352", "2.76 kB/s", "0.4019 J": a series' newest value as its header shows it.
function valueText(series, value) {
  const number = value === null ? "–" : series.format ? series.format(value) : formatNumber(value, 4);
  return [series.label, number, series.unit].filter(Boolean).join(" ");
}

/// Tick labels with as many decimals as their spacing needs (0.995, 1, 1.005), not more.
function tickFormatter(ticks) {
  const spacing = ticks.length > 1 ? Math.abs(ticks[1] - ticks[0]) : 1;
  const decimals = Math.min(6, Math.max(0, -Math.floor(Math.log10(spacing || 1))));
  return (value) => (Math.abs(value) >= 1e5 ? formatNumber(value, 3) : value.toFixed(decimals));
}

function chartOptions(spec, width, height) {
  const axisFont = "10px system-ui, sans-serif";
  const grid = { stroke: "rgba(128,128,128,0.15)", width: 1 };
  return {
    width,
    height,
    legend: { show: false },
    cursor: { show: false },
    padding: [6, 6, 0, 0],
    scales: { x: { time: true } },
    axes: [
      { font: axisFont, stroke: "#7a8494", grid, ticks: { show: false }, size: 20, space: 60 },
      { font: axisFont, stroke: "#7a8494", grid, ticks: { show: false }, size: 46, values: (_plot, ticks) => ticks.map(spec.axis ?? tickFormatter(ticks)) },
    ],
    series: [{}, ...spec.series.map((series, i) => ({ label: series.label, stroke: kColours[i], width: 1.5, points: { show: false } }))],
  };
}
