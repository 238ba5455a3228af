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

  const count = (n) => dl.el("td", { class: "num count" + (n ? "" : " zero"), text: String(n || 0) });

  function render(overview) {
    const rows = overview.sweeps.map((s) => dl.el("tr", { "data-sweep": s.id },
      dl.el("td", {}, dl.el("a", { href: "/studies/" + encodeURIComponent(s.id), text: s.name || s.id })),
      dl.el("td", { class: "muted", text: s.id }),
      count(s.jobs), count(s.queued), count(s.running), count(s.completed), count(s.failed), count(s.cancelled),
      dl.el("td", {}, dl.bar(s.progress)),
      dl.el("td", { text: dl.when(s.created_time) })));
    studies.replaceChildren(...(rows.length ? rows : [dl.el("tr", {}, dl.el("td", { colspan: 10, class: "empty", text: "No studies yet: dlmfd sweep SCENE --grid KEY=V1,V2 ... starts one." }))]));
    const jobRows = overview.jobs.map((j) => dl.el("tr", { "data-job": j.id },
      dl.el("td", {}, dl.el("a", { href: "/jobs/" + encodeURIComponent(j.id), text: j.name || j.id })),
      dl.el("td", { text: j.id }),
      dl.el("td", {}, dl.badge(j.state, j.held)),
      dl.el("td", {}, dl.bar(dl.fraction(j), dl.num(j.time) + " / " + dl.num(j.end_time))),
      dl.el("td", { text: dl.when(j.created_time) })));
    jobs.replaceChildren(...(jobRows.length ? jobRows : [dl.el("tr", {}, dl.el("td", { colspan: 5, class: "empty", text: "None." }))]));
  }

  async function reload() {
    try { render(await dl.api("/api/overview")); } catch (e) { dl.notice(e.message, "error"); }
  }
  dl.live("/events/overview", { overview: render }, reload);
})();
