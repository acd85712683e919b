// Unit test of the dashboard's thinning (emulator/src/dashboard/web/decimate.js), run by
// tests/tests/dashboard.rs with `node --test`.
import { test } from "node:test";
import assert from "node:assert/strict";
import { arrayColumn, decimate, PlotBuffers } from "../../emulator/src/dashboard/web/decimate.js";

const ticks = (n) => Array.from({ length: n }, (_, i) => i);

test("a one-tick spike survives 100 ticks per pixel column, in the order it came", () => {
  const v = ticks(10000).map((i) => (i === 5001 ? 100 : i === 5003 ? -100 : 0));
  const [x, y] = decimate(arrayColumn(ticks(10000), 1e-3), [arrayColumn(v)], [{ lo: 0, hi: 10000, buckets: 100 }], new PlotBuffers());
  assert.equal(x.length, 200);
  const at = y.indexOf(100);
  assert.ok(at >= 0 && y[at + 1] === -100, `max then min in column ${at >> 1}`);
  assert.equal(x[0], 0);
  assert.equal(x[199], 9.999);
  for (let i = 1; i < x.length; i++) assert.ok(x[i] >= x[i - 1], "times never go back");
});

test("few enough points are drawn as they are", () => {
  const v = ticks(150).map((i) => Math.sin(i));
  const [x, y] = decimate(arrayColumn(ticks(150), 1), [arrayColumn(v)], [{ lo: 0, hi: 150, buckets: 100 }], new PlotBuffers());
  assert.deepEqual(Array.from(x), ticks(150));
  assert.deepEqual(Array.from(y), v);
});

test("a ring's wrap is read in order, and a column of gaps stays a gap", () => {
  // Ring of 8 holding absolute samples 5..12 (start at 5 % 8).
  const buf = new Float64Array(8);
  const times = new Float64Array(8);
  for (let n = 5; n < 13; n++) {
    buf[n % 8] = n >= 9 ? NaN : n;
    times[n % 8] = n;
  }
  const ring = (b, scale) => ({ buf: b, start: 5, cap: 8, scale });
  const [x, y] = decimate(ring(times, 1), [ring(buf, 1)], [{ lo: 0, hi: 8, buckets: 2 }], new PlotBuffers());
  assert.deepEqual(Array.from(x), [5, 8, 9, 12]);
  assert.deepEqual(Array.from(y.subarray(0, 2)), [5, 8]);
  assert.ok(Number.isNaN(y[2]) && Number.isNaN(y[3]));
});

test("regions: the zoomed range whole, the rest thinner", () => {
  const n = 10000;
  const v = ticks(n);
  const regions = [{ lo: 0, hi: 4000, buckets: 25 }, { lo: 4000, hi: 4100, buckets: 100 }, { lo: 4100, hi: n, buckets: 25 }];
  const [x] = decimate(arrayColumn(ticks(n), 1), [arrayColumn(v)], regions, new PlotBuffers());
  assert.equal(x.length, 50 + 100 + 50);
  assert.deepEqual(Array.from(x.subarray(50, 150)), ticks(100).map((i) => 4000 + i));
});
