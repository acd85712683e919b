// The trace CSV (emulator/src/trace.rs `HEADER`): written from what the scope shows, read back
// to look at a recorded trace. Columns the stream does not carry are left empty.

export const HEADER = [
  "time_s", "axis", "state", "cmd_pos", "cmd_vel", "cmd_acc", "act_pos", "act_vel",
  "following_error", "pulses", "encoder_counts", "limit_pos", "limit_neg", "home_switch",
  "homed", "error", "group", "path_velocity", "segment", "user_segment", "captures",
  "capture_position", "compare_outputs", "output_pos", "compensation", "gantry_deviation",
  "coupling", "in_sync", "stream_used", "move_time", "settling_time", "position_offset",
  "rollover_turns", "torque", "z_output", "compensation_offset",
];

/** Channels that are trace columns of the same name. */
const VALUE_COLUMNS = ["cmd_pos", "cmd_vel", "cmd_acc", "act_pos", "act_vel", "following_error"];
/** Flag columns and the flag names (`flag_bits` of the stream's hello) they come from. */
const FLAG_COLUMNS = [["limit_pos", "hw_limit_pos"], ["limit_neg", "hw_limit_neg"], ["home_switch", "home_switch"], ["homed", "homed"]];

/**
 * A frame (`{time: [s], series: [{axis, channel, values}], states: Map axis → [state per tick]}`)
 * as trace CSV: one row per tick per axis, in time order.
 */
export function toCsv(frame, flagBits) {
  const axes = [...new Set(frame.series.filter((s) => s.axis != null).map((s) => s.axis))].sort((a, b) => a - b);
  const lines = [HEADER.join(",")];
  for (let i = 0; i < frame.time.length; i++) {
    for (const axis of axes) {
      const row = new Array(HEADER.length).fill("");
      row[0] = String(frame.time[i]);
      row[1] = String(axis);
      const states = frame.states && frame.states.get(axis);
      row[2] = states ? states[i] ?? "" : "";
      for (const s of frame.series) {
        if (s.axis !== axis) continue;
        const v = s.values[i];
        if (v == null) continue;
        const col = HEADER.indexOf(s.channel);
        if (VALUE_COLUMNS.includes(s.channel)) row[col] = String(v);
        if (s.channel === "flags" && flagBits) {
          for (const [column, flag] of FLAG_COLUMNS) {
            const bit = flagBits[flag];
            if (bit != null) row[HEADER.indexOf(column)] = (v & bit) !== 0 ? "1" : "0";
          }
        }
      }
      lines.push(row.join(","));
    }
  }
  return lines.join("\n") + "\n";
}

/**
 * A trace CSV as a frame: the numeric columns of each axis as series against `time_s`. Throws
 * an Error saying what is wrong with a file that is not a trace.
 */
export function parseCsv(text) {
  const lines = text.split(/\r?\n/).filter((l) => l.length > 0);
  if (lines.length === 0) throw new Error("the file is empty");
  const header = lines[0].split(",");
  const t = header.indexOf("time_s");
  const a = header.indexOf("axis");
  if (t < 0 || a < 0) throw new Error("not a trace CSV: no time_s and axis columns");
  const numeric = header
    .map((name, i) => [name, i])
    .filter(([name]) => VALUE_COLUMNS.includes(name) || ["pulses", "encoder_counts", "output_pos", "compensation", "gantry_deviation", "stream_used", "move_time", "settling_time", "position_offset", "rollover_turns", "torque", "z_output", "compensation_offset"].includes(name));
  const times = [];
  const timeIndex = new Map();
  const byAxis = new Map();
  for (let n = 1; n < lines.length; n++) {
    const cols = lines[n].split(",");
    const time = Number(cols[t]);
    const axis = Number(cols[a]);
    if (!Number.isFinite(time) || !Number.isInteger(axis)) throw new Error(`line ${n + 1}: bad time_s or axis`);
    if (!timeIndex.has(time)) {
      timeIndex.set(time, times.length);
      times.push(time);
    }
    if (!byAxis.has(axis)) byAxis.set(axis, []);
    byAxis.get(axis).push([timeIndex.get(time), cols]);
  }
  const series = [];
  for (const [axis, rows] of [...byAxis].sort((x, y) => x[0] - y[0])) {
    for (const [name, i] of numeric) {
      const values = new Array(times.length).fill(null);
      let any = false;
      for (const [ti, cols] of rows) {
        if (cols[i] !== undefined && cols[i] !== "") {
          values[ti] = Number(cols[i]);
          any = true;
        }
      }
      if (any) series.push({ axis, channel: name, values });
    }
  }
  return { time: times, series, states: new Map() };
}
