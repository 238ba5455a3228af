// A study's page: its counts and progress, actions on the whole study, a chart of a result
// against a parameter (drawn by the server with viz/, as `dlmfd chart --study`), and a table with
// one row per job: a thumbnail of its latest field, its state and progress (live), one column per
// swept parameter and per result (the columns of `dlmfd table`); sortable by any column (click the
// header) and filtered by text and state.
"use strict";

(function () {
  const studyId = decodeURIComponent(window.location.pathname.split("/")[2]);
  dl.header([{ text: "studies", href: "/" }, { text: studyId }]);
  const main = document.getElementById("main");
  const state = { study: null, columns: [], parameters: [], rows: new Map(), sort: { column: null, desc: false }, filter: "", stateFilter: "", particles: false };
  const thumbs = new Map();  // job id -> img element, kept across renders

  const title = dl.el("h1", { text: studyId });
  const meta = dl.el("div", { class: "meta" });
  const stats = dl.el("div", { class: "stats" });
  const progress = dl.el("div", { class: "wide" });
  const actions = dl.el("div", { class: "actions" },
    dl.el("button", { id: "cancel-study", text: "Cancel unfinished", onclick: () => act("cancel", "Cancel every unfinished job of this study?") }),
    dl.el("button", { id: "retry-study", text: "Retry failed and cancelled", onclick: () => act("retry") }),
    dl.el("button", { id: "delete-study", class: "danger", text: "Delete study", onclick: () => act("delete", "Delete this study: every job's record and results? This cannot be undone.") }));
  const xSelect = dl.el("select", { id: "chart-x" }), ySelect = dl.el("select", { id: "chart-y" }), groupSelect = dl.el("select", { id: "chart-group" });
  const logx = dl.el("input", { type: "checkbox", id: "chart-logx" }), logy = dl.el("input", { type: "checkbox", id: "chart-logy" });
  const chart = dl.el("img", { class: "chart", id: "chart", alt: "chart of the study" });
  const chartNote = dl.el("div", { class: "meta" });
  const filter = dl.el("input", { type: "search", id: "filter", placeholder: "filter rows (any text, e.g. 0.04 or failed)" });
  const stateSelect = dl.el("select", { id: "state-filter" }, dl.el("option", { value: "", text: "every state" }),
    ...["queued", "running", "completed", "failed", "cancelled"].map((s) => dl.el("option", { value: s, text: s })));
  const particleBox = dl.el("input", { type: "checkbox", id: "particle-columns" });
  const thead = dl.el("thead"), tbody = dl.el("tbody");
  main.append(title, meta, stats, progress, actions,
    dl.el("div", { class: "toolbar" }, filter, stateSelect, dl.el("label", {}, particleBox, " particle columns"),
      dl.el("span", { id: "row-count", class: "meta" })),
    dl.el("div", { class: "scroll" }, dl.el("table", { class: "grid", id: "jobs-table" }, thead, tbody)),
    dl.el("h2", { text: "Chart" }),
    dl.el("div", { class: "panel" },
      dl.el("div", { class: "toolbar" }, "y", ySelect, "against", xSelect, "group by", groupSelect,
        dl.el("label", {}, logx, " log x"), dl.el("label", {}, logy, " log y")),
      chart, chartNote));

  async function act(action, question) {
    if (question && !(await dl.confirm(question, action === "delete" ? "Delete" : "Yes"))) return;
    try {
      await dl.post("/api/studies/" + encodeURIComponent(studyId) + "/" + action, action === "delete" ? { confirm: studyId, force: true } : {});
      if (action === "delete") { window.location.href = "/"; return; }
      dl.notice(action === "retry" ? "Requeued." : "Cancel requested.", "info");
      reload();
    } catch (e) { dl.notice(e.message, "error"); }
  }

  const resultColumns = () => state.columns.filter((c) => !["job", "name", "state", "status", "reason"].includes(c) && !state.parameters.includes(c));
  const shownColumns = () => {
    const results = resultColumns().filter((c) => state.particles || !/^p\d+\./.test(c));
    return ["thumb", "name", "state", "progress", ...state.parameters, "status", ...results];
  };

  function fillSelect(select, values, keep, allowNone) {
    const current = select.value || keep;
    select.replaceChildren(...(allowNone ? [dl.el("option", { value: "", text: "(none)" })] : []), ...values.map((v) => dl.el("option", { value: v, text: v })));
    if (values.includes(current) || (allowNone && current === "")) select.value = current;
  }

  function refreshChart() {
    if (!xSelect.value || !ySelect.value) return;
    const q = new URLSearchParams({ x: xSelect.value, y: ySelect.value, width: 860, height: 480 });
    if (groupSelect.value) q.set("group", groupSelect.value);
    if (logx.checked) q.set("logx", "1");
    if (logy.checked) q.set("logy", "1");
    q.set("v", String(Date.now()));
    chart.src = "/pictures/studies/" + encodeURIComponent(studyId) + "/chart.png?" + q;
  }
  chart.addEventListener("error", () => { chart.style.display = "none"; chartNote.textContent = "No job has both " + ySelect.value + " and " + xSelect.value + " yet."; });
  chart.addEventListener("load", () => { chart.style.display = "block"; chartNote.textContent = ""; });
  for (const c of [xSelect, ySelect, groupSelect, logx, logy]) c.addEventListener("change", refreshChart);
  filter.addEventListener("input", () => { state.filter = filter.value.trim().toLowerCase(); render(); });
  stateSelect.addEventListener("change", () => { state.stateFilter = stateSelect.value; render(); });
  particleBox.addEventListener("change", () => { state.particles = particleBox.checked; render(); });

  function thumbFor(id, step) {
    let img = thumbs.get(id);
    if (!img) {
      img = dl.el("img", { class: "thumb", alt: "latest field of " + id });
      img.addEventListener("error", () => { img.style.display = "none"; img.dataset.missing = "1"; });
      img.addEventListener("load", () => { img.style.display = "block"; delete img.dataset.missing; });
      thumbs.set(id, img);
    }
    const src = "/pictures/jobs/" + encodeURIComponent(id) + "/field.png?width=220&height=220&caption=0&v=" + step;
    dl.setPicture(img, src, 5000);
    return img;
  }

  function value(row, column) {
    if (column === "state") return dl.stateName(row.live.state);
    if (column === "progress") return dl.fraction(row.live);
    if (column === "name") return row.name;
    return row.cells[column];
  }

  function compare(a, b) {
    const { column, desc } = state.sort;
    if (!column) return 0;
    const x = value(a, column), y = value(b, column);
    const empty = (v) => v === null || v === undefined || v === "";
    if (empty(x) || empty(y)) return empty(x) === empty(y) ? 0 : empty(x) ? 1 : -1;  // empty last
    const r = typeof x === "number" && typeof y === "number" ? x - y : String(x).localeCompare(String(y), undefined, { numeric: true });
    return desc ? -r : r;
  }

  function headerCell(c) {
    const sorted = state.sort.column === c ? (state.sort.desc ? "sorted-desc" : "sorted-asc") : "";
    return { sig: c + "|" + sorted, make: () => {
      const th = dl.el("th", { text: c === "thumb" ? "field" : c, "data-column": c });
      if (c === "thumb") return th;
      th.classList.add("sortable");
      if (sorted) th.classList.add(sorted);
      th.addEventListener("click", () => {
        state.sort = { column: c, desc: state.sort.column === c ? !state.sort.desc : false };
        render();
      });
      return th;
    } };
  }

  function bodyCell(r, c) {
    const live = r.live;
    if (c === "thumb") {
      const img = thumbFor(r.id, live.snapshot_step || 0);  // kept across renders; only its src moves
      return { sig: "thumb", make: () => dl.el("td", {}, img) };
    }
    if (c === "name") return { sig: "name|" + r.name, make: () => dl.el("td", {}, dl.el("a", { href: "/jobs/" + encodeURIComponent(r.id), text: r.name || r.id })) };
    if (c === "state") return { sig: "state|" + live.state + "|" + live.held, make: () => dl.el("td", { class: "state" }, dl.badge(live.state, live.held)) };
    if (c === "progress") {
      const eta = live.state === "RUNNING" && isFinite(live.eta_seconds) ? "  ETA " + dl.duration(live.eta_seconds) : "";
      const fraction = dl.fraction(live), label = "t " + dl.num(live.time) + " / " + dl.num(live.end_time) + eta;
      return { sig: "progress|" + fraction + "|" + label, make: () => dl.el("td", { class: "progress" }, dl.bar(fraction, label)) };
    }
    const v = r.cells[c];
    return { sig: c + "|" + typeof v + "|" + dl.num(v), make: () => dl.el("td", { class: typeof v === "number" ? "num" : "", text: dl.num(v) }) };
  }

  // Updates the table in place (dl.syncRows): progress events arrive many times a second, and a
  // header or link rebuilt under the pointer would swallow the user's click.
  function render() {
    const columns = shownColumns();
    dl.syncRows(thead, [columns], () => "header", (cs) => cs.map(headerCell));
    let rows = [...state.rows.values()];
    if (state.stateFilter) rows = rows.filter((r) => dl.stateName(r.live.state) === state.stateFilter);
    if (state.filter) rows = rows.filter((r) => columns.some((c) => c !== "thumb" && String(dl.num(value(r, c)) || "").toLowerCase().includes(state.filter)) || r.id.includes(state.filter));
    rows.sort(compare);
    dl.syncRows(tbody, rows, (r) => r.id, (r) => columns.map((c) => bodyCell(r, c)), (id) => ({ "data-job": id }));
    document.getElementById("row-count").textContent = rows.length + " of " + state.rows.size + " jobs";
  }

  let renderQueued = false;
  function scheduleRender() {
    if (renderQueued) return;
    renderQueued = true;
    requestAnimationFrame(() => { renderQueued = false; render(); });
  }

  function showStudy(s) {
    state.study = s;
    title.textContent = s.name || s.id;
    dl.fill(meta, dl.el("span", { text: s.id }), dl.el("span", { text: "created " + dl.when(s.created_time) }),
      dl.el("span", { text: (s.axes || []).map((a) => a.key + " = " + (a.values || []).join(", ")).join("; ") }),
      s.max_running ? dl.el("span", { text: "at most " + s.max_running + " running" }) : null);
    const stat = (n, label) => dl.el("div", { "data-count": label }, dl.el("b", { text: String(n || 0) }), dl.el("span", { text: label }));
    stats.replaceChildren(stat(s.jobs, "jobs"), stat(s.queued, "queued"), stat(s.running, "running"), stat(s.completed, "completed"), stat(s.failed, "failed"), stat(s.cancelled, "cancelled"));
    progress.replaceChildren(dl.bar(s.progress));
  }

  async function reload() {
    let data;
    try { data = await dl.api("/api/studies/" + encodeURIComponent(studyId)); } catch (e) { dl.notice(e.message, "error"); return; }
    showStudy(data.study);
    state.columns = data.columns;
    state.parameters = data.parameters.filter((p) => data.columns.includes(p));
    const live = new Map(data.jobs.map((j) => [j.id, j]));
    const next = new Map();
    for (const row of data.rows) {
      const old = state.rows.get(row.job);
      const job = live.get(row.job) || (old && old.live) || { id: row.job, state: row.state };
      if (old && old.live.snapshot_step) job.snapshot_step = old.live.snapshot_step;
      next.set(row.job, { id: row.job, name: row.name, cells: row, live: Object.assign({}, job) });
    }
    state.rows = next;
    fillSelect(xSelect, state.parameters, state.parameters[0], false);
    const results = resultColumns();
    fillSelect(ySelect, results, results.includes("max_trA") ? "max_trA" : results[0], false);
    fillSelect(groupSelect, state.parameters, state.parameters.length > 1 ? state.parameters[1] : "", true);
    render();
    refreshChart();
  }

  function onJob(job) {
    const row = state.rows.get(job.id);
    if (!row) { reload(); return; }
    const wasFinal = dl.final(row.live.state);
    row.live = Object.assign(row.live, job);
    scheduleRender();
    if (dl.final(job.state) && !wasFinal) reload();  // its results are in the table now
  }
  function onProgress(p) {
    const row = state.rows.get(p.job_id);
    if (!row) return;
    Object.assign(row.live, { step: p.step, time: p.time, end_time: p.end_time, eta_seconds: p.eta_seconds });
    if (row.live.state === "QUEUED") row.live.state = "RUNNING";
    scheduleRender();
  }
  function onSnapshot(s) {
    const row = state.rows.get(s.job_id);
    if (!row) return;
    row.live.snapshot_step = s.step;
    scheduleRender();
  }
  dl.live("/events/studies/" + encodeURIComponent(studyId),
    { job: onJob, progress: onProgress, snapshot: onSnapshot, study: showStudy,
      gone: () => dl.notice("This study no longer exists.", "error") }, reload);
})();
