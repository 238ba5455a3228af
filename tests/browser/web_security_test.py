"""The dashboard's security rules over HTTP (issue 36, point 3), against the real dlmfd-web and a
real dlmfdd with two users' tokens: no user, no data; a token is taken only by the daemon's
word; the session cookie is HttpOnly and SameSite=Strict and the token never reaches the browser;
a state-changing request without the session's CSRF token, or from another site's Origin, is
refused; another user's job and study answer 404 as missing ones do, for data, pictures, files,
events and actions; paths outside a job are refused; a foreign Host header is refused (DNS
rebinding); bad requests get clear 4xx errors; the process keeps serving through all of it; and
the start rules (a non-loopback address without TLS, bad flags) refuse to start.

Run by ctest (label browser) as `python3 web_security_test.py`.
"""

import json
import os
import subprocess
import unittest
import urllib.parse

import web_support as ws


def tiny_scene():
    return ws.study_scene().replace("end = 1.0", "end = 0.05")


class WebSecurityTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.daemon = ws.Daemon(tokens=True, max_concurrent=2)
        cls.web = ws.Web(cls.daemon)
        cls.study = cls.daemon.submit_study("alice-study", tiny_scene(), "particles.*.density=1.01,1.02")
        cls.job = cls.daemon.cli("list", "--study", cls.study, "-q").split()[0]
        cls.daemon.cli("watch", "--study", cls.study)  # both points end (files to serve)

    @classmethod
    def tearDownClass(cls):
        status, web_reports = cls.web.stop()
        daemon_reports = cls.daemon.stop()
        if web_reports or daemon_reports:
            raise AssertionError("sanitizer reports:\n" + web_reports + daemon_reports)
        if status != 0:
            raise AssertionError(f"dlmfd-web exited with {status} on SIGTERM")

    def login(self, token):
        """Signs in by the form; returns (cookie header, csrf token)."""
        code, headers, _ = self.web.request(
            "POST", "/login", body=urllib.parse.urlencode({"token": token}),
            headers={"Content-Type": "application/x-www-form-urlencoded"})
        self.assertEqual(code, 303)
        self.assertEqual(headers.get("location"), "/")
        cookie = headers["set-cookie"]
        self.assertIn("HttpOnly", cookie)
        self.assertIn("SameSite=Strict", cookie)
        self.assertNotIn(token, cookie)
        pair = cookie.split(";")[0]
        code, _, body = self.web.request("GET", "/api/session", headers={"Cookie": pair})
        self.assertEqual(code, 200)
        session = json.loads(body)
        self.assertNotIn(token, body.decode())
        return pair, session["csrf"]

    def error_of(self, body):
        data = json.loads(body)
        self.assertIn("error", data)
        return data["error"]

    def test_no_user_no_data(self):
        for path in ["/api/overview", f"/api/jobs/{self.job}", f"/events/jobs/{self.job}",
                     f"/files/jobs/{self.job}/summary.json", f"/pictures/jobs/{self.job}/field.png"]:
            code, _, body = self.web.request("GET", path)
            self.assertEqual(code, 401, path)
            self.assertIn("sign in", self.error_of(body))
        code, headers, _ = self.web.request("GET", "/")
        self.assertEqual(code, 303)
        self.assertEqual(headers["location"], "/login")
        code, _, _ = self.web.request("GET", "/login")
        self.assertEqual(code, 200)

    def test_a_wrong_token_is_refused_and_a_right_one_signs_in(self):
        code, headers, _ = self.web.request(
            "POST", "/login", body="token=not-a-token-of-anyone-0000",
            headers={"Content-Type": "application/x-www-form-urlencoded"})
        self.assertEqual(code, 303)
        self.assertEqual(headers["location"], "/login?error=rejected")
        self.assertNotIn("set-cookie", headers)
        code, _, _ = self.web.request("GET", "/api/overview",
                                      headers={"Authorization": "Bearer not-a-token-of-anyone-0000"})
        self.assertEqual(code, 401)
        cookie, _ = self.login(ws.Daemon.TOKEN)
        code, _, body = self.web.request("GET", "/api/overview", headers={"Cookie": cookie})
        self.assertEqual(code, 200)
        self.assertEqual([s["id"] for s in json.loads(body)["studies"]], [self.study])

    def test_state_changes_need_the_csrf_token_and_this_origin(self):
        cookie, csrf = self.login(ws.Daemon.TOKEN)
        path = f"/api/jobs/{self.job}/retry"
        code, _, body = self.web.request("POST", path, headers={"Cookie": cookie})
        self.assertEqual(code, 403)
        self.assertIn("CSRF", self.error_of(body))
        code, _, _ = self.web.request("POST", path, headers={"Cookie": cookie, "X-CSRF-Token": "0" * 64})
        self.assertEqual(code, 403)
        code, _, body = self.web.request("POST", path, headers={
            "Cookie": cookie, "X-CSRF-Token": csrf, "Origin": "http://evil.example"})
        self.assertEqual(code, 403)
        self.assertIn("another site", self.error_of(body))
        # A cross-site form post of a token to /login is refused too.
        code, _, _ = self.web.request("POST", "/login", body="token=" + ws.Daemon.TOKEN, headers={
            "Content-Type": "application/x-www-form-urlencoded", "Origin": "http://evil.example"})
        self.assertEqual(code, 403)
        # Deletion needs the confirmation in the body.
        code, _, body = self.web.request("POST", f"/api/jobs/{self.job}/delete", body={},
                                         headers={"Cookie": cookie, "X-CSRF-Token": csrf})
        self.assertEqual(code, 400)
        self.assertIn("confirm", self.error_of(body))
        # With the token, from this origin: the daemon answers (the job has finished: hold is 409).
        code, _, body = self.web.request("POST", f"/api/jobs/{self.job}/hold", headers={
            "Cookie": cookie, "X-CSRF-Token": csrf, "Origin": self.web.url})
        self.assertEqual(code, 409, body)
        self.assertIn("failed precondition", self.error_of(body))

    def test_hold_and_release_a_queued_job(self):
        # A study of two long points, one running at a time: the second waits, QUEUED.
        study = self.daemon.submit_study("hold-study", ws.study_scene().replace("end = 1.0", "end = 1000.0"),
                                         "particles.*.density=1.001,1.002", extra=("--max-running", "1"))
        try:
            cookie, csrf = self.login(ws.Daemon.TOKEN)
            headers = {"Cookie": cookie, "X-CSRF-Token": csrf}
            queued = ws.wait_for(lambda: self.daemon.cli("list", "--study", study, "--state", "queued", "-q").split(),
                                 "a queued point", 60)[0]
            code, _, body = self.web.request("POST", f"/api/jobs/{queued}/hold", headers=headers)
            self.assertEqual(code, 200, body)
            self.assertTrue(json.loads(body)["held"])
            self.assertIn('"held":true', self.daemon.cli("show", queued, "--json").replace(" ", ""))
            code, _, body = self.web.request("POST", f"/api/jobs/{queued}/release", headers=headers)
            self.assertEqual(code, 200, body)
            self.assertFalse(json.loads(body)["held"])
            code, _, body = self.web.request("POST", f"/api/studies/{study}/cancel", headers=headers)
            self.assertEqual(code, 200, body)
            self.assertTrue(all(j["state"] in ("CANCELLED", "RUNNING") for j in json.loads(body)["jobs"]))
        finally:
            self.daemon.cli("cancel", "--study", study)
            self.daemon.cli("watch", "--study", study, exit_codes=(0, 1))  # 1: some cancelled

    def test_another_users_job_and_study_are_not_found(self):
        bob = {"Authorization": "Bearer " + ws.Daemon.OTHER_TOKEN}
        for method, path in [("GET", f"/api/jobs/{self.job}"), ("GET", f"/api/studies/{self.study}"),
                             ("GET", f"/api/jobs/{self.job}/files"), ("GET", f"/api/jobs/{self.job}/log"),
                             ("GET", f"/api/jobs/{self.job}/particles"),
                             ("GET", f"/pictures/jobs/{self.job}/field.png"),
                             ("GET", f"/pictures/studies/{self.study}/chart.png?x=particles.*.density&y=steps"),
                             ("GET", f"/files/jobs/{self.job}/summary.json"),
                             ("GET", f"/events/jobs/{self.job}"), ("GET", f"/events/studies/{self.study}"),
                             ("POST", f"/api/jobs/{self.job}/retry"), ("POST", f"/api/jobs/{self.job}/cancel"),
                             ("POST", f"/api/studies/{self.study}/retry")]:
            code, _, body = self.web.request(method, path, headers=bob)
            self.assertEqual(code, 404, f"{method} {path}: {body!r}")
            self.assertIn("not found", self.error_of(body))
        code, _, body = self.web.request("POST", f"/api/jobs/{self.job}/delete",
                                         body={"confirm": self.job}, headers=bob)
        self.assertEqual(code, 404)
        # Alice still has it, and bob's overview is empty.
        alice = {"Authorization": "Bearer " + ws.Daemon.TOKEN}
        self.assertEqual(self.web.request("GET", f"/api/jobs/{self.job}", headers=alice)[0], 200)
        self.assertEqual(json.loads(self.web.request("GET", "/api/overview", headers=bob)[2])["studies"], [])

    def test_only_files_inside_a_job_are_served(self):
        alice = {"Authorization": "Bearer " + ws.Daemon.TOKEN}
        code, headers, body = self.web.request("GET", f"/files/jobs/{self.job}/summary.json", headers=alice)
        self.assertEqual(code, 200)
        self.assertEqual(json.loads(body)["status"], "completed")
        self.assertIn("attachment", headers["content-disposition"])
        for path in ["..%2F..%2Fjobs.db", "../../jobs.db", "%2Fetc%2Fpasswd", "fields/..%2F..%2Fscene.in.toml",
                     "a%00b", "./summary.json", "fields//snap.h5"]:
            code, _, body = self.web.request("GET", f"/files/jobs/{self.job}/{path}", headers=alice)
            self.assertIn(code, (400, 404), path)
            self.assertTrue(self.error_of(body), path)
        code, _, body = self.web.request("GET", f"/files/jobs/{self.job}/no-such-file.h5", headers=alice)
        self.assertEqual(code, 404)

    def test_a_foreign_host_is_refused(self):
        code, _, body = self.web.request("GET", "/api/overview", headers={
            "Host": f"evil.example:{self.web.port}", "Authorization": "Bearer " + ws.Daemon.TOKEN})
        self.assertEqual(code, 421)
        self.assertIn("not this server", self.error_of(body))
        code, _, _ = self.web.request("GET", "/login", headers={"Host": f"localhost:{self.web.port}"})
        self.assertEqual(code, 200)

    def test_bad_requests_get_clear_errors_and_the_process_keeps_serving(self):
        alice = {"Authorization": "Bearer " + ws.Daemon.TOKEN}
        cases = [
            ("GET", "/api/jobs/j-does-not-exist", None, 404, "not found"),
            ("GET", f"/api/jobs/{self.job}/log?offset=-5", None, 400, "offset"),
            ("GET", f"/api/jobs/{self.job}/log?offset=abc", None, 400, "offset"),
            ("GET", f"/pictures/jobs/{self.job}/field.png?width=5", None, 400, "width"),
            ("GET", f"/pictures/studies/{self.study}/chart.png?x=nope&y=steps", None, 400, "no such column"),
            ("GET", f"/pictures/studies/{self.study}/chart.png", None, 400, "x and y"),
            ("GET", "/api/jobs/bad%20id", None, 404, "no such page"),
            ("GET", "/no/such/page", None, 404, "no such page"),
            ("POST", f"/api/jobs/{self.job}/delete", "{not json", 400, "JSON object"),
            ("POST", f"/api/jobs/{self.job}/delete", "[1, 2]", 400, "JSON object"),
            ("POST", f"/api/jobs/{self.job}/cancel", None, 409, "failed precondition"),
        ]
        for method, path, body, status, words in cases:
            code, headers, data = self.web.request(method, path, body=body, headers=dict(alice))
            self.assertEqual(code, status, f"{method} {path}: {data!r}")
            self.assertIn(words, self.error_of(data), f"{method} {path}")
            self.assertIn("default-src 'none'", headers.get("content-security-policy", ""))
        code, _, _ = self.web.request("POST", "/api/overview", body="x" * (2 << 20), headers=dict(alice))
        self.assertIn(code, (404, 413))
        code, _, _ = self.web.request("GET", "/api/overview", headers=alice)
        self.assertEqual(code, 200)

    def test_https_with_a_certificate(self):
        """--tls-cert/--tls-key serve HTTPS (here on loopback, with a self-signed certificate made
        by openssl); the session cookie is then Secure too."""
        import ssl
        import http.client
        import shutil
        import tempfile
        if shutil.which("openssl") is None:
            self.skipTest("no openssl command (Debian: openssl)")
        folder = tempfile.mkdtemp(prefix="dlmfd-web-tls-")
        try:
            cert, key = os.path.join(folder, "cert.pem"), os.path.join(folder, "key.pem")
            subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1",
                            "-subj", "/CN=127.0.0.1", "-addext", "subjectAltName=IP:127.0.0.1",
                            "-keyout", key, "-out", cert], check=True, capture_output=True)
            web = ws.Web(self.daemon, "--tls-cert", cert, "--tls-key", key)
            try:
                context = ssl.create_default_context(cafile=cert)
                connection = http.client.HTTPSConnection("127.0.0.1", web.port, context=context, timeout=60)
                connection.request("POST", "/login", body="token=" + ws.Daemon.TOKEN, headers={
                    "Host": f"127.0.0.1:{web.port}", "Content-Type": "application/x-www-form-urlencoded"})
                response = connection.getresponse()
                response.read()
                self.assertEqual(response.status, 303)
                cookie = response.getheader("Set-Cookie")
                self.assertIn("Secure", cookie)
                self.assertIn("HttpOnly", cookie)
                connection.close()
                # Plain HTTP to the HTTPS port gets no page.
                with self.assertRaises(Exception):
                    code, _, _ = web.request("GET", "/login")
                    if code == 200:
                        raise AssertionError("plain HTTP served")
                    raise ConnectionError(code)
            finally:
                status, reports = web.stop()
                self.assertEqual(status, 0)
                self.assertEqual(reports, "")
            # Beyond loopback, even with TLS, a daemon that takes calls without a token is refused.
            tokenless = ws.Daemon(tokens=False)
            try:
                env = dict(os.environ)
                env.pop("DLMFD_WEB_LISTEN", None)
                result = subprocess.run([ws.WEB, "--server", tokenless.address, "--listen", "0.0.0.0:0",
                                         "--tls-cert", cert, "--tls-key", key], env=env,
                                        capture_output=True, text=True, timeout=60)
                self.assertEqual(result.returncode, 2)
                self.assertIn("takes calls without a token", result.stderr)
            finally:
                tokenless.stop()
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def test_start_rules(self):
        def start(*args):
            env = dict(os.environ)
            env.pop("DLMFD_WEB_LISTEN", None)
            return subprocess.run([ws.WEB, "--server", self.daemon.address, *args], env=env,
                                  capture_output=True, text=True, timeout=60)
        result = start("--listen", "0.0.0.0:0")
        self.assertEqual(result.returncode, 2)
        self.assertIn("not a loopback address and no TLS", result.stderr)
        result = start("--listen", "127.0.0.1:99999")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--listen", result.stderr)
        result = start("--listen", "127.0.0.1:0", "--tls-cert", "/nonexistent.pem")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--tls-key", result.stderr)
        result = start("--listen", f"127.0.0.1:{self.web.port}")
        self.assertEqual(result.returncode, 1)
        self.assertIn("cannot listen", result.stderr)


if __name__ == "__main__":
    unittest.main()
