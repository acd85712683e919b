// Load generator of emulator/benches/dashboard_stream.rs: PAGES dashboard pages in one headless
// chromium, each streaming the page's default channels, for SECONDS. Prints `measuring` once
// every page streams, then one JSON line: per page the requestAnimationFrame rate over the
// window, the live JS heap (after a collection) at its start and its end, and the batches the
// server reported lost.
//
//   node bench.mjs BASE_URL PAGES SECONDS

import { chromium } from "playwright-core";

const [base, pages, seconds] = [process.argv[2], Number(process.argv[3]), Number(process.argv[4])];
const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--enable-precise-memory-info", "--js-flags=--expose-gc"],
  headless: true,
});
try {
  const open = [];
  for (let i = 0; i < pages; i++) {
    const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
    await page.goto(`${base}/`);
    await page.waitForFunction(() => /streaming: tick/.test(document.getElementById("stream-status").textContent), null, { timeout: 60000 });
    open.push(page);
  }
  // Live heap: collect first, so garbage not yet collected does not read as growth.
  const heapOf = () =>
    Promise.all(
      open.map((p) =>
        p.evaluate(() => {
          if (window.gc) window.gc();
          return performance.memory ? performance.memory.usedJSHeapSize : 0;
        }),
      ),
    );
  const heapStart = await heapOf();
  const start = await Promise.all(open.map((p) => p.evaluate(() => window.mcemuScope.frames)));
  console.log("measuring");
  await new Promise((r) => setTimeout(r, seconds * 1000));
  const end = await Promise.all(open.map((p) => p.evaluate(() => window.mcemuScope.frames)));
  const heap = await heapOf();
  const lost = await Promise.all(open.map((p) => p.evaluate(() => Number(document.getElementById("stream-status").dataset.dropped || 0))));
  const fps = end.map((e, i) => (e - start[i]) / seconds);
  console.log(JSON.stringify({ fps, heap_start: heapStart, heap, lost }));
} finally {
  await browser.close();
}
