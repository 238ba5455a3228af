"""Test support for the dashboard's tests (ctest label browser): a real dlmfdd on a free loopback
port (restartable on the same port), the real dlmfd-web in front of it, the real CLI to submit a
study, Debian's headless Chromium driven by Selenium, and a check that a screenshot is not blank.

The build tree comes from $DLMFD_BINARY_DIR (ctest sets it); the solver from $DLMFD_SOLVER_BINARY
when set, as for the other tests. Every process started here is stopped by its own stop().
"""

import http.client
import importlib.util
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

BINARY_DIR = os.environ.get("DLMFD_BINARY_DIR", "build")
SOLVER = os.environ.get("DLMFD_SOLVER_BINARY") or os.path.join(BINARY_DIR, "solver", "dlmfd-solve")
DAEMON = os.path.join(BINARY_DIR, "server", "dlmfdd")
WEB = os.path.join(BINARY_DIR, "web", "dlmfd-web")
CLI = os.path.join(BINARY_DIR, "client", "dlmfd")
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
SKIP = 77  # ctest's SKIP_RETURN_CODE

SANITIZER_MARKERS = ("ERROR: AddressSanitizer", "runtime error:", "WARNING: ThreadSanitizer",
                     "ERROR: LeakSanitizer")


def skip_unless_browser():
    """Exits with SKIP, naming the Debian packages, when Chromium, its driver or Selenium is
    missing (scripts/setup.sh installs them)."""
    missing = []
    if importlib.util.find_spec("selenium") is None:
        missing.append("python3-selenium")
    if importlib.util.find_spec("PIL") is None:
        missing.append("python3-pil")
    if not os.path.exists(CHROMIUM):
        missing.append("chromium")
    if not os.path.exists(CHROMEDRIVER):
        missing.append("chromium-driver")
    if missing:
        print(f"SKIPPED: missing Debian packages {', '.join(missing)} (scripts/setup.sh)")
        sys.exit(SKIP)


def wait_for(predicate, what, timeout):
    """Polls predicate until it returns a true value (returned); raises naming `what` after
    `timeout` seconds. The bounds are generous: the machine is shared and ctest runs tests side
    by side; they bound a hang, they are not measurements."""
    deadline = time.monotonic() + timeout
    last_error = None
    while time.monotonic() < deadline:
        try:
            value = predicate()
            if value:
                return value
        except Exception as error:  # noqa: BLE001 - the page may be between states
            last_error = error
        time.sleep(0.1)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}"
                         + (f" (last error: {last_error})" if last_error else ""))


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def study_scene():
    """One disk (diameter 0.25, density 1.01) in a closed 1 x 2 box of 16 x 32 cells of an
    Oldroyd-B liquid at the defaults; dt = 1e-3, about 0.18 ms a step on an idle core: 18 s of run
    to t = 100, 180 s to t = 1000. Progress events then come many times a second, which the pages
    must take without swallowing a click (they update their tables in place)."""
    return ("title = \"dashboard test\"\n"
            "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
            "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = 0.5\n"
            "solvent_ratio = 0.5\ngravity = [0.0, -981.0]\n"
            "[time]\ndt = 0.001\nend = 1.0\n"
            "[particle_mesh]\nh = 0.08571428571428572\n"
            "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.01\n"
            "[output]\nfields_every = 0.1\nparticles_every = 0.01\ncheckpoint_every = 0.5\n")


class Daemon:
    """A real dlmfdd on 127.0.0.1 with a data directory of its own; with `token`, a tokens file
    of two users (alice: TOKEN, bob: OTHER_TOKEN)."""

    TOKEN = "alice-dashboard-token-0123456789"
    OTHER_TOKEN = "bob-dashboard-token-9876543210"

    def __init__(self, tokens=True, max_concurrent=2):
        self.dir = tempfile.mkdtemp(prefix="dlmfd-web-test-")
        self.tokens = None
        if tokens:
            self.tokens = os.path.join(self.dir, "tokens")
            with open(self.tokens, "w") as f:
                f.write(f"{self.TOKEN} alice\n{self.OTHER_TOKEN} bob\n")
            os.chmod(self.tokens, 0o600)
        self.max_concurrent = max_concurrent
        self.port = 0
        self.logs = []
        self.process = None
        self.start()

    def start(self):
        """Starts the daemon (again, on the same port and data directory after a stop)."""
        port_file = os.path.join(self.dir, "port")
        if os.path.exists(port_file):
            os.remove(port_file)
        log = open(os.path.join(self.dir, f"daemon{len(self.logs)}.log"), "w")
        self.logs.append(log)
        args = [DAEMON, "--listen", f"127.0.0.1:{self.port}", "--data-dir",
                os.path.join(self.dir, "data"), "--port-file", port_file, "--solver", SOLVER,
                "--solver-threads", "1", "--max-concurrent", str(self.max_concurrent)]
        if self.tokens:
            args += ["--tokens-file", self.tokens]
        self.process = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT)

        def bound():
            if self.process.poll() is not None:
                raise RuntimeError(f"dlmfdd exited with {self.process.returncode}: {self.log_text()}")
            if os.path.exists(port_file):
                with open(port_file) as f:
                    text = f.read().strip()
                return text.isdigit() and int(text) > 0 and int(text)
            return False
        self.port = wait_for(bound, "dlmfdd to listen", 60)
        self.address = f"127.0.0.1:{self.port}"

    def log_text(self):
        text = ""
        for log in self.logs:
            log.flush()
            with open(log.name) as f:
                text += f.read()
        return text

    def cli(self, *args, token=None, exit_codes=(0,)):
        """Runs the real CLI against this daemon; returns its stdout (raises on another exit
        status than those given)."""
        env = dict(os.environ, DLMFD_SERVER=self.address, XDG_CONFIG_HOME=self.dir)
        env.pop("DLMFD_TOKEN", None)
        if token or (self.tokens and token is None):
            env["DLMFD_TOKEN"] = token or self.TOKEN
        result = subprocess.run([CLI, *args], env=env, capture_output=True, text=True)
        if result.returncode not in exit_codes:
            raise RuntimeError(f"dlmfd {' '.join(args)}: exit {result.returncode}: {result.stderr}")
        return result.stdout

    def submit_study(self, name, scene, *axes, token=None, extra=()):
        path = os.path.join(self.dir, name + ".toml")
        with open(path, "w") as f:
            f.write(scene)
        grid = [a for axis in axes for a in ("--grid", axis)]
        return self.cli("study", path, *grid, "--name", name, "-q", *extra, token=token).strip()

    def stop_process(self):
        """SIGTERM, as a user stops it (solvers checkpoint; running jobs resume at the next start)."""
        if self.process and self.process.poll() is None:
            self.process.terminate()
            self.process.wait()

    def stop(self):
        """Stops the daemon, removes its directory; returns its sanitizer reports ("" if none)."""
        self.stop_process()
        log = self.log_text()
        for f in self.logs:
            f.close()
        shutil.rmtree(self.dir, ignore_errors=True)
        return log if any(m in log for m in SANITIZER_MARKERS) else ""


class Web:
    """The real dlmfd-web on a free loopback port, in front of `daemon`."""

    def __init__(self, daemon, *extra):
        self.dir = tempfile.mkdtemp(prefix="dlmfd-web-process-")
        port_file = os.path.join(self.dir, "port")
        self.log = open(os.path.join(self.dir, "web.log"), "w")
        env = dict(os.environ, XDG_CONFIG_HOME=self.dir)
        env.pop("DLMFD_SERVER", None)
        self.process = subprocess.Popen(
            [WEB, "--listen", "127.0.0.1:0", "--server", daemon.address, "--port-file", port_file,
             *extra], stdout=self.log, stderr=subprocess.STDOUT, env=env)

        def bound():
            if self.process.poll() is not None:
                raise RuntimeError(f"dlmfd-web exited with {self.process.returncode}: {self.log_text()}")
            if os.path.exists(port_file):
                with open(port_file) as f:
                    text = f.read().strip()
                return text.isdigit() and int(text)
            return False
        self.port = wait_for(bound, "dlmfd-web to listen", 60)
        self.url = f"http://127.0.0.1:{self.port}"

    def log_text(self):
        self.log.flush()
        with open(self.log.name) as f:
            return f.read()

    def request(self, method, path, body=None, headers=None):
        """One HTTP request; returns (status, headers dict (lower-case names), body bytes)."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        try:
            all_headers = {"Host": f"127.0.0.1:{self.port}"}
            all_headers.update(headers or {})
            if isinstance(body, (dict, list)):
                body = json.dumps(body)
                all_headers.setdefault("Content-Type", "application/json")
            connection.request(method, path, body=body, headers=all_headers)
            response = connection.getresponse()
            data = response.read()
            return response.status, {k.lower(): v for k, v in response.getheaders()}, data
        finally:
            connection.close()

    def status(self, token=Daemon.TOKEN):
        """/api/status: the live pages and Watch streams the web process holds now."""
        code, _, body = self.request("GET", "/api/status", headers={"Authorization": "Bearer " + token})
        if code != 200:
            raise AssertionError(f"/api/status answered {code}: {body!r}")
        data = json.loads(body)
        return {"live_pages": data["live_pages"], "watch_streams": data["watch_streams"]}

    def stop(self):
        """SIGTERM; returns (exit status, sanitizer reports or "")."""
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=60)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
                raise AssertionError("dlmfd-web did not stop within 60 s of SIGTERM:\n" + self.log_text())
        log = self.log_text()
        self.log.close()
        shutil.rmtree(self.dir, ignore_errors=True)
        return self.process.returncode, (log if any(m in log for m in SANITIZER_MARKERS) else "")


def start_browser(width=1400, height=1000):
    """Debian's Chromium, headless, with a new empty profile and no network of its own."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    profile = tempfile.mkdtemp(prefix="dlmfd-chromium-")
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--disable-dev-shm-usage", f"--user-data-dir={profile}",
                f"--window-size={width},{height}"]:
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.profile_dir = profile
    return driver


def stop_browser(driver):
    try:
        driver.quit()
    finally:
        shutil.rmtree(driver.profile_dir, ignore_errors=True)


def assert_not_blank(path, what):
    """A screenshot shows a page: at least 2 % of its pixels are not the background colour, and it
    has at least 16 distinct colours (text, bars, badges, pictures)."""
    from PIL import Image
    image = Image.open(path).convert("RGB")
    small = image.resize((image.width // 2, image.height // 2))
    pixels = list(small.getdata())
    background = max(set(pixels[::97]), key=pixels[::97].count)
    share = sum(1 for p in pixels if p != background) / len(pixels)
    colours = len(set(pixels))
    if share < 0.02 or colours < 16:
        raise AssertionError(f"{what}: the screenshot {path} looks blank ({share:.1%} of pixels "
                             f"differ from the background, {colours} colours)")
    return share, colours
