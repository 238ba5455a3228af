// The studies page: one row per study, newest first, with its counts by state and a progress bar;
// below, the newest jobs outside studies. Live: /events/overview sends the whole list again
// within a fraction of a second of any event of an unfinished job.
"use strict";

(function () {
  dl.header([{ text: "studies" }]);
  const main = document.getElementById("main");
  const studies = dl.el("tbody");
  const jobs = dl.el("tbody");
  const head = (...names) => dl.el("thead", {}, dl.el("tr", {}, names.map((n) => dl.el("th", { text: n }))));
  main.append(
    dl.el("h1", { text: "Studies" }),
    dl.el("div", { class: "scroll" }, dl.el("table", { class: "grid", id: "studies" },
      head("study", "id", "jobs", "queued", "running", "done", "failed", "cancelled", "progress", "created"), studies)),
    dl.el("h2", { text: "Jobs outside studies" }),
    dl.el("div", { class: "scroll" }, dl.el("table", { class: "grid", id: "jobs" },
      head("job", "id", "state", "progress", "created"), jobs)));

  const count = (n) => ({ sig: String(n || 0), make: () => dl.el("td", { class: "num count" + (n ? "" : " zero"), text: String(n || 0) }) });
  const cell = (sig, make) => ({ sig, make });
  const text = (t, cls) => cell(t, () => dl.el("td", { class: cls, text: t }));
  const empty = (span, t) => [cell(t, () => dl.el("td", { colspan: span, class: "empty", text: t }))];

  function studyCells(s) {
    if (!s) return empty(10, "No studies yet: dlmfd study SCENE --grid KEY=V1,V2 ... starts one.");
    return [cell(s.name || s.id, () => dl.el("td", {}, dl.el("a", { href: "/studies/" + encodeURIComponent(s.id), text: s.name || s.id }))),
      text(s.id, "muted"), count(s.jobs), count(s.queued), count(s.running), count(s.completed), count(s.failed), count(s.cancelled),
      cell(String(s.progress), () => dl.el("td", {}, dl.bar(s.progress))), text(dl.when(s.created_time))];
  }

  function jobCells(j) {
    if (!j) return empty(5, "None.");
    const label = dl.num(j.time) + " / " + dl.num(j.end_time), fraction = dl.fraction(j);
    return [cell(j.name || j.id, () => dl.el("td", {}, dl.el("a", { href: "/jobs/" + encodeURIComponent(j.id), text: j.name || j.id }))),
      text(j.id), cell(j.state + "|" + j.held, () => dl.el("td", {}, dl.badge(j.state, j.held))),
      cell(fraction + "|" + label, () => dl.el("td", {}, dl.bar(fraction, label))), text(dl.when(j.created_time))];
  }

  // In place (dl.syncRows): the overview arrives again on every event of an unfinished job, and a
  // link rebuilt under the pointer would swallow the user's click.
  function render(overview) {
    const orNone = (list) => (list.length ? list : [null]);
    dl.syncRows(studies, orNone(overview.studies), (s) => (s ? s.id : ""), studyCells, (id) => (id ? { "data-study": id } : {}));
    dl.syncRows(jobs, orNone(overview.jobs), (j) => (j ? j.id : ""), jobCells, (id) => (id ? { "data-job": id } : {}));
  }

  async function reload() {
    try { render(await dl.api("/api/overview")); } catch (e) { dl.notice(e.message, "error"); }
  }
  dl.live("/events/overview", { overview: render }, reload);
})();
