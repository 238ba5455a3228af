// Shared by the dashboard's pages: calls to this server's API, live events, safe DOM building
// (text only, never HTML from data), number and time formats, the confirmation dialog.
"use strict";

const dl = {};

dl.el = function (tag, attrs, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key === "class") node.className = value;
    else if (key === "text") node.textContent = value;
    else if (key.startsWith("on")) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value === true ? "" : String(value));
  }
  for (const child of children.flat()) {
    if (child === undefined || child === null) continue;
    node.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return node;
};

// Replaces the node's children, skipping null and undefined (replaceChildren would write "null").
dl.fill = function (node, ...children) {
  node.replaceChildren(...children.flat().filter((c) => c !== null && c !== undefined));
};

// Points the picture at `src`, one load at a time and at most one every `every` ms: while a
// picture loads (the server draws it) or waits its turn, a newer src replaces the one before it,
// so snapshots written faster than pictures are drawn neither starve the picture nor keep the
// server drawing.
dl.setPicture = function (img, src, every) {
  if (img.dataset.want === src) return;
  img.dataset.want = src;
  img.dataset.every = String(every || 0);
  if (img.dataset.loading === "1" || img.dataset.timer === "1") return;
  const next = () => {
    if (!img.dataset.want || img.dataset.want === img.dataset.shown) return;
    const wait = Number(img.dataset.last || 0) + Number(img.dataset.every) - Date.now();
    if (wait > 0) {
      img.dataset.timer = "1";
      setTimeout(() => { img.dataset.timer = "0"; next(); }, wait);
      return;
    }
    img.dataset.loading = "1";
    img.dataset.last = String(Date.now());
    img.dataset.shown = img.dataset.want;
    img.src = img.dataset.want;
  };
  if (!img.dataset.hooked) {
    img.dataset.hooked = "1";
    const done = () => { img.dataset.loading = "0"; next(); };
    img.addEventListener("load", done);
    img.addEventListener("error", done);
  }
  next();
};

dl.latencies = [];
dl.catchUp = [];
dl.steadyFrom = 0;
dl.session = null;
dl.loadSession = async function () {
  if (!dl.session) dl.session = await dl.api("/api/session");
  return dl.session;
};

dl.api = async function (path, options) {
  const response = await fetch(path, Object.assign({ credentials: "same-origin" }, options || {}));
  if (response.status === 401) {
    window.location.href = "/login";
    throw new Error("signed out");
  }
  const text = await response.text();
  let body = null;
  try { body = text ? JSON.parse(text) : null; } catch (e) { body = null; }
  if (!response.ok) throw new Error((body && body.error) || response.status + " " + response.statusText);
  return body;
};

dl.post = async function (path, body) {
  const session = await dl.loadSession();
  return dl.api(path, {
    method: "POST",
    headers: { "Content-Type": "application/json", "X-CSRF-Token": session.csrf },
    body: JSON.stringify(body || {}),
  });
};

// A message line at the top of the page: kind "error", "info" or "" (hidden).
dl.notice = function (text, kind) {
  const box = document.getElementById("notice");
  if (!box) return;
  box.textContent = text || "";
  box.className = "notice " + (text ? kind || "info" : "hidden");
};

// Live events of `path`; `handlers` maps event names to functions of the parsed data, and
// `reload` is called when the stream (re)opens or asks for it (missed events).
dl.live = function (path, handlers, reload) {
  const status = document.getElementById("live");
  const show = (text, kind) => { if (status) { status.textContent = text; status.className = "live " + kind; } };
  let source = null;
  const open = () => {
    source = new EventSource(path);
    source.onopen = () => { dl.steadyFrom = Date.now() + 3000; show("live", "on"); reload(); };
    source.onerror = () => show("reconnecting…", "off");
    for (const [name, handler] of Object.entries(handlers)) {
      source.addEventListener(name, (event) => {
        const data = JSON.parse(event.data);
        handler(data);
        // Seconds from the daemon's event to the page showing it (docs/dashboard.md measures it).
        // Events within 3 s of the stream (re)opening are catch-up: issued while no stream ran.
        if (name === "progress" && data.wall_time) {
          const list = Date.now() < dl.steadyFrom ? dl.catchUp : dl.latencies;
          list.push(Date.now() / 1000 - data.wall_time);
          if (list.length > 1000) list.shift();
        }
      });
    }
    source.addEventListener("resync", () => reload());
    source.addEventListener("daemon", (event) => {
      const data = JSON.parse(event.data);
      if (data.connected) { dl.steadyFrom = Date.now() + 3000; show("live", "on"); dl.notice(""); }
      else { show("daemon lost", "off"); dl.notice(data.message, "error"); }
    });
  };
  open();
  window.addEventListener("pagehide", () => source && source.close());
  return { restart() { if (source) source.close(); open(); } };
};

dl.stateNames = { QUEUED: "queued", RUNNING: "running", COMPLETED: "completed", FAILED: "failed", CANCELLED: "cancelled" };
dl.stateName = (state) => dl.stateNames[state] || String(state || "").toLowerCase();
dl.final = (state) => state === "COMPLETED" || state === "FAILED" || state === "CANCELLED";
dl.badge = function (state, held) {
  const name = dl.stateName(state);
  return dl.el("span", { class: "badge " + name, text: held && state === "QUEUED" ? "held" : name });
};

dl.num = function (x) {
  if (x === null || x === undefined || x === "" || (typeof x === "number" && !isFinite(x))) return "";
  if (typeof x !== "number") return String(x);
  if (Number.isInteger(x)) return String(x);
  const a = Math.abs(x);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? x.toExponential(3) : String(Number(x.toPrecision(4)));
};
dl.duration = function (seconds) {
  if (seconds === null || seconds === undefined || !isFinite(seconds) || seconds < 0) return "–";
  const s = Math.round(seconds);
  if (s < 60) return s + "s";
  if (s < 3600) return Math.floor(s / 60) + "m" + String(s % 60).padStart(2, "0") + "s";
  return Math.floor(s / 3600) + "h" + String(Math.floor((s % 3600) / 60)).padStart(2, "0") + "m";
};
dl.when = function (epoch) {
  if (!epoch) return "–";
  const d = new Date(epoch * 1000);
  const pad = (n) => String(n).padStart(2, "0");
  return d.getFullYear() + "-" + pad(d.getMonth() + 1) + "-" + pad(d.getDate()) + " " + pad(d.getHours()) + ":" + pad(d.getMinutes()) + ":" + pad(d.getSeconds());
};
dl.fraction = function (job) {
  if (dl.final(job.state)) return job.state === "COMPLETED" ? 1 : Math.min(1, job.end_time > 0 ? job.time / job.end_time : 0);
  return job.end_time > 0 ? Math.max(0, Math.min(1, job.time / job.end_time)) : 0;
};
dl.bar = function (fraction, label) {
  const pct = Math.round(100 * Math.max(0, Math.min(1, fraction || 0)));
  const fill = dl.el("span", { class: "fill" });
  fill.style.width = pct + "%";
  return dl.el("span", { class: "bar", title: pct + "%" }, fill, dl.el("span", { class: "bar-label", text: label !== undefined ? label : pct + "%" }));
};

// Brings a table section (tbody or thead) to `items` in place: one row per key, kept across calls,
// each cell rebuilt only when its signature changed, rows moved only when their order changed. Live
// updates then neither replace what a user is about to click (a header, a link) nor redo the DOM
// work of what did not change. `cellsOf(item)` gives [{ sig, make }], `make()` building the <td>
// or <th>; `rowAttrs(key)` the new row's attributes.
dl.syncRows = function (section, items, keyOf, cellsOf, rowAttrs) {
  const old = section.dlRows || new Map();
  const kept = new Map();
  const order = items.map((item) => {
    const key = keyOf(item);
    const entry = old.get(key) || { tr: dl.el("tr", rowAttrs ? rowAttrs(key) : {}), sigs: [] };
    const cells = cellsOf(item);
    cells.forEach((cell, i) => {
      if (entry.sigs[i] === cell.sig && entry.tr.children[i]) return;
      const node = cell.make();
      if (entry.tr.children[i]) entry.tr.replaceChild(node, entry.tr.children[i]);
      else entry.tr.append(node);
      entry.sigs[i] = cell.sig;
    });
    while (entry.tr.children.length > cells.length) entry.tr.lastChild.remove();
    entry.sigs.length = cells.length;
    kept.set(key, entry);
    return entry.tr;
  });
  section.dlRows = kept;
  const now = section.children;
  if (now.length !== order.length || order.some((tr, i) => now[i] !== tr)) section.replaceChildren(...order);
};

// A modal question; resolves true when confirmed.
dl.confirm = function (text, action) {
  return new Promise((resolve) => {
    const dialog = dl.el("dialog", { class: "confirm" },
      dl.el("p", { text }),
      dl.el("div", { class: "buttons" },
        dl.el("button", { class: "cancel-button", text: "Keep", onclick: () => { dialog.close(); resolve(false); } }),
        dl.el("button", { class: "danger confirm-button", text: action, onclick: () => { dialog.close(); resolve(true); } })));
    dialog.addEventListener("close", () => { dialog.remove(); resolve(false); });
    document.body.append(dialog);
    dialog.showModal();
  });
};

dl.signOut = async function () {
  await dl.post("/logout");
  window.location.href = "/login";
};

dl.header = function (crumbs) {
  const bar = document.getElementById("top");
  bar.replaceChildren(
    dl.el("a", { class: "brand", href: "/", text: "dlmfd" }),
    ...crumbs.map((c) => [dl.el("span", { class: "sep", text: "/" }), c.href ? dl.el("a", { href: c.href, text: c.text }) : dl.el("span", { text: c.text })]).flat(),
    dl.el("span", { class: "grow" }),
    dl.el("span", { id: "live", class: "live off", text: "connecting…" }),
    dl.el("button", { class: "link", text: "sign out", onclick: dl.signOut }));
};
