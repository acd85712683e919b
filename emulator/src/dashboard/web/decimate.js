// What the plot draws: at most two points per pixel column of each series (its minimum and its
// maximum, in the order they occurred), so a 200 000-tick window costs what a 2 600-point one
// does, and a one-tick spike still shows. The data themselves stay whole (cursors, trigger and
// export read them); only the drawing is thinned.
//
// A column is { buf, start, cap, scale }: element i is buf[start + i], wrapping at cap (a ring);
// times are multiplied by scale (ticks → seconds). A plain array is { buf, start: 0, cap: ∞ }.

/** A column over a plain array. */
export function arrayColumn(values, scale = 1) {
  return { buf: values, start: 0, cap: Infinity, scale };
}

function at(col, i) {
  let k = col.start + i;
  if (k >= col.cap) k -= col.cap;
  return col.buf[k];
}

/** Reusable output storage, grown as needed (no garbage per frame). */
export class PlotBuffers {
  constructor() {
    this.arrays = [];
  }
  /** `count` arrays of at least `length` elements. */
  take(count, length) {
    for (let c = 0; c < count; c++) {
      if (!this.arrays[c] || this.arrays[c].length < length) this.arrays[c] = new Float64Array(Math.max(length, 1024));
    }
    return this.arrays.slice(0, count);
  }
}

/**
 * The points to draw of samples [lo, hi) of `time` and `series` (columns), split into
 * `regions`: [{ lo, hi, buckets }] in order, covering [lo, hi); each region gets at most
 * 2 × buckets points per series. Returns uPlot data: [x, ...y] as views of `buffers`.
 */
export function decimate(time, series, regions, buffers) {
  let room = 0;
  for (const r of regions) room += Math.min(r.hi - r.lo, 2 * r.buckets);
  const out = buffers.take(series.length + 1, room);
  const x = out[0];
  let m = 0;
  for (const { lo, hi, buckets } of regions) {
    const n = hi - lo;
    if (n <= 0) continue;
    if (n <= 2 * buckets) {
      for (let i = lo; i < hi; i++, m++) {
        x[m] = at(time, i) * time.scale;
        for (let s = 0; s < series.length; s++) out[s + 1][m] = at(series[s], i);
      }
      continue;
    }
    for (let b = 0; b < buckets; b++) {
      const i0 = lo + Math.floor((b * n) / buckets);
      const i1 = lo + Math.floor(((b + 1) * n) / buckets);
      x[m] = at(time, i0) * time.scale;
      x[m + 1] = at(time, i1 - 1) * time.scale;
      for (let s = 0; s < series.length; s++) {
        const col = series[s];
        let min = Infinity;
        let max = -Infinity;
        let iMin = -1;
        let iMax = -1;
        for (let i = i0; i < i1; i++) {
          const v = at(col, i);
          if (v < min) (min = v), (iMin = i);
          if (v > max) (max = v), (iMax = i);
        }
        const y = out[s + 1];
        if (iMin < 0) {
          // No number in the column (NaN, a gap): a gap it stays.
          y[m] = y[m + 1] = NaN;
        } else if (iMin <= iMax) {
          y[m] = min;
          y[m + 1] = max;
        } else {
          y[m] = max;
          y[m + 1] = min;
        }
      }
      m += 2;
    }
  }
  return out.map((a) => a.subarray(0, m));
}
