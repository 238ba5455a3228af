"""A dashboard page left open for an hour of runs (issue 36, point 2): the real dlmfdd, dlmfd-web
and solver, Debian's headless Chromium holding the studies page and one study's page open on a
single load while 4-job studies are submitted one after another, and the daemon is
restarted every 15 minutes. Every 30 s it records the web process's resident memory, threads and
descriptors, /api/status (live pages, Watch streams), the tab's JavaScript heap, and checks the
pages against the daemon: one row per study and per job (no duplicate, none missing), the counts
and states the daemon gives once they settle, the page never reloaded. Prints a table and writes
it as CSV; docs/evidence/service.md records a run.

    DLMFD_BINARY_DIR=build nice -n 10 python3 bench/dashboard_soak.py [--minutes 60] [--csv F]
        [--restart-minutes 15] [--max-studies N]
"""

import argparse
import csv
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "browser"))
import web_support as ws  # noqa: E402

ws.skip_unless_browser()

from selenium.webdriver.common.by import By  # noqa: E402


def study_scene():
    # About 30 s of solver per job on an idle core (t = 20 at dt = 1e-3), a snapshot every 0.1:
    # a 4-job study runs for about 2 minutes, one job at a time.
    return ws.study_scene().replace("end = 1.0", "end = 20.0").replace("density = 1.01", "density = 1.001")


def web_memory(web):
    values = {}
    with open(f"/proc/{web.process.pid}/status") as f:
        for line in f:
            key, _, rest = line.partition(":")
            if key in ("VmRSS", "Threads"):
                values[key] = int(rest.split()[0])
    values["fds"] = len(os.listdir(f"/proc/{web.process.pid}/fd"))
    return values


def write_csv(path, rows):
    if not rows:
        return
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--minutes", type=float, default=60.0)
    parser.add_argument("--csv", default="dashboard_soak.csv")
    # Daemon restarts closer together, and no new studies after the first few, isolate what a
    # restart costs the web process (each restart is sampled just before the next one).
    parser.add_argument("--restart-minutes", type=float, default=15.0)
    parser.add_argument("--max-studies", type=int, default=1000000)
    args = parser.parse_args()

    daemon = ws.Daemon(tokens=True, max_concurrent=1)
    web = ws.Web(daemon)
    overview_page = ws.start_browser()
    study_page = ws.start_browser()
    rows = []
    failures = []
    try:
        for b in (overview_page, study_page):
            b.get(web.url + "/login")
            b.find_element(By.ID, "token").send_keys(ws.Daemon.TOKEN)
            b.find_element(By.CSS_SELECTOR, "form button").click()
            ws.wait_for(lambda: b.current_url.rstrip("/") == web.url, "the sign in", 60)
        first = daemon.submit_study("soak-0", study_scene(), "particles.*.density=1.001,1.002",
                                    "fluid.relaxation_time=0.5,1")
        study_page.get(web.url + "/studies/" + first)
        for b in (overview_page, study_page):
            ws.wait_for(lambda: b.execute_script("return document.querySelector('#live') && "
                                                 "document.querySelector('#live').textContent === 'live'"),
                        "the page to be live", 60)
            b.execute_script("window.__one_load = true")
        start = time.monotonic()
        next_sample = start
        next_restart = start + args.restart_minutes * 60
        studies = 1
        while time.monotonic() - start < args.minutes * 60:
            unfinished = daemon.cli("list", "--state", "queued", "--state", "running", "-q").split()
            if not unfinished and studies < args.max_studies:
                daemon.submit_study(f"soak-{studies}", study_scene(), "particles.*.density=1.001,1.002",
                                    "fluid.relaxation_time=0.5,1")
                studies += 1
            if time.monotonic() >= next_restart:
                daemon.stop_process()
                time.sleep(2)
                daemon.start()
                next_restart += args.restart_minutes * 60
            if time.monotonic() >= next_sample:
                next_sample += 30
                code, _, body = web.request("GET", "/api/overview", headers={
                    "Authorization": "Bearer " + ws.Daemon.TOKEN})
                if code != 200:  # the daemon is restarting: sample a moment later
                    next_sample = time.monotonic() + 2
                    continue
                truth = json.loads(body)
                memory = web_memory(web)
                status = web.status()
                ids = overview_page.execute_script(
                    "return [...document.querySelectorAll('tr[data-study]')].map(r => r.dataset.study)")
                job_ids = study_page.execute_script(
                    "return [...document.querySelectorAll('#jobs-table tbody tr')].map(r => r.dataset.job)")
                heap = [b.execute_script("return performance.memory ? performance.memory.usedJSHeapSize : 0")
                        for b in (overview_page, study_page)]
                one_load = all(b.execute_script("return window.__one_load === true")
                               for b in (overview_page, study_page))
                expected = [s["id"] for s in truth["studies"]]
                row = {"minute": round((time.monotonic() - start) / 60, 2), "studies": studies,
                       "rss_kib": memory["VmRSS"], "threads": memory["Threads"], "fds": memory["fds"],
                       "live_pages": status["live_pages"], "watch_streams": status["watch_streams"],
                       "overview_rows": len(ids), "overview_unique": len(set(ids)),
                       "daemon_studies": len(expected), "study_rows": len(job_ids),
                       "study_unique": len(set(job_ids)), "heap_overview": heap[0],
                       "heap_study": heap[1], "one_load": one_load}
                rows.append(row)
                print(json.dumps(row), flush=True)
                write_csv(args.csv, rows)
                if len(ids) != len(set(ids)) or len(job_ids) != len(set(job_ids)) or len(job_ids) != 4:
                    failures.append(f"minute {row['minute']}: duplicate or missing rows {row}")
                if not one_load:
                    failures.append(f"minute {row['minute']}: a page reloaded")
                if set(ids) != set(expected):
                    # The page may be a fraction of a second behind: look again after 2 s.
                    time.sleep(2)
                    ids = overview_page.execute_script(
                        "return [...document.querySelectorAll('tr[data-study]')].map(r => r.dataset.study)")
                    expected = [s["id"] for s in json.loads(web.request("GET", "/api/overview", headers={
                        "Authorization": "Bearer " + ws.Daemon.TOKEN})[2])["studies"]]
                    if set(ids) != set(expected):
                        failures.append(f"minute {row['minute']}: the studies page shows {len(ids)} "
                                        f"studies, the daemon {len(expected)}")
            time.sleep(1)
    finally:
        for b in (overview_page, study_page):
            ws.stop_browser(b)
        web.stop()
        daemon.stop()
    write_csv(args.csv, rows)
    print(f"{len(rows)} samples written to {args.csv}; {len(failures)} failures")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
