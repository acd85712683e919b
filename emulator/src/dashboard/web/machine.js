// The machine view: axes (one compact row each, a click opens its controls), I/O, groups,
// couplings, drives, front-ends and the runtime, from `GET /api/v1/state`. Rows are built
// once per axis and then only their text changes, so 64 axes stay cheap to refresh.

import { control } from "./api.js";

const AXIS_FIELDS = [
  "state", "flags", "cmd_pos", "act_pos", "cmd_vel", "following_error",
  "pulses", "encoder_counts", "fifo_len", "current_command",
];
const INPUTS = ["limit_pos", "limit_neg", "home", "index"];
/** Flags shown as warnings. */
const ALARM_FLAGS = /limit|error|alarm|loss|fault/;

function num(v) {
  if (typeof v !== "number") return v == null ? "" : String(v);
  if (Number.isInteger(v)) return String(v);
  return Math.abs(v) >= 1e6 || (v !== 0 && Math.abs(v) < 1e-4) ? v.toExponential(4) : v.toFixed(4);
}

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") e.className = v;
    else if (k.startsWith("data-") || k === "type" || k === "name" || k === "value" || k === "step" || k === "size" || k === "placeholder" || k === "title") e.setAttribute(k, v);
    else e[k] = v;
  }
  for (const c of children) e.append(c);
  return e;
}

function commandText(c) {
  if (!c) return "";
  return c.kind ? `${c.kind}${c.id != null ? ` #${c.id}` : ""}` : JSON.stringify(c);
}

/** The controls of one axis, sending the control API's own requests. */
function axisControls(axis, refresh) {
  const box = el("div", { class: "controls", "data-controls": String(axis) });
  const send = (where, path, body) => control(where, "POST", path, body, refresh);
  const group = (label, ...items) => el("div", { class: "control-group" }, el("span", { class: "label" }, label), ...items, el("span", { class: "error", "data-error": "" }));

  const motion = group("motion");
  for (const action of ["enable", "disable", "reset", "stop"]) {
    const b = el("button", { type: "button", "data-action": action }, action);
    b.onclick = () => send(motion, "/commands", { type: action, axis });
    motion.append(b);
  }
  motion.append(motion.querySelector("[data-error]"));

  const moveTo = group("move to");
  const position = el("input", { type: "number", step: "any", size: "8", value: "10", "data-input": "position" });
  const velocity = el("input", { type: "number", step: "any", size: "6", placeholder: "velocity", "data-input": "velocity" });
  const go = el("button", { type: "button", "data-action": "move_absolute" }, "move");
  go.onclick = () => {
    const body = { type: "move_absolute", axis, position: Number(position.value) };
    if (velocity.value !== "") body.velocity = Number(velocity.value);
    send(moveTo, "/commands", body);
  };
  moveTo.insertBefore(go, moveTo.querySelector("[data-error]"));
  moveTo.insertBefore(velocity, go);
  moveTo.insertBefore(position, velocity);

  const jog = group("jog");
  const speed = el("input", { type: "number", step: "any", size: "6", value: "10", "data-input": "jog_velocity" });
  const minus = el("button", { type: "button", "data-action": "jog_neg" }, "jog −");
  const plus = el("button", { type: "button", "data-action": "jog_pos" }, "jog +");
  minus.onclick = () => send(jog, "/commands", { type: "move_velocity", axis, velocity: -Math.abs(Number(speed.value)) });
  plus.onclick = () => send(jog, "/commands", { type: "move_velocity", axis, velocity: Math.abs(Number(speed.value)) });
  for (const e of [speed, minus, plus]) jog.insertBefore(e, jog.querySelector("[data-error]"));

  const inputs = group("force inputs");
  for (const input of INPUTS) {
    const select = el("select", { "data-force": input, title: input });
    for (const [label, value] of [[`${input}: sim`, "sim"], [`${input}: on`, "on"], [`${input}: off`, "off"]]) {
      select.append(el("option", { value }, label));
    }
    select.onchange = () => {
      const value = select.value === "sim" ? null : select.value === "on";
      send(inputs, "/inputs", { axis, input, value });
    };
    inputs.insertBefore(select, inputs.querySelector("[data-error]"));
  }

  const faults = group("faults");
  for (const fault of ["drive_alarm", "encoder_loss"]) {
    const inject = el("button", { type: "button", "data-fault": fault }, fault);
    inject.onclick = () => send(faults, "/faults", { axis, fault, active: true });
    const clear = el("button", { type: "button", "data-fault-clear": fault }, "clear");
    clear.onclick = () => send(faults, "/faults", { axis, fault, active: false });
    faults.insertBefore(inject, faults.querySelector("[data-error]"));
    faults.insertBefore(clear, faults.querySelector("[data-error]"));
  }
  const amount = el("input", { type: "number", step: "any", size: "6", value: "1", "data-input": "fe_amount" });
  const fe = el("button", { type: "button", "data-fault": "following_error" }, "following error");
  fe.onclick = () => send(faults, "/faults", { axis, fault: "following_error", amount: Number(amount.value) });
  const feClear = el("button", { type: "button", "data-fault-clear": "following_error" }, "clear");
  feClear.onclick = () => send(faults, "/faults", { axis, fault: "following_error", active: false });
  for (const e of [amount, fe, feClear]) faults.insertBefore(e, faults.querySelector("[data-error]"));

  box.append(motion, moveTo, jog, inputs, faults);
  return box;
}

/** A table of objects' scalar fields (nested values as compact JSON). */
function table(title, rows) {
  if (!rows || rows.length === 0) return el("p", { class: "muted" }, `${title}: none`);
  const keys = Object.keys(rows[0]);
  const t = el("table", { class: "generic" });
  t.append(el("caption", {}, title));
  t.append(el("tr", {}, ...keys.map((k) => el("th", {}, k))));
  for (const r of rows) {
    t.append(el("tr", {}, ...keys.map((k) => el("td", {}, typeof r[k] === "object" && r[k] !== null ? JSON.stringify(r[k]) : num(r[k])))));
  }
  return t;
}

export class MachineView {
  constructor(refresh) {
    this.refresh = refresh;
    this.rows = [];
    this.body = document.querySelector("#axes tbody");
    this.ioBuilt = false;
  }

  render(state) {
    document.getElementById("machine-name").textContent = `${state.machine} · ${state.clock} clock`;
    this.renderRuntime(state);
    this.renderAxes(state.axes);
    this.renderIo(state.io);
    this.renderStructure(state);
    this.renderFrontends(state.frontends, state.listeners || []);
  }

  renderRuntime(state) {
    const r = state.runtime;
    const l = r.lateness || {};
    const items = [
      ["tick", state.tick], ["time", `${num(state.time)} s`], ["period", `${num(state.period * 1e3)} ms`],
      ["lateness p50/p99/max", `${num(l.p50 * 1e6)}/${num(l.p99 * 1e6)}/${num(l.max * 1e6)} µs`],
      ["overruns", r.overruns], ["max tick", `${num(r.max_tick_time * 1e6)} µs`],
      ["streams", `${state.stream.clients}/${state.stream.max_clients}, lost ${state.stream.dropped_batches}`],
      ["trace", state.trace.state],
    ];
    const dl = document.getElementById("runtime");
    dl.replaceChildren(...items.flatMap(([k, v]) => [el("dt", {}, k), el("dd", { "data-runtime": k }, String(v))]));
  }

  renderAxes(axes) {
    document.getElementById("axis-count").textContent = `(${axes.length})`;
    while (this.rows.length < axes.length) this.addRow(this.rows.length);
    while (this.rows.length > axes.length) {
      const r = this.rows.pop();
      r.row.remove();
      r.detail.remove();
    }
    axes.forEach((a, i) => {
      const cells = this.rows[i].cells;
      cells.name.textContent = a.name ? `${a.axis} ${a.name}` : String(a.axis);
      for (const f of AXIS_FIELDS) {
        const cell = cells[f];
        if (f === "flags") {
          const text = a.flags.join(" ");
          if (cell.textContent !== text) {
            cell.replaceChildren(...a.flags.map((n) => el("span", { class: ALARM_FLAGS.test(n) ? "flag alarm" : "flag", "data-flag": n }, n)));
            cell.dataset.value = text;
          }
        } else if (f === "current_command") {
          cell.textContent = commandText(a.current_command);
        } else {
          cell.textContent = num(a[f]);
          if (typeof a[f] === "number") cell.dataset.value = String(a[f]);
        }
      }
      this.rows[i].row.dataset.state = a.state;
    });
  }

  addRow(axis) {
    const cells = { name: el("td", { class: "axis-name" }) };
    for (const f of AXIS_FIELDS) cells[f] = el("td", { "data-field": f });
    const row = el("tr", { class: "axis-row", "data-axis": String(axis), title: "click for controls" }, cells.name, ...AXIS_FIELDS.map((f) => cells[f]));
    const detail = el("tr", { class: "axis-detail", "data-axis-detail": String(axis), hidden: true });
    const td = el("td", { colSpan: AXIS_FIELDS.length + 1 });
    detail.append(td);
    row.onclick = () => {
      if (!td.firstChild) td.append(axisControls(axis, this.refresh));
      detail.hidden = !detail.hidden;
    };
    this.body.append(row, detail);
    this.rows.push({ row, detail, cells });
  }

  renderIo(io) {
    const box = document.getElementById("io");
    if (!this.ioBuilt) {
      this.ioBuilt = true;
      const di = el("div", { class: "control-group", "data-control": "di" }, el("span", { class: "label" }, "DI"));
      io.di.forEach((_, n) => {
        const s = el("select", { "data-di": String(n), title: `DI ${n}` });
        for (const [label, value] of [[`${n}`, "sim"], [`${n}: on`, "on"], [`${n}: off`, "off"]]) s.append(el("option", { value }, label));
        s.onchange = () => control(di, "POST", "/inputs", { di: n, value: s.value === "sim" ? null : s.value === "on" }, this.refresh);
        di.append(s);
      });
      di.append(el("span", { class: "error", "data-error": "" }));
      const ai = el("div", { class: "control-group", "data-control": "ai" }, el("span", { class: "label" }, "AI"));
      const channel = el("input", { type: "number", size: "3", value: "0", "data-input": "ai_channel" });
      const value = el("input", { type: "number", step: "any", size: "6", value: "0", "data-input": "ai_value" });
      const force = el("button", { type: "button", "data-action": "force_ai" }, "force");
      force.onclick = () => control(ai, "POST", "/inputs", { ai: Number(channel.value), value: Number(value.value) }, this.refresh);
      const release = el("button", { type: "button", "data-action": "release_ai" }, "release");
      release.onclick = () => control(ai, "POST", "/inputs", { ai: Number(channel.value), value: null }, this.refresh);
      ai.append(channel, value, force, release, el("span", { class: "error", "data-error": "" }));
      this.ioValues = el("div", { class: "io-values" });
      box.append(di, ai, this.ioValues);
    }
    const bits = (v) => v.map((b) => (b ? "1" : "0")).join("");
    this.ioValues.replaceChildren(
      el("div", { "data-io": "di" }, `DI ${bits(io.di)}`),
      el("div", { "data-io": "do" }, `DO ${bits(io.do)}`),
      el("div", { "data-io": "ai" }, `AI ${io.ai.map(num).join(" ")}`),
      el("div", { "data-io": "ao" }, `AO ${io.ao.map(num).join(" ")}`),
    );
  }

  renderStructure(state) {
    const parts = [
      ["groups", "groups"], ["couplings", "couplings"], ["handwheels", "handwheels"], ["captures", "capture channels"],
      ["compares", "compare channels"], ["samplers", "samplers"], ["drives", "drives (CiA 402)"],
    ];
    const key = JSON.stringify(parts.map(([k]) => state[k]));
    if (key === this.structureKey) return;
    this.structureKey = key;
    for (const [k, title] of parts) document.getElementById(k).replaceChildren(table(title, state[k]));
  }

  renderFrontends(frontends, listeners) {
    const key = JSON.stringify(listeners);
    if (key !== this.listenersKey) {
      this.listenersKey = key;
      document.getElementById("listeners").replaceChildren(table("listening", listeners));
    }
    const box = document.getElementById("frontends");
    if (!this.frontendBoxes || this.frontendBoxes.length !== frontends.length) {
      this.frontendBoxes = frontends.map((f) => {
        const status = el("pre", { class: "frontend-status" });
        const body = el("input", { size: "40", value: '{"fault":"delay","ms":100}', "data-input": "frontend_fault" });
        const where = el("div", { class: "control-group" });
        const inject = el("button", { type: "button", "data-action": "frontend_fault" }, "inject");
        inject.onclick = () => {
          let fault;
          try {
            fault = JSON.parse(body.value);
          } catch (e) {
            where.querySelector("[data-error]").textContent = `not JSON: ${e.message}`;
            return;
          }
          control(where, "POST", "/faults", { ...fault, frontend: f.name }, this.refresh);
        };
        const clear = el("button", { type: "button", "data-action": "frontend_clear" }, "clear faults");
        clear.onclick = () => control(where, "POST", "/faults", { frontend: f.name, fault: "clear" }, this.refresh);
        where.append(el("span", { class: "label" }, "fault"), body, inject, clear, el("span", { class: "error", "data-error": "" }));
        const section = el("details", { class: "frontend", "data-frontend": f.name, open: true }, el("summary", {}, f.name), status, where);
        return { section, status };
      });
      box.replaceChildren(...this.frontendBoxes.map((b) => b.section));
    }
    frontends.forEach((f, i) => {
      const c = f.counters || {};
      const conn = c.connections || {};
      // A front-end's listeners are those its `listening:` lines named after its section.
      const own = listeners.filter((l) => l.protocol === f.name.replaceAll("_", "-")).map((l) => l.address);
      const lines = [
        `listening: ${own.length ? own.join(", ") : "-"}`,
        Object.entries(f).filter(([, v]) => v === null || typeof v !== "object").map(([k, v]) => `${k}: ${v}`).join(", "),
        `connections: open ${conn.open ?? "-"}, opened ${conn.opened ?? "-"}, refused ${conn.refused_at_limit ?? "-"}`,
        `requests ${c.requests ?? "-"}, replies ${c.replies ?? "-"}, exceptions ${c.exceptions ?? "-"}, bytes in/out ${c.bytes_in ?? "-"}/${c.bytes_out ?? "-"}`,
        `active faults: ${JSON.stringify(f.active_faults ?? [])}`,
        `last error: ${f.last_error ?? "none"}`,
      ];
      this.frontendBoxes[i].status.textContent = lines.join("\n");
    });
  }
}
