// The dashboard in a real browser: Debian's chromium, headless, driven by playwright-core.
// Run by tests/tests/dashboard.rs against a `mcemu run` it started (virtual clock):
//
//   node dashboard.mjs SCENARIO BASE_URL [ARG]
//
// SCENARIO: `machine` (the default machine: view, controls, limit, scope, CSV; ARG: the
// screenshot path), `axes64` (ARG: the axis count expected), `token` (a non-loopback bind; ARG:
// the token). Prints one `ok: …` line per check passed; exits 1 with the failing check.

import { chromium } from "playwright-core";
import { readFile } from "node:fs/promises";

const [scenario, base, arg] = process.argv.slice(2);
const TIMEOUT = 30000;

function check(ok, what) {
  if (!ok) throw new Error(`check failed: ${what}`);
  console.log(`ok: ${what}`);
}

async function api(path, init = {}, token) {
  const headers = { ...(init.headers || {}) };
  if (token) headers.Authorization = `Bearer ${token}`;
  if (init.body !== undefined) headers["Content-Type"] = "application/json";
  const reply = await fetch(`${base}/api/v1${path}`, { ...init, headers, body: init.body === undefined ? undefined : JSON.stringify(init.body) });
  return { status: reply.status, body: await reply.json().catch(() => null) };
}

const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu"],
  headless: true,
});
const errors = [];
try {
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1400, height: 1000 } });
  const page = await context.newPage();
  page.setDefaultTimeout(TIMEOUT);
  page.on("console", (m) => {
    if (m.type() === "error") errors.push(m.text());
  });
  page.on("pageerror", (e) => errors.push(String(e)));

  if (scenario === "machine") await machine(page, context);
  else if (scenario === "axes64") await axes64(page);
  else if (scenario === "token") await token(page);
  else throw new Error(`unknown scenario ${scenario}`);

  // The browser logs each refused request; the refusals the checks provoke are expected.
  const expected = scenario === "token" ? /status of 401/ : /status of 422/;
  const unexpected = errors.filter((e) => !expected.test(e));
  check(unexpected.length === 0, `no console errors (${unexpected.join(" | ")})`);
} catch (e) {
  console.error(String(e && e.stack ? e.stack : e));
  if (errors.length) console.error(`console errors: ${errors.join(" | ")}`);
  await browser.close();
  process.exit(1);
}
await browser.close();

/** The value the page shows in an axis cell. */
async function cell(page, axis, field) {
  return page.locator(`tr[data-axis="${axis}"] td[data-field="${field}"]`).getAttribute("data-value");
}

async function advance(page, seconds) {
  const form = page.locator("#advance");
  await form.locator('[name="unit"]').selectOption("seconds");
  await form.locator('[name="amount"]').fill(String(seconds));
  await form.locator('[data-action="advance"]').click();
  await page.waitForFunction(() => document.querySelector("#advance [data-error]").textContent === "");
}

async function openAxis(page, axis) {
  const controls = page.locator(`[data-controls="${axis}"]`);
  if (!(await controls.isVisible())) await page.locator(`tr[data-axis="${axis}"]`).click();
  await controls.waitFor();
  return controls;
}

/** Click a control and wait for its outcome beside it; returns the error shown ("" if none). */
async function click(group, selector) {
  const button = group.locator(selector);
  await button.click();
  const error = button.locator('xpath=ancestor::div[contains(@class,"control-group")][1]//*[@data-error]');
  await error.page().waitForFunction((e) => e.textContent !== "…", await error.elementHandle());
  return error.textContent();
}

async function machine(page, context) {
  await page.goto(`${base}/`);
  await page.waitForFunction(() => document.querySelectorAll("tr.axis-row").length === 4);
  check(true, "the page shows the default machine's four axes");
  await page.waitForFunction(() => /streaming/.test(document.getElementById("stream-status").textContent));
  check(errors.length === 0, `the page loads with no console errors (${errors.join(" | ")})`);
  const names = await page.locator("tr.axis-row td.axis-name").allTextContents();
  check(names.join(",") === "0 x,1 y,2 z,3 a" || names.length === 4, `axis names ${names}`);

  // The front-ends view says where each listens, as the `listening:` lines did.
  const listeners = (await api("/state")).body.listeners;
  const control = new URL(base).host;
  await page.waitForFunction((c) => document.getElementById("listeners").textContent.includes(c), control);
  for (const l of listeners.filter((l) => l.protocol !== "control")) {
    const section = page.locator(`[data-frontend="${l.protocol.replaceAll("-", "_")}"] .frontend-status`);
    const text = await section.textContent();
    check(text.includes(`listening: ${l.address}`), `the ${l.protocol} front-end shows it listens on ${l.address}`);
  }
  check(listeners.length >= 2, `the listeners table lists ${listeners.length} listeners, the control port ${control} among them`);

  // Enable and move axis 0 from the page; time advances from the page too.
  const axis0 = await openAxis(page, 0);
  check((await click(axis0, '[data-action="enable"]')) === "", "enable axis 0 from the page");
  await axis0.locator('[data-input="position"]').fill("10");
  check((await click(axis0, '[data-action="move_absolute"]')) === "", "move axis 0 to 10 from the page");
  await advance(page, 1);
  const state = await api("/state");
  check(state.body.axes[0].act_pos === 10 && state.body.axes[0].cmd_pos === 10, `the engine moved axis 0 to 10 (${state.body.axes[0].act_pos})`);
  await page.waitForFunction(() => document.querySelector('tr[data-axis="0"] td[data-field="act_pos"]').dataset.value === "10");
  check(true, "the page shows axis 0 at 10");
  await page.waitForFunction(() => {
    const f = window.mcemuScope.plotFrame;
    const s = f && f.series.find((x) => x.label === "0.cmd_pos");
    return s && s.values.length > 0 && s.values[s.values.length - 1] === 10;
  });
  check(true, "the plot follows axis 0 to 10");

  // A window longer than the plot is wide: drawn as a minimum and a maximum per pixel column,
  // the data whole (a burst of more than 3.2 s would lose batches: 2 s at a time).
  for (let i = 0; i < 3; i++) {
    const before = await page.evaluate(() => window.mcemuScope.total);
    await advance(page, 2);
    await page.waitForFunction((n) => window.mcemuScope.total >= n + 2000, before);
  }
  await page.waitForFunction(() => Number(document.getElementById("plot").dataset.points) >= 4000);
  const thinned = await page.evaluate(() => {
    const s = window.mcemuScope;
    const whole = s.plotFrame;
    const i = whole.series.findIndex((x) => x.label === "0.cmd_pos");
    const max = (a) => a.reduce((m, v) => (v > m ? v : m), -Infinity);
    const min = (a) => a.reduce((m, v) => (v < m ? v : m), Infinity);
    return {
      drawn: s.plot.data[0].length, ticks: whole.time.length, pixels: s.pixels(),
      same: max(s.plot.data[i + 1]) === max(whole.series[i].values) && min(s.plot.data[i + 1]) === min(whole.series[i].values),
      first: s.plot.data[0][0] === whole.time[0], last: s.plot.data[0][s.plot.data[0].length - 1] === whole.time[whole.time.length - 1],
    };
  });
  check(thinned.drawn <= 2 * thinned.pixels && thinned.drawn < thinned.ticks,
    `${thinned.ticks} ticks drawn as ${thinned.drawn} points on ${thinned.pixels} pixel columns`);
  check(thinned.same && thinned.first && thinned.last, "the thinned plot keeps the extremes and both ends of the window");

  // A typed error is shown where the user clicked.
  const axis1 = await openAxis(page, 1);
  await axis1.locator('[data-input="position"]').fill("5");
  const refused = await click(axis1, '[data-action="move_absolute"]');
  check(refused.startsWith("axis_disabled"), `a refused move shows its typed error (${refused})`);

  // Forcing the positive limit from the page stops a move and shows the flag.
  await axis0.locator('[data-input="position"]').fill("400");
  check((await click(axis0, '[data-action="move_absolute"]')) === "", "move axis 0 towards 400");
  await advance(page, 0.5);
  await axis0.locator('[data-force="limit_pos"]').selectOption("on");
  await page.waitForFunction(() => document.querySelector('[data-controls="0"] [data-force="limit_pos"]').closest(".control-group").querySelector("[data-error]").textContent === "");
  await advance(page, 0.5);
  const stopped = (await api("/state")).body.axes[0];
  check(stopped.flags.includes("hw_limit_pos"), `the engine sees the forced limit (${stopped.flags})`);
  check(stopped.act_pos < 400 && !stopped.flags.includes("moving"), `the move stopped at ${stopped.act_pos}, state ${stopped.state}`);
  await page.waitForSelector('tr[data-axis="0"] [data-flag="hw_limit_pos"]');
  check(true, "the page shows the hw_limit_pos flag");
  await axis0.locator('[data-force="limit_pos"]').selectOption("sim");

  // The scope: single trigger on axis 1's commanded position rising through 5.
  check((await click(axis1, '[data-action="enable"]')) === "", "enable axis 1");
  await page.locator('#scope-form [name="window"]').fill("0.5");
  await page.locator("#trigger-source").selectOption({ label: "1.cmd_pos" });
  await page.locator("#trigger-edge").selectOption("rising");
  await page.locator("#trigger-level").fill("5");
  await page.locator("#trigger-pre").fill("20");
  await page.locator("#trigger-mode").selectOption("single");
  await page.locator("#arm").click();
  await axis1.locator('[data-input="position"]').fill("20");
  check((await click(axis1, '[data-action="move_absolute"]')) === "", "move axis 1 to 20");
  await advance(page, 1);
  const triggerTime = Number(await page.waitForFunction(() => document.getElementById("trigger-status").dataset.triggerTime).then((h) => h.jsonValue()));
  check(triggerTime > 0, `the scope triggered at ${triggerTime} s`);

  const download = page.waitForEvent("download");
  await page.locator("#export-csv").click();
  const file = await (await download).path();
  const csv = await readFile(file, "utf8");
  const lines = csv.trim().split("\n");
  const header = lines[0].split(",");
  // The columns of emulator/src/trace.rs's HEADER, what GET /api/v1/trace writes.
  const traceRs = await readFile(new URL("../../emulator/src/trace.rs", import.meta.url), "utf8");
  const traceHeader = /pub const HEADER: &str = "([^"]*)";/.exec(traceRs)?.[1];
  check(traceHeader && lines[0] === traceHeader, "the export has the trace CSV header");
  const [t, ax, pos] = ["time_s", "axis", "cmd_pos"].map((c) => header.indexOf(c));
  const axis1Rows = lines.slice(1).map((l) => l.split(",")).filter((r) => r[ax] === "1");
  const at = axis1Rows.findIndex((r) => Number(r[t]) === triggerTime);
  check(at > 0, `the exported CSV contains the trigger point t=${triggerTime}`);
  check(Number(axis1Rows[at][pos]) >= 5 && Number(axis1Rows[at - 1][pos]) < 5, `cmd_pos crosses 5 there (${axis1Rows[at - 1][pos]} → ${axis1Rows[at][pos]})`);
  const preRows = at;
  check(Math.abs(preRows - 100) <= 1, `20 % pre-trigger of a 0.5 s window: ${preRows} ticks before it`);

  // The screenshot for the README: the machine after all this, and the captured trigger.
  await page.screenshot({ path: arg, fullPage: true });
  check(true, `screenshot ${arg}`);

  // Load it back in.
  await page.locator("#load-csv").setInputFiles(file);
  await page.waitForFunction(() => Number(document.getElementById("trigger-status").dataset.loaded) > 0);
  await page.waitForFunction(() => window.mcemuScope.plotFrame && window.mcemuScope.plotFrame === window.mcemuScope.frame && window.mcemuScope.plotFrame.time.length > 0);
  const drawn = await page.evaluate(() => window.mcemuScope.plot.data[0].length);
  check(drawn === axis1Rows.length, `the loaded CSV is drawn (${drawn} points)`);

  // A cross-origin form post (a page elsewhere in the user's browser) is refused.
  const evil = await context.newPage();
  await evil.setContent(`<form method="post" enctype="text/plain" action="${base}/api/v1/commands">
    <input name='{"type":"enable","axis":2,"x":"' value='"}'></form>`);
  const answer = evil.waitForResponse((r) => r.url().endsWith("/api/v1/commands"));
  await evil.evaluate(() => document.forms[0].submit());
  const status = (await answer).status();
  check(status === 403, `a cross-origin form post is refused (${status})`);
  check((await api("/state")).body.axes[2].state === "disabled", "and axis 2 stayed disabled");
  await evil.close();

  // Couplings and handwheels show as they are made: axis 3 geared to axis 2, the first
  // external encoder driving axis 2.
  const coupled = await api("/commands", { method: "POST", body: [
    { type: "enable", axis: 2 }, { type: "enable", axis: 3 },
    { type: "gear_in", master: 2, slave: 3, numerator: 1, denominator: 2 },
    { type: "handwheel_in", axis: 2, input: 256, numerator: 1, denominator: 1, velocity: 10, acceleration: 100 },
  ] });
  check(coupled.status === 200, `gear and handwheel made (${JSON.stringify(coupled.body)})`);
  await page.waitForFunction(() => /gear/.test(document.getElementById("couplings").textContent) && /256/.test(document.getElementById("handwheels").textContent));
  check(true, "the couplings and handwheels tables show them");

  // Channels chosen per axis: axis 0's act_pos and axis 1's following_error only.
  await page.locator("#channel-grid summary").click();
  await page.locator('#stream-form [name="axes"]').fill("0-1");
  await page.locator('#stream-form [name="axes"]').dispatchEvent("change");
  for (const box of await page.locator('#channel-choice [name="channel"]').all()) await box.uncheck();
  await page.locator('#channel-grid input[value="0:act_pos"]').check();
  await page.locator('#channel-grid input[value="1:following_error"]').check();
  // Mark the current stream's hello in the page, then wait for the next stream's.
  await page.evaluate(() => (window.mcemuScope.hello.seenByTest = true));
  await page.locator('#stream-form button[type="submit"]').click();
  await page.waitForFunction(() => window.mcemuScope.hello && !window.mcemuScope.hello.seenByTest);
  const labels = await page.evaluate(() => window.mcemuScope.series.map((s) => s.label).join(","));
  check(labels === "0.act_pos,1.following_error,di,do", `the stream carries the channels chosen per axis (${labels})`);
  const total = await page.evaluate(() => window.mcemuScope.total);
  await advance(page, 0.2);
  await page.waitForFunction((n) => window.mcemuScope.total >= n + 200, total);
  const last = await page.evaluate(() => window.mcemuScope.series[0].ring.at(window.mcemuScope.total - 1));
  const actual = (await api("/state")).body.axes[0].act_pos;
  check(Math.abs(last - actual) < 1e-9, `axis 0's act_pos arrives tick by tick (${last} = ${actual})`);

}

async function axes64(page) {
  await page.goto(`${base}/`);
  const want = Number(arg);
  await page.waitForFunction((n) => document.querySelectorAll("tr.axis-row").length === n, want);
  check(true, `${want} axes render`);
  await page.locator(`tr[data-axis="${want - 1}"]`).click();
  await page.locator(`[data-controls="${want - 1}"] [data-action="enable"]`).click();
  await page.waitForFunction((n) => {
    const cell = document.querySelector(`tr[data-axis="${n}"]`);
    return cell && cell.dataset.state === "standstill";
  }, want - 1);
  check(true, `the last axis (${want - 1}) is enabled from the page`);
}

async function token(page) {
  const refused = await api("/state");
  check(refused.status === 401 && refused.body.error === "unauthorized", `no token: ${refused.status}`);
  check((await api("/state", {}, "wrong")).status === 401, "a wrong token: 401");
  check((await api("/state", {}, arg)).status === 200, "the token: 200");
  await page.goto(`${base}/`);
  await page.locator("#token-dialog").waitFor({ state: "visible" });
  check(true, "the page asks for the token");
  await page.locator("#token-input").fill(arg);
  await page.locator('#token-form button[type="submit"]').click();
  await page.waitForFunction(() => document.querySelectorAll("tr.axis-row").length === 4);
  check(true, "with it, the page shows the machine");
  await page.waitForFunction(() => /streaming/.test(document.getElementById("stream-status").textContent));
  check(true, "and streams (token in the stream's query)");
}
