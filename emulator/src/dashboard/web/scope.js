// Live plots and the scope. The data are the server's: every servo tick of the chosen channels
// arrives from `GET /api/v1/stream` in batches and goes into ring buffers; the browser's timer
// only decides when to redraw (requestAnimationFrame), never what was sampled.
//
// Drawing is thinned to two points per pixel column (decimate.js); the data are not.
//
// Modes: rolling (the last `window` seconds), paused (frozen), triggered (normal: the latest
// capture, re-armed after each; single: one capture, then stopped until armed again), loaded
// (a trace CSV from disk). Export writes what the plot shows, zoom included, as trace CSV.

import uPlot from "./vendor/uplot/uPlot.esm.js";
import { streamUrl } from "./api.js";
import { parseCsv, toCsv } from "./csv.js";
import { arrayColumn, decimate, PlotBuffers } from "./decimate.js";

/** Ticks kept per channel: 200 s at 1 kHz. */
const CAPACITY = 200000;
const DEFAULT_CHANNELS = ["cmd_pos", "act_pos", "cmd_vel", "following_error"];
const ALL_CHANNELS = ["cmd_pos", "act_pos", "cmd_vel", "act_vel", "cmd_acc", "following_error", "flags"];
const COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];

class Ring {
  constructor(capacity, Type = Float64Array) {
    this.buf = new Type(capacity);
    this.capacity = capacity;
  }
  /** Value of absolute sample `n` (the caller keeps `n` within what is held). */
  at(n) {
    return this.buf[n % this.capacity];
  }
  set(n, v) {
    this.buf[n % this.capacity] = v;
  }
}

export class Scope {
  constructor() {
    this.plotBox = document.getElementById("plot");
    this.status = document.getElementById("stream-status");
    this.triggerStatus = document.getElementById("trigger-status");
    this.readout = document.getElementById("cursor-readout");
    this.paused = false;
    this.loaded = false;
    this.dirty = false;
    this.frame = null; // the frame on the plot while paused, triggered or loaded
    this.view = null; // what the plot shows: { frame } or the rings' samples { from, to }
    this.buffers = new PlotBuffers();
    this.cursors = { a: null, b: null };
    this.hello = null;
    this.setupForms();
    requestAnimationFrame(() => this.draw());
  }

  setupForms() {
    // Channels for every axis (a column of the per-axis grid at once) …
    const choice = document.getElementById("channel-choice");
    for (const c of ALL_CHANNELS) {
      const box = document.createElement("input");
      box.type = "checkbox";
      box.name = "channel";
      box.value = c;
      box.checked = DEFAULT_CHANNELS.includes(c);
      box.onchange = () => {
        for (const cell of document.querySelectorAll(`#channel-grid input[data-channel="${c}"]`)) cell.checked = box.checked;
      };
      const label = document.createElement("label");
      label.append(box, ` ${c}`);
      choice.append(label);
    }
    // … or per axis, in the grid (rows: the axes field's axes).
    this.gridChoice = new Map(); // "axis:channel" → checked, as the user left it
    document.querySelector('#stream-form [name="axes"]').addEventListener("change", () => this.buildGrid());
    document.getElementById("stream-form").addEventListener("submit", (e) => {
      e.preventDefault();
      this.connect();
    });
    document.getElementById("pause").onclick = () => this.setPaused(!this.paused);
    document.getElementById("arm").onclick = () => this.arm();
    document.getElementById("trigger-mode").onchange = () => this.arm();
    document.getElementById("export-csv").onclick = () => this.exportCsv();
    document.getElementById("load-csv").onchange = (e) => this.loadCsv(e.target.files[0]);
    document.querySelector('#scope-form [name="window"]').onchange = () => (this.dirty = true);
  }

  windowTicks() {
    const seconds = Number(document.querySelector('#scope-form [name="window"]').value) || 5;
    const period = this.hello ? this.hello.period : 1e-3;
    return Math.max(2, Math.min(CAPACITY, Math.round(seconds / period)));
  }

  /** The axes field's axes (`0-3,6`), filled with the first eight axes when empty. */
  axisList() {
    const form = document.getElementById("stream-form");
    let axes = form.elements.axes.value.trim();
    if (!axes) {
      const n = Math.min(this.axisCount || 1, 8);
      axes = n > 1 ? `0-${n - 1}` : "0";
      form.elements.axes.value = axes;
    }
    const list = [];
    for (const part of axes.split(",")) {
      const [from, to] = part.split("-").map((s) => Number(s.trim()));
      for (let a = from; Number.isInteger(a) && a <= (Number.isFinite(to) ? to : from); a++) if (!list.includes(a)) list.push(a);
    }
    return list;
  }

  /** The per-axis channel grid for the axes field's axes, keeping what the user chose. */
  buildGrid() {
    const grid = document.getElementById("channel-grid");
    for (const cell of grid.querySelectorAll("input[data-channel]")) this.gridChoice.set(cell.value, cell.checked);
    const all = Object.fromEntries([...document.querySelectorAll('[name="channel"]')].map((b) => [b.value, b.checked]));
    const head = document.createElement("tr");
    head.append(document.createElement("th"), ...ALL_CHANNELS.map((c) => Object.assign(document.createElement("th"), { textContent: c })));
    const rows = this.axisList().map((axis) => {
      const row = document.createElement("tr");
      row.append(Object.assign(document.createElement("th"), { textContent: `axis ${axis}` }));
      for (const c of ALL_CHANNELS) {
        const box = document.createElement("input");
        box.type = "checkbox";
        box.value = `${axis}:${c}`;
        box.dataset.channel = c;
        box.checked = this.gridChoice.get(box.value) ?? all[c];
        const td = document.createElement("td");
        td.append(box);
        row.append(td);
      }
      return row;
    });
    grid.querySelector("table").replaceChildren(head, ...rows);
  }

  /** (Re)open the stream with the grid's channels of each axis. */
  connect(axisCount) {
    if (axisCount != null) this.axisCount = axisCount;
    this.buildGrid();
    const series = [...document.querySelectorAll("#channel-grid input[data-channel]:checked")].map((b) => b.value);
    if (series.length === 0) {
      this.status.textContent = "choose at least one channel of one axis";
      return;
    }
    if (this.source) this.source.close();
    this.status.textContent = "connecting…";
    const source = new EventSource(streamUrl({ series: series.join(",") }));
    this.source = source;
    source.addEventListener("hello", (e) => this.onHello(JSON.parse(e.data)));
    source.addEventListener("samples", (e) => this.onSamples(JSON.parse(e.data)));
    source.onerror = () => {
      this.status.textContent =
        source.readyState === EventSource.CLOSED
          ? "stream refused (too many streams, or a bad axis or channel): press stream to retry"
          : "stream interrupted, reconnecting…";
    };
  }

  onHello(hello) {
    this.hello = hello;
    this.series = [];
    hello.axes.forEach((axis, a) => {
      const channels = hello.axis_channels ? hello.axis_channels[a] : hello.channels;
      for (const channel of channels) this.series.push({ axis, channel, label: `${axis}.${channel}`, ring: new Ring(CAPACITY) });
    });
    if (hello.io) {
      for (const channel of ["di", "do"]) this.series.push({ axis: null, channel, label: channel, ring: new Ring(CAPACITY) });
    }
    this.ticks = new Ring(CAPACITY);
    this.states = new Map(hello.axes.map((a) => [a, new Ring(CAPACITY, Array)]));
    this.current = new Map();
    this.total = 0;
    this.dropped = 0;
    this.scanFrom = 0;
    this.pending = null;
    const source = document.getElementById("trigger-source");
    const keep = source.value;
    source.replaceChildren(...this.series.map((s, i) => new Option(s.label, String(i))));
    const again = this.series.findIndex((s) => s.label === keep);
    source.value = String(again >= 0 ? again : 0);
    const values = hello.axis_channels ? hello.axis_channels.reduce((n, cs) => n + cs.length, 0) : hello.axes.length * hello.channels.length;
    this.status.textContent = `streaming ${values} channels of ${hello.axes.length} axes, ${hello.batch} ticks a batch`;
    if (!this.loaded) this.buildPlot(this.series.map(({ axis, channel, label }) => ({ axis, channel, label })));
    this.dirty = true;
  }

  onSamples(batch) {
    const nAxes = this.hello.axes.length;
    const perAxis = this.hello.axes.map((_, a) => (this.hello.axis_channels ? this.hello.axis_channels[a].length : this.hello.channels.length));
    let change = 0;
    const changes = batch.changes;
    for (let k = 0; k < batch.ticks; k++) {
      const tick = batch.first_tick + k;
      while (change < changes.length && changes[change].tick <= tick) {
        this.current.set(changes[change].axis, changes[change].state);
        change++;
      }
      const n = this.total;
      this.ticks.set(n, tick);
      let s = 0;
      for (let a = 0; a < nAxes; a++) {
        for (let c = 0; c < perAxis[a]; c++) {
          const v = batch.data[a][c][k];
          this.series[s++].ring.set(n, v == null ? NaN : v);
        }
        const axis = this.hello.axes[a];
        this.states.get(axis).set(n, this.current.get(axis) ?? "");
      }
      if (this.hello.io) {
        this.series[s++].ring.set(n, batch.di[k]);
        this.series[s++].ring.set(n, batch.do[k]);
      }
      this.total++;
    }
    if (batch.dropped !== this.dropped) {
      this.dropped = batch.dropped;
    }
    this.status.textContent = `streaming: tick ${batch.first_tick + batch.ticks - 1}, ${this.dropped} batches lost`;
    this.status.dataset.dropped = String(this.dropped);
    this.scanTrigger();
    this.dirty = true;
  }

  /** Oldest absolute sample still held. */
  oldest() {
    return Math.max(0, this.total - CAPACITY);
  }

  /** Samples [from, to) as a frame. */
  frameOf(from, to) {
    from = Math.max(from, this.oldest());
    to = Math.min(to, this.total);
    const period = this.hello.period;
    const time = [];
    for (let n = from; n < to; n++) time.push(this.ticks.at(n) * period);
    const series = this.series.map(({ axis, channel, label, ring }) => {
      const values = new Array(Math.max(0, to - from));
      for (let n = from; n < to; n++) values[n - from] = ring.at(n);
      return { axis, channel, label, values };
    });
    const states = new Map();
    for (const [axis, ring] of this.states) {
      const values = [];
      for (let n = from; n < to; n++) values.push(ring.at(n));
      states.set(axis, values);
    }
    return { time, series, states };
  }

  mode() {
    return document.getElementById("trigger-mode").value;
  }

  arm() {
    this.loaded = false;
    this.armed = this.mode() !== "off";
    this.pending = null;
    this.scanFrom = this.total;
    this.frame = null;
    this.setPaused(false);
    this.triggerStatus.textContent = this.armed ? "armed, waiting for the trigger" : "";
    delete this.triggerStatus.dataset.triggerTime;
    if (this.series) this.buildPlot(this.series.map(({ axis, channel, label }) => ({ axis, channel, label })));
  }

  /** Look for the trigger in samples not yet scanned; complete a pending capture. */
  scanTrigger() {
    if (!this.armed || this.mode() === "off") return;
    const source = this.series[Number(document.getElementById("trigger-source").value)];
    if (!source) return;
    const level = Number(document.getElementById("trigger-level").value);
    const edge = document.getElementById("trigger-edge").value;
    const width = this.windowTicks();
    const pre = Math.round((width * Math.min(100, Math.max(0, Number(document.getElementById("trigger-pre").value) || 0))) / 100);
    if (!this.pending) {
      for (let n = Math.max(this.scanFrom, this.oldest() + 1); n < this.total; n++) {
        const before = source.ring.at(n - 1);
        const now = source.ring.at(n);
        const hit =
          (edge === "rising" && before < level && now >= level) ||
          (edge === "falling" && before > level && now <= level) ||
          (edge === "above" && now >= level && !(before >= level)) ||
          (edge === "below" && now <= level && !(before <= level));
        if (hit) {
          this.pending = { at: n, from: n - pre, to: n - pre + width };
          break;
        }
      }
      this.scanFrom = this.total;
    }
    if (this.pending && this.total >= this.pending.to) {
      const { at, from, to } = this.pending;
      this.frame = this.frameOf(from, to);
      const t = this.ticks.at(at) * this.hello.period;
      this.triggerStatus.textContent = `triggered at ${t} s (tick ${this.ticks.at(at)}) on ${source.label}`;
      this.triggerStatus.dataset.triggerTime = String(t);
      this.cursors.a = t;
      this.pending = null;
      if (this.mode() === "single") {
        this.armed = false;
        this.triggerStatus.textContent += "; single: stopped, arm to capture again";
      } else {
        this.scanFrom = at + 1;
      }
      this.dirty = true;
    }
  }

  setPaused(paused) {
    this.paused = paused;
    document.getElementById("pause").textContent = paused ? "resume" : "pause";
    if (paused && !this.frame && this.hello) this.frame = this.frameOf(this.total - this.windowTicks(), this.total);
    if (!paused && this.mode() === "off") this.frame = null;
    this.dirty = true;
  }

  buildPlot(series) {
    const key = series.map((s) => s.label).join("|");
    if (this.plot && key === this.plotKey) return;
    this.plotKey = key;
    if (this.plot) this.plot.destroy();
    const opts = {
      width: Math.max(400, this.plotBox.clientWidth || 900),
      height: 360,
      scales: { x: { time: false } },
      axes: [{ label: "s" }, {}],
      series: [{ label: "time s" }, ...series.map((s, i) => ({ label: s.label, stroke: COLORS[i % COLORS.length], width: 1, spanGaps: false }))],
      cursor: { drag: { x: true, y: false } },
      hooks: { draw: [(u) => this.drawCursors(u)], setScale: [(u, key) => key === "x" && this.onZoom()] },
    };
    this.plot = new uPlot(opts, [[], ...series.map(() => [])], this.plotBox);
    this.plot.over.addEventListener("click", (e) => {
      const t = this.plot.posToVal(e.offsetX, "x");
      if (e.shiftKey) this.cursors.b = t;
      else this.cursors.a = t;
      this.showReadout();
      this.plot.redraw(false);
    });
  }

  drawCursors(u) {
    const ctx = u.ctx;
    for (const [name, t, color] of [["A", this.cursors.a, "#c00"], ["B", this.cursors.b, "#00c"]]) {
      if (t == null) continue;
      const x = Math.round(u.valToPos(t, "x", true));
      if (x < u.bbox.left || x > u.bbox.left + u.bbox.width) continue;
      ctx.save();
      ctx.strokeStyle = color;
      ctx.setLineDash([4, 4]);
      ctx.beginPath();
      ctx.moveTo(x, u.bbox.top);
      ctx.lineTo(x, u.bbox.top + u.bbox.height);
      ctx.stroke();
      ctx.fillStyle = color;
      ctx.fillText(name, x + 3, u.bbox.top + 12);
      ctx.restore();
    }
  }

  showReadout() {
    const { a, b } = this.cursors;
    const frame = this.plotFrame;
    const value = (t) => {
      if (!frame || t == null || frame.time.length === 0) return "";
      let i = frame.time.findIndex((x) => x >= t);
      if (i < 0) i = frame.time.length - 1;
      return frame.series.slice(0, 4).map((s) => `${s.label}=${s.values[i]}`).join(" ");
    };
    const parts = [];
    if (a != null) parts.push(`A ${a.toFixed(4)} s ${value(a)}`);
    if (b != null) parts.push(`B ${b.toFixed(4)} s ${value(b)}`);
    if (a != null && b != null) parts.push(`Δt ${(b - a).toFixed(4)} s`);
    this.readout.textContent = parts.join(" · ");
  }

  /** What the plot shows, whole (every tick): for cursors, export and the tests. */
  get plotFrame() {
    const v = this.view;
    if (!v) return null;
    return v.frame || this.frameOf(v.from, v.to);
  }

  /** The view's columns for decimate(): its times and each series' values. */
  columns(view) {
    if (view.frame) {
      const f = view.frame;
      return { length: f.time.length, time: arrayColumn(f.time), series: f.series.map((s) => arrayColumn(s.values)) };
    }
    const start = view.from % CAPACITY;
    const ring = (r, scale) => ({ buf: r.buf, start, cap: CAPACITY, scale });
    return { length: view.to - view.from, time: ring(this.ticks, this.hello.period), series: this.series.map((s) => ring(s.ring, 1)) };
  }

  /** Pixel columns of the plotting area. */
  pixels() {
    return Math.max(100, Math.round(this.plot.bbox.width / (window.devicePixelRatio || 1)));
  }

  draw() {
    requestAnimationFrame(() => this.draw());
    this.frames = (this.frames || 0) + 1;
    if (!this.dirty || !this.plot) return;
    if (this.paused && this.view) return;
    let view;
    if (this.frame) view = { frame: this.frame };
    else if (this.hello) view = { from: Math.max(this.oldest(), this.total - this.windowTicks()), to: this.total };
    else return;
    this.dirty = false;
    this.view = view;
    const cols = this.columns(view);
    this.drawnRange = null;
    this.plot.setData(decimate(cols.time, cols.series, [{ lo: 0, hi: cols.length, buckets: this.pixels() }], this.buffers));
    document.getElementById("plot").dataset.points = String(cols.length);
  }

  /**
   * Zoom on a still view (paused, triggered, loaded): the zoomed range drawn at full
   * resolution, the rest thinned harder, so zooming out again (double click) finds it all.
   */
  onZoom() {
    const v = this.view;
    if (!v || !(v.frame || this.paused)) return;
    const { min, max } = this.plot.scales.x;
    if (min == null || (this.drawnRange && this.drawnRange[0] === min && this.drawnRange[1] === max)) return;
    this.drawnRange = [min, max];
    const cols = this.columns(v);
    const t = (i) => cols.time.buf[(cols.time.start + i) % cols.time.cap] * cols.time.scale;
    const first = (x) => {
      let lo = 0;
      let hi = cols.length;
      while (lo < hi) {
        const mid = (lo + hi) >> 1;
        if (t(mid) < x) lo = mid + 1;
        else hi = mid;
      }
      return lo;
    };
    const a = Math.max(0, first(min) - 1);
    const b = Math.min(cols.length, first(max) + 1);
    const px = this.pixels();
    const regions = [
      { lo: 0, hi: a, buckets: px >> 2 },
      { lo: a, hi: b, buckets: px },
      { lo: b, hi: cols.length, buckets: px >> 2 },
    ];
    this.plot.setData(decimate(cols.time, cols.series, regions, this.buffers), false);
    this.plot.redraw();
  }

  /** The shown frame cut to the plot's x range (zoom included). */
  visibleFrame() {
    const frame = this.plotFrame;
    if (!frame) return null;
    const { min, max } = this.plot.scales.x;
    const keep = frame.time.map((t) => min == null || (t >= min && t <= max));
    const pick = (values) => values.filter((_, i) => keep[i]);
    const states = new Map();
    for (const [axis, values] of frame.states || []) states.set(axis, pick(values));
    return { time: pick(frame.time), series: frame.series.map((s) => ({ ...s, values: pick(s.values) })), states };
  }

  exportCsv() {
    const frame = this.visibleFrame();
    if (!frame) return;
    const csv = toCsv(frame, this.hello && this.hello.flag_bits);
    const link = document.createElement("a");
    link.href = URL.createObjectURL(new Blob([csv], { type: "text/csv" }));
    link.download = "mcemu-scope.csv";
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 10000);
  }

  async loadCsv(file) {
    if (!file) return;
    try {
      const frame = parseCsv(await file.text());
      for (const s of frame.series) s.label = `${s.axis}.${s.channel}`;
      this.loaded = true;
      this.armed = false;
      this.buildPlot(frame.series);
      this.frame = frame;
      this.view = null;
      this.paused = false;
      this.dirty = true;
      this.triggerStatus.textContent = `loaded ${file.name}: ${frame.time.length} ticks, ${frame.series.length} series (arm or stream to go live)`;
      this.triggerStatus.dataset.loaded = String(frame.time.length);
    } catch (e) {
      this.triggerStatus.textContent = `cannot load ${file.name}: ${e.message}`;
    }
  }
}
