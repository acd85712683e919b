// The control API as the page uses it: the same requests and bodies as any client, with the
// token (asked for once, on the first 401) and the typed error bodies passed back untouched.

const TOKEN_KEY = "mcemu.token";

let token = sessionStorage.getItem(TOKEN_KEY) || "";
let asking = null;

/** Ask for the token once; every request waiting on a 401 shares the answer. */
function askToken() {
  if (asking) return asking;
  const dialog = document.getElementById("token-dialog");
  const form = document.getElementById("token-form");
  asking = new Promise((resolve) => {
    form.addEventListener(
      "submit",
      () => {
        token = document.getElementById("token-input").value.trim();
        sessionStorage.setItem(TOKEN_KEY, token);
        asking = null;
        resolve();
      },
      { once: true },
    );
    dialog.showModal();
  });
  return asking;
}

/**
 * One API request. Resolves to `{ok, status, body}`; `body` is the parsed JSON reply (an error
 * body on failure, `{error, detail}` or an engine refusal `{code, message}`).
 */
export async function request(method, path, body) {
  for (;;) {
    const headers = {};
    if (token) headers.Authorization = `Bearer ${token}`;
    const init = { method, headers };
    if (body !== undefined) {
      headers["Content-Type"] = "application/json";
      init.body = JSON.stringify(body);
    }
    let reply;
    try {
      reply = await fetch(`/api/v1${path}`, init);
    } catch (e) {
      return { ok: false, status: 0, body: { error: "network", detail: String(e) } };
    }
    if (reply.status === 401) {
      await askToken();
      continue;
    }
    const text = await reply.text();
    let parsed;
    try {
      parsed = text ? JSON.parse(text) : null;
    } catch {
      parsed = text;
    }
    return { ok: reply.ok, status: reply.status, body: parsed };
  }
}

/** The stream's URL for `query` (EventSource cannot send headers: the token goes along). */
export function streamUrl(query) {
  const q = new URLSearchParams(query);
  if (token) q.set("token", token);
  return `/api/v1/stream?${q}`;
}

/** A reply's error as one line: the typed error's code and its message. */
export function errorText(reply) {
  const b = reply.body;
  if (b && typeof b === "object") {
    const code = b.code || b.error || `HTTP ${reply.status}`;
    const message = b.message || b.detail || "";
    return `${code}: ${message}`;
  }
  return `HTTP ${reply.status}: ${b ?? ""}`;
}

/**
 * Send `method path body` for a control and show the outcome in `where` (the element beside
 * it with `data-error`): cleared on success, the typed error on failure. Calls `after` either
 * way (to refresh the machine view).
 */
export async function control(where, method, path, body, after) {
  const out = where.querySelector("[data-error]") || where;
  out.textContent = "…";
  out.classList.remove("failed");
  const reply = await request(method, path, body);
  if (reply.ok) {
    out.textContent = "";
  } else {
    out.textContent = errorText(reply);
    out.classList.add("failed");
  }
  if (after) after();
  return reply;
}
