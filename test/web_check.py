#!/usr/bin/env python3
"""test/web_check.py -- the page (web/) in a real browser against afv run.

make test-web runs it.  It serves web/ on 127.0.0.1 (an ephemeral port),
starts Debian's chromium headless and drives it through the DevTools
protocol over a pipe (--remote-debugging-pipe: JSON messages ended by NUL
on file descriptors 3 and 4; no websocket, no driver to install).  For each
preset it clicks the page's code path (afvPage.preset, what the button
calls), reads the numbers after the relaxation and after 1000 steps, and
compares them bit for bit with afv run's observables.csv for the same keys
(the detachment preset at dt 0.01 also every 1000 steps to LONG_STEPS);
it saves a screenshot per preset into OUT.  It fails on a JavaScript error
(page or worker), a blank canvas, a number that is not finite, a control
that is not clamped, or a non-finite state that the page does not stop and
name.  It prints the frame rate at N = 400 (a measurement, not a test).

Usage: test/web_check.py --afv ./afv --web web --out out/web
"""
import argparse
import base64
import functools
import http.server
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

# Relaxation steps of the test's runs (the page and afv run alike).  afv
# run's default (100000) for three presets, whose relaxation stops at a
# kink after 5000 to 7000 steps; the two at P0 8.8 never converge and would
# take all 100000 steps (about 30 s each), the one at dt 0.0025 takes 18000:
# the test stops those at 2000 and 5000, to stay under a minute.
FULL_RELAX = 100000
SHORT_RELAX = 2000
SMALL_DT_RELAX = 5000
PRESETS = [  # name on the page, afv run's keys, relax_max_steps
    ("clustered-epithelial", {"P0": 4, "v0": 0.1, "dt": 0.01}, FULL_RELAX),
    ("clustered-mesenchymal", {"P0": 8.8, "v0": 0.1, "dt": 0.01}, SHORT_RELAX),
    ("dispersed-epithelial", {"P0": 4.4, "v0": 2.6, "dt": 0.01}, FULL_RELAX),
    ("dispersed-mesenchymal", {"P0": 8.8, "v0": 2.6, "dt": 0.01}, SHORT_RELAX),
    ("detach-dt-0.01", {"P0": 4, "v0": 1.85, "dt": 0.01}, FULL_RELAX),
    ("detach-dt-0.0025", {"P0": 4, "v0": 1.85, "dt": 0.0025}, SMALL_DT_RELAX),
]
STEPS = 1000
# Longer, against the plain afv run (doc/web.md, "Same numbers"): every
# 1000 steps up to LONG_STEPS.  The noise's log and the library's other
# libm functions are its own (fastmath.h), so the page (wasi-libc) and afv
# run (glibc, which on a CPU with FMA uses an FMA variant of its log) give
# the same bits; with the C library's log (afv 0.4.0) they parted after
# 2000 to 11000 steps.
LONG_PRESET, LONG_STEPS = "detach-dt-0.01", 20000
# observables.csv's columns and the page's web_observe indices (OBS)
COMPARED = [("energy", "energy"), ("ngc_frac", "giant"), ("omega", "omega"),
            ("n_clusters", "clusters")]
TIMEOUT = 120          # seconds for one browser call
RUNAWAY_LAMBDA = "1e20"  # a runaway step: the page must stop and say where


class Fail(Exception):
    pass


# ---- afv run ---------------------------------------------------------------
def afv_run(afv, tmp, name, keys, relax, steps):
    """afv run of a preset, started (it runs while the browser works):
    (process, directory, command)."""
    out = os.path.join(tmp, "run-%s-%d" % (name, steps))
    cmd = [afv, "run", "--N", "400", "--seed", "1", "--steps", str(steps),
           "--relax_max_steps", str(relax), "--sample_every", str(STEPS),
           "--frame_every", "0", "--checkpoint_every", "0",
           "--svg_every", "0", "--quiet", "1", "--out", out]
    for k, v in keys.items():
        cmd += ["--" + k, repr(v)]
    return subprocess.Popen(cmd), out, " ".join(cmd)


def start_afv_runs(afv, tmp):
    """afv run of every preset (LONG_PRESET for LONG_STEPS): {name: run}."""
    return {name: afv_run(afv, tmp, name, keys, relax,
                          LONG_STEPS if name == LONG_PRESET else STEPS)
            for name, keys, relax in PRESETS}


def afv_rows(run):
    """observables.csv of a finished run: {step: {column: float}}."""
    proc, out, cmd = run
    if proc.wait() != 0:
        raise Fail("%s: exit status %d" % (cmd, proc.returncode))
    with open(os.path.join(out, "observables.csv")) as f:
        head = f.readline().strip().split(",")
        rows = [dict(zip(head, map(float, line.split(",")))) for line in f]
    return {int(r["step"]): r for r in rows}


# ---- the server ------------------------------------------------------------
def serve(web):
    handler = functools.partial(Quiet, directory=web)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


class Quiet(http.server.SimpleHTTPRequestHandler):
    extensions_map = dict(http.server.SimpleHTTPRequestHandler.extensions_map,
                          **{".wasm": "application/wasm"})

    def log_message(self, *args):
        pass


# ---- the browser: DevTools protocol over a pipe -----------------------------
class Browser:
    def __init__(self, chromium, profile):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()
        # the browser reads commands on fd 3 and writes answers on fd 4
        def fds():
            os.dup2(to_browser_r, 3)
            os.dup2(from_browser_w, 4)
        self.proc = subprocess.Popen(
            [chromium, "--headless=new", "--remote-debugging-pipe",
             "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--no-default-browser-check", "--user-data-dir=" + profile,
             "--window-size=1120,900", "about:blank"],
            preexec_fn=fds, pass_fds=(3, 4),
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.buf = b""
        self.next_id = 0
        self.events = []
        self.session = None

    def send(self, method, params=None, session=True):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(msg).encode() + b"\0")
        deadline = time.time() + TIMEOUT
        while time.time() < deadline:
            m = self.read()
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise Fail("%s: %s" % (method, m["error"]))
                return m["result"]
            self.events.append(m)
        raise Fail("%s: no answer in %d s" % (method, TIMEOUT))

    def read(self):
        while b"\0" not in self.buf:
            chunk = os.read(self.from_browser, 1 << 20)
            if not chunk:
                raise Fail("chromium closed its pipe")
            self.buf += chunk
        line, self.buf = self.buf.split(b"\0", 1)
        return json.loads(line)

    def js(self, expr):
        """The value of a JavaScript expression (awaited if a promise)."""
        r = self.send("Runtime.evaluate", {"expression": expr,
                      "awaitPromise": True, "returnByValue": True})
        if "exceptionDetails" in r:
            raise Fail("%s: %s" % (expr, r["exceptionDetails"].get(
                "exception", {}).get("description", r["exceptionDetails"])))
        return r["result"].get("value")

    def errors(self):
        """JavaScript errors so far: uncaught exceptions, console.error and
        the browser's error log (a failed load, a worker's error)."""
        found = []
        for m in self.events:
            p = m.get("params", {})
            if m.get("method") == "Runtime.exceptionThrown":
                d = p["exceptionDetails"]
                found.append(d.get("exception", {}).get("description")
                             or d.get("text"))
            elif (m.get("method") == "Runtime.consoleAPICalled"
                  and p.get("type") == "error"):
                found.append(" ".join(str(a.get("value", a.get("description")))
                                      for a in p.get("args", [])))
            elif (m.get("method") == "Log.entryAdded"
                  and p["entry"].get("level") == "error"):
                found.append(p["entry"].get("text"))
        return found

    def close(self):
        self.proc.kill()
        self.proc.wait()


def open_page(browser, url):
    target = browser.send("Target.createTarget", {"url": "about:blank"},
                          session=False)["targetId"]
    browser.session = browser.send("Target.attachToTarget", {
        "targetId": target, "flatten": True}, session=False)["sessionId"]
    for domain in ("Runtime", "Page", "Log"):
        browser.send(domain + ".enable")
    browser.send("Emulation.setDeviceMetricsOverride", {
        "width": 1100, "height": 860, "deviceScaleFactor": 1, "mobile": False})
    browser.send("Page.navigate", {"url": url})
    deadline = time.time() + TIMEOUT
    while not browser.js("!!(window.afvPage && afvPage.state().obs)"):
        if time.time() > deadline:
            raise Fail("the page did not show a tissue in %d s" % TIMEOUT)
        time.sleep(0.2)


CANVAS_INK = """(() => {
  const c = document.getElementById('tissue'), g = c.getContext('2d');
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let ink = 0; const colours = new Set();
  for (let k = 0; k < d.length; k += 4 * 97) {
    if (d[k] < 250 || d[k + 1] < 250 || d[k + 2] < 250) ink++;
    colours.add((d[k] << 16) | (d[k + 1] << 8) | d[k + 2]);
  }
  return {ink: ink / (d.length / (4 * 97)), colours: colours.size};
})()"""


def check_state(browser, what):
    """The page's numbers now; fails on a blank canvas, a NaN, an error."""
    st = browser.js("afvPage.state()")
    obs = st["obs"]
    idx = browser.js("afvPage.obsIndex")
    if st["broken"]:
        raise Fail("%s: the page stopped: %s" % (what, st["status"]))
    for key in ("energy", "giant", "omega", "clusters"):
        if obs[idx[key]] is None or not math.isfinite(obs[idx[key]]):
            raise Fail("%s: %s is %r" % (what, key, obs[idx[key]]))
    shown = browser.js("['r-energy','r-giant','r-omega','r-clusters']"
                       ".map((id) => document.getElementById(id).textContent)")
    if any(not math.isfinite(float(t)) for t in shown):
        raise Fail("%s: a readout is not a finite number: %s" % (what, shown))
    ink = browser.js(CANVAS_INK)
    if ink["ink"] < 0.05 or ink["colours"] < 3:
        raise Fail("%s: blank canvas (%.1f%% inked, %d colours)"
                   % (what, 100 * ink["ink"], ink["colours"]))
    errs = browser.errors()
    if errs:
        raise Fail("%s: JavaScript error: %s" % (what, errs[0]))
    return {key: obs[idx[key]] for key in idx if key != "count"}


def compare(name, when, page, row):
    """Bit-for-bit equality of the page's numbers with afv run's row."""
    bad = []
    for column, key in COMPARED:
        if page[key] != row[column]:
            bad.append("%s: page %r, afv run %r" % (column, page[key],
                                                    row[column]))
    if bad:
        raise Fail("%s, %s: %s" % (name, when, "; ".join(bad)))
    print("  %-22s %s:\n    E %.17g  N_GC/N %.17g  Omega %.17g  clusters %d: "
          "the same bits as afv run" % (name, when, page["energy"],
                                        page["giant"], page["omega"],
                                        page["clusters"]))


def screenshot(browser, path):
    data = browser.send("Page.captureScreenshot", {"format": "png"})["data"]
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(base64.b64decode(data))
    os.replace(tmp, path)


def check_presets(browser, runs, out):
    for name, keys, relax in PRESETS:
        browser.js("afvPage.preset(%s, {start: false, relax_max_steps: %d})"
                   ".then(() => 0)" % (json.dumps(name), relax))
        after_relax = check_state(browser, name + " after relaxation")
        browser.js("afvPage.run(%d).then(() => 0)" % STEPS)
        after_steps = check_state(browser, name + " after %d steps" % STEPS)
        screenshot(browser, os.path.join(out, name + ".png"))
        rows = afv_rows(runs[name])
        compare(name, "after relaxation", after_relax, rows[0])
        compare(name, "after %d steps" % STEPS, after_steps, rows[STEPS])
        if name == LONG_PRESET:
            for step in range(2 * STEPS, LONG_STEPS + 1, STEPS):
                browser.js("afvPage.run(%d).then(() => 0)" % STEPS)
                when = "after %d steps" % step
                compare(name, when, check_state(browser, name + " " + when),
                        rows[step])


def check_bad_input(browser):
    """Clamping with its reason; a runaway state stops the page and names
    the cell and the step; Reset recovers."""
    def set_control(name, text):
        browser.js("(() => { const e = document.getElementById(%s); e.value = %s;"
                   " e.dispatchEvent(new Event('change')); return 0; })()"
                   % (json.dumps(name), json.dumps(text)))
        return browser.js("[document.getElementById(%s).value, "
                          "document.getElementById(%s).textContent]"
                          % (json.dumps(name), json.dumps(name + "-why")))
    browser.js("afvPage.preset('clustered-epithelial', {start: false, "
               "relax_max_steps: 200}).then(() => 0)")
    for name, text, want in (("P0", "-1", "0.001"), ("cap", "-0.5", "0"),
                             ("N", "5000", "400"), ("N", "2", "3"),
                             ("dt", "abc", "0.01")):
        value, why = set_control(name, text)
        if value != want or not why:
            raise Fail("%s = %s: the page shows %r (reason %r), wanted %s "
                       "with a reason" % (name, text, value, why, want))
        print("  %s = %-5s -> %-6s %s" % (name, text, value, why))
    # a Lambda that afv run accepts (1e300 it refuses: the sums of the
    # energy could overflow) but whose force moves a cell 1e18 l in a step
    set_control("Lambda", RUNAWAY_LAMBDA)
    browser.js("afvPage.run(1).then(() => 0)")
    st = browser.js("afvPage.state()")
    if not st["broken"] or "cell" not in st["status"] \
            or "step 1" not in st["status"]:
        raise Fail("Lambda %s: the page did not stop naming the cell and "
                   "step: %r" % (RUNAWAY_LAMBDA, st["status"]))
    print("  Lambda = %s: %s" % (RUNAWAY_LAMBDA, st["status"]))
    set_control("Lambda", "0.2")
    browser.js("afvPage.reset({relax_max_steps: 200}).then(() => 0)")
    check_state(browser, "Reset after the runaway")
    print("  Reset: recovered (%s)" % browser.js("afvPage.state().status"))


def measure_fps(browser, steps_per_frame=10, seconds=3.0):
    """Frames per second after a click on a preset's button (which relaxes
    the tissue, then runs it): a measurement, printed, not a test."""
    browser.js("(() => { const e = document.getElementById('spf'); e.value = "
               "'%d'; e.dispatchEvent(new Event('change')); document."
               "getElementById('preset-clustered-epithelial').click(); "
               "return 0; })()" % steps_per_frame)
    deadline = time.time() + TIMEOUT
    while not browser.js("afvPage.state().running"):
        if time.time() > deadline:
            raise Fail("the preset's button did not start the tissue")
        time.sleep(0.2)
    time.sleep(seconds)
    st = browser.js("afvPage.state()")
    browser.js("afvPage.pause()")
    check_state(browser, "running at %d steps per frame" % steps_per_frame)
    return st["fps"], st["perFrame"]


def doc_screenshot(browser, path, seconds=12.0):
    """The picture of doc/web.md: the dispersed epithelial phase, running."""
    browser.send("Emulation.setDeviceMetricsOverride", {
        "width": 1100, "height": 960, "deviceScaleFactor": 1, "mobile": False})
    browser.js("afvPage.preset('dispersed-epithelial')")
    time.sleep(seconds)
    check_state(browser, "the picture for the docs")
    screenshot(browser, path)
    browser.js("afvPage.pause()")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--afv", default="./afv")
    ap.add_argument("--web", default="web")
    ap.add_argument("--out", default="out/web")
    ap.add_argument("--doc-screenshot", metavar="PNG",
                    help="also write the picture of doc/web.md there")
    ap.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    t0 = time.time()
    tmp = tempfile.mkdtemp(prefix="afv-web-")
    server = browser = None
    try:
        runs = start_afv_runs(os.path.abspath(args.afv), tmp)
        server = serve(os.path.abspath(args.web))
        browser = Browser(args.chromium, os.path.join(tmp, "profile"))
        open_page(browser, "http://127.0.0.1:%d/index.html"
                  % server.server_address[1])
        print("web_check: presets against afv run (N 400, seed 1):")
        check_presets(browser, runs, args.out)
        print("web_check: bad input:")
        check_bad_input(browser)
        fps, cost = measure_fps(browser)
        print("web_check: N 400, 10 steps per frame: %.0f frames/s (%.0f "
              "steps/s) in headless chromium at load average %.1f; per "
              "frame %.1f ms in the worker (steps, clusters, outlines) and "
              "%.1f ms of the page's script (drawing, plots)" % (
                  fps, 10 * fps, os.getloadavg()[0], cost["work"],
                  cost["draw"]))
        if args.doc_screenshot:
            doc_screenshot(browser, args.doc_screenshot)
        print("web_check: passed in %.0f s; screenshots in %s/"
              % (time.time() - t0, args.out))
        return 0
    except Fail as e:
        print("web_check: FAILED: %s" % e, file=sys.stderr)
        return 1
    finally:
        if browser:
            browser.close()
        if server:
            server.shutdown()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
