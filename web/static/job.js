// A job's page: its state and live progress (step, t, ETA), the actions of the CLI (cancel, retry,
// hold, release, delete with a confirmation), the latest field picture (drawn by the server with
// viz/, as `dlmfd plot`), the particles' positions and velocities as charts that grow while it
// runs, the solver's log, and its result files to download.
"use strict";

(function () {
  const jobId = decodeURIComponent(window.location.pathname.split("/")[2]);
  const enc = encodeURIComponent(jobId);
  dl.header([{ text: "studies", href: "/" }, { text: jobId }]);
  const main = document.getElementById("main");
  let job = null;
  let history = { time: [], particles: [] };
  let logOffset = 0;

  const title = dl.el("h1", { text: jobId });
  const meta = dl.el("div", { class: "meta" });
  const stateLine = dl.el("div", { class: "toolbar" });
  const stats = dl.el("div", { class: "stats" });
  const progress = dl.el("div", { class: "wide" });
  const button = (id, text, onclick, cls) => dl.el("button", { id, text, onclick, class: cls });
  const actions = dl.el("div", { class: "actions" },
    button("cancel", "Cancel", () => act("cancel")),
    button("retry", "Retry", () => act("retry")),
    button("hold", "Hold", () => act("hold")),
    button("release", "Release", () => act("release")),
    button("delete", "Delete", () => act("delete"), "danger"));
  const field = dl.el("img", { class: "field", id: "field", alt: "latest field snapshot" });
  const fieldNote = dl.el("div", { class: "meta", text: "No field snapshot yet." });
  const movie = dl.el("video", { id: "movie", controls: true, muted: true, playsinline: true });
  const movieNote = dl.el("span", { class: "meta" });
  const movieButton = dl.el("button", { id: "make-movie", text: "Make the movie", onclick: makeMovie });
  const positions = dl.el("canvas", { class: "chart", id: "positions" });
  const velocities = dl.el("canvas", { class: "chart", id: "velocities" });
  const log = dl.el("pre", { class: "log", id: "log" });
  const files = dl.el("tbody");
  main.append(title, meta, stateLine, stats, progress, actions,
    dl.el("div", { class: "cols" },
      dl.el("div", { class: "panel" }, dl.el("h2", { text: "Latest field" }), field, fieldNote,
        dl.el("h2", { text: "Movie" }), dl.el("div", { class: "toolbar" }, movieButton, movieNote), movie),
      dl.el("div", { class: "panel" }, dl.el("h2", { text: "Particles" }), positions, velocities)),
    dl.el("div", { class: "cols" },
      dl.el("div", { class: "panel" }, dl.el("h2", { text: "Solver log" }), log),
      dl.el("div", { class: "panel" }, dl.el("h2", { text: "Files" }),
        dl.el("table", { class: "grid", id: "files" }, dl.el("thead", {}, dl.el("tr", {}, dl.el("th", { text: "file" }), dl.el("th", { text: "bytes" }), dl.el("th", { text: "modified" }))), files))));
  field.style.display = "none";
  field.addEventListener("load", () => { field.style.display = "block"; fieldNote.textContent = ""; });
  field.addEventListener("error", () => { field.style.display = "none"; fieldNote.textContent = "No field snapshot yet."; });

  // The movie of every snapshot so far, drawn by the server as `dlmfd movie` draws it.
  movie.style.display = "none";
  function makeMovie() {
    const url = "/movies/jobs/" + enc + "/movie.mp4?v=" + Date.now();
    movieButton.disabled = true;
    movieNote.textContent = "drawing the movie: one frame per snapshot…";
    movie.src = url;
  }
  movie.addEventListener("loadeddata", () => {
    movie.style.display = "block";
    movieButton.disabled = false;
    movieButton.textContent = "Make it again";
    movieNote.textContent = dl.num(movie.duration) + " s at 10 frames/s";
  });
  movie.addEventListener("error", async () => {
    movieButton.disabled = false;
    movie.style.display = "none";
    try { await dl.api(movie.src); movieNote.textContent = "the movie cannot be played"; }
    catch (e) { movieNote.textContent = e.message; }
  });

  let live = null;
  async function act(action) {
    if (action === "delete") {
      const running = job && job.state === "RUNNING";
      if (!(await dl.confirm("Delete job " + jobId + ": its record, results and log?" + (running ? " It is running: it will be cancelled first." : "") + " This cannot be undone.", "Delete"))) return;
    }
    try {
      const reply = await dl.post("/api/jobs/" + enc + "/" + action, action === "delete" ? { confirm: jobId, force: true } : {});
      if (action === "delete") { window.location.href = job && job.study_id ? "/studies/" + encodeURIComponent(job.study_id) : "/"; return; }
      if (reply && reply.id) showJob(reply);
      if (reply && reply.jobs && reply.jobs[0]) showJob(reply.jobs[0]);
      dl.notice("");
      if (action === "retry") { history = { time: [], particles: [] }; live.restart(); }
    } catch (e) { dl.notice(e.message, "error"); }
  }

  function showJob(j) {
    job = Object.assign(job || {}, j);
    title.textContent = job.name || job.id;
    dl.fill(meta, dl.el("span", { text: job.id }),
      job.study_id ? dl.el("span", {}, "study ", dl.el("a", { href: "/studies/" + encodeURIComponent(job.study_id), text: job.study_id })) : null,
      dl.el("span", { text: "attempt " + (job.attempt || 1) }),
      dl.el("span", { text: "created " + dl.when(job.created_time) }),
      (job.overrides || []).length ? dl.el("span", { text: job.overrides.join(" ") }) : null);
    dl.fill(stateLine, dl.el("span", { id: "state" }, dl.badge(job.state, job.held)), job.reason ? dl.el("span", { class: "meta", id: "reason", text: job.reason }) : null);
    const s = job.state;
    document.getElementById("cancel").disabled = dl.final(s);
    document.getElementById("retry").disabled = !dl.final(s);
    document.getElementById("hold").disabled = s !== "QUEUED" || job.held;
    document.getElementById("release").disabled = !job.held;
    showProgress();
  }

  function showProgress() {
    const stat = (id, value, label) => dl.el("div", {}, dl.el("b", { id, text: value }), dl.el("span", { text: label }));
    stats.replaceChildren(stat("step", dl.num(job.step || 0), "step"), stat("time", dl.num(job.time || 0) + " / " + dl.num(job.end_time), "t / end"),
      stat("eta", job.state === "RUNNING" ? dl.duration(job.eta_seconds) : "–", "ETA"),
      stat("speed", job.steps_per_second ? dl.num(job.steps_per_second) : "–", "steps/s"),
      stat("max-tra", job.max_trA ? dl.num(job.max_trA) : "–", "max trA"));
    progress.replaceChildren(dl.bar(dl.fraction(job)));
  }

  function drawCharts() {
    const series = (key, suffix) => history.particles.map((p) => ({ name: "p" + p.id + " " + suffix, x: history.time, y: p[key] }));
    charts.draw(positions, [...series("x", "x"), ...series("y", "y")], { title: "position", xlabel: "t", ylabel: "x, y" });
    charts.draw(velocities, [...series("u", "u"), ...series("v", "v")], { title: "velocity", xlabel: "t", ylabel: "u, v" });
  }
  let chartQueued = false;
  function scheduleCharts() {
    if (chartQueued) return;
    chartQueued = true;
    setTimeout(() => { chartQueued = false; drawCharts(); }, 250);
  }

  function refreshField(step) {
    dl.setPicture(field, "/pictures/jobs/" + enc + "/field.png?width=900&height=700&v=" + (step || Date.now()), 2000);
  }

  let logBusy = false, logAgain = false;
  async function readLog() {
    if (logBusy) { logAgain = true; return; }
    logBusy = true;
    try {
      while (true) {
        const chunk = await dl.api("/api/jobs/" + enc + "/log?offset=" + logOffset);
        if (chunk.text) { log.textContent += chunk.text; log.scrollTop = log.scrollHeight; }
        logOffset = chunk.next_offset;
        if (logOffset >= chunk.size || !chunk.text) break;
      }
    } catch (e) { /* the log appears once the solver starts */ }
    logBusy = false;
    if (logAgain) { logAgain = false; readLog(); }
  }

  async function readFiles() {
    try {
      const list = await dl.api("/api/jobs/" + enc + "/files");
      files.replaceChildren(...(list.files || []).map((f) => dl.el("tr", {},
        dl.el("td", {}, dl.el("a", { href: "/files/jobs/" + enc + "/" + f.path.split("/").map(encodeURIComponent).join("/"), download: f.path.split("/").pop(), text: f.path })),
        dl.el("td", { class: "num", text: String(f.size) }),
        dl.el("td", { text: dl.when(f.modified_time) }))));
    } catch (e) { files.replaceChildren(); }
  }

  async function reload() {
    try { showJob(await dl.api("/api/jobs/" + enc)); } catch (e) { dl.notice(e.message, "error"); return; }
    try { history = await dl.api("/api/jobs/" + enc + "/particles"); } catch (e) { /* none yet */ }
    drawCharts();
    refreshField();
    readLog();
    readFiles();
  }

  function onParticles(p) {
    const last = history.time.length ? history.time[history.time.length - 1] : -Infinity;
    if (!(p.time > last)) return;
    history.time.push(p.time);
    for (const q of p.particles) {
      let track = history.particles.find((t) => t.id === q.id);
      if (!track) {
        track = { id: q.id, x: history.time.slice(0, -1).map(() => null), y: [], u: [], v: [], omega: [] };
        for (const key of ["y", "u", "v", "omega"]) track[key] = track.x.slice();
        history.particles.push(track);
      }
      for (const key of ["x", "y", "u", "v", "omega"]) track[key].push(q[key]);
    }
    scheduleCharts();
  }

  live = dl.live("/events/jobs/" + enc, {
    job: (j) => { const ended = dl.final(j.state) && !(job && dl.final(job.state)); showJob(j); if (ended) { readFiles(); readLog(); refreshField(); } },
    progress: (p) => { if (!job) return; Object.assign(job, p); if (job.state === "QUEUED") job.state = "RUNNING"; showProgress(); },
    particles: onParticles,
    snapshot: (s) => { refreshField(s.step); readFiles(); },
    log: () => readLog(),
    gone: () => dl.notice("This job no longer exists.", "error"),
  }, reload);
})();
