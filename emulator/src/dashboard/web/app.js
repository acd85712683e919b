// The dashboard's entry: the machine view refreshed from `/state` (a few times a second and
// after every control), the scope fed by the stream, the time-advance control.

import { control, errorText, request } from "./api.js";
import { MachineView } from "./machine.js";
import { Scope } from "./scope.js";

/** Machine view refresh while nothing is clicked, ms (the plots stream every tick). */
const REFRESH_MS = 250;

let inFlight = false;
let again = false;

async function refresh() {
  if (inFlight) {
    again = true;
    return;
  }
  inFlight = true;
  const reply = await request("GET", "/state");
  inFlight = false;
  if (reply.ok) {
    view.render(reply.body);
    document.body.dataset.tick = String(reply.body.tick);
    if (!scope.source) scope.connect(reply.body.axes.length);
  } else {
    document.getElementById("machine-name").textContent = `state unavailable: ${errorText(reply)}`;
  }
  if (again) {
    again = false;
    refresh();
  }
}

const view = new MachineView(refresh);
const scope = new Scope();
window.mcemuScope = scope; // for the browser tests and the console

document.getElementById("advance").addEventListener("submit", (e) => {
  e.preventDefault();
  const form = e.target;
  const amount = Number(form.elements.amount.value);
  const body = form.elements.unit.value === "ticks" ? { ticks: amount } : { seconds: amount };
  control(form, "POST", "/time/advance", body, refresh);
});

refresh();
setInterval(refresh, REFRESH_MS);
