#!/usr/bin/env python3
"""The HTML report in a real browser: Debian's chromium, headless, driven over the
DevTools protocol on a pipe (--remote-debugging-pipe: no network port, no package
beyond the standard library and python3-pil). For the report of a scene it checks:

  - the page loads without a console error, an uncaught exception or a failed request;
  - every table of the report is in the DOM under its key, every section under its id;
  - no section says it was not computed;
  - nothing is fetched but the page itself;
  - a screenshot of the whole page shows each figure drawn: inside each figure's box
    at least 0.3 % of the pixels are coloured (curves: grid, frame and text are grey or
    black, so an empty or unrendered figure fails);
  - the page prints (Page.printToPDF gives a PDF of more than one page).

--screenshot PATH keeps the screenshot's top (docs/report.md shows it as
docs/img/report.png). Without chromium the check is skipped with a message (exit 0).
Run by .ci/run as its own stage, outside the README's test run:

    python3 tests/report_browser.py --gyrokit build/apps/gyrokit --data data --out build/report-browser
"""
import argparse
import base64
import fcntl
import io
import json
import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time

CHROMIUM = ("chromium", "chromium-browser")
WIDTH = 1100


class Browser:
    """chromium with its DevTools protocol on fds 3 (commands) and 4 (replies), NUL-separated JSON."""

    def __init__(self, exe, profile):
        to_chrome_r, self._to_chrome = os.pipe()
        self._from_chrome, from_chrome_w = os.pipe()

        def fds():   # chromium reads commands on fd 3 and writes replies on fd 4
            r = fcntl.fcntl(to_chrome_r, fcntl.F_DUPFD, 10)   # out of the way of 3 and 4 first
            w = fcntl.fcntl(from_chrome_w, fcntl.F_DUPFD, 10)
            os.dup2(r, 3)
            os.dup2(w, 4)

        # pass_fds keeps 3 and 4 open: the other descriptors are closed after fds() runs.
        self.proc = subprocess.Popen(
            [exe, "--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe", "--no-first-run",
             "--hide-scrollbars", "--disable-extensions", f"--user-data-dir={profile}", "about:blank"],
            pass_fds=(3, 4), preexec_fn=fds, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            start_new_session=True)   # its own process group: closed with every renderer
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self._buffer = b""
        self._id = 0
        self.events = []

    def _read_message(self, deadline):
        while b"\0" not in self._buffer:
            left = deadline - time.time()
            if left <= 0 or not select.select([self._from_chrome], [], [], left)[0]:
                raise TimeoutError("chromium did not answer in time")
            chunk = os.read(self._from_chrome, 1 << 20)
            if not chunk:
                raise RuntimeError("chromium closed its DevTools pipe")
            self._buffer += chunk
        raw, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method, params=None, session=None, timeout=60):
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_chrome, json.dumps(msg).encode() + b"\0")
        deadline = time.time() + timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self._id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def wait_event(self, name, timeout=60):
        deadline = time.time() + timeout
        for i, e in enumerate(self.events):
            if e.get("method") == name:
                return self.events.pop(i)
        while True:
            m = self._read_message(deadline)
            if m.get("method") == name:
                return m
            self.events.append(m)

    def close(self):
        try:
            self.call("Browser.close", timeout=10)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)   # renderers left behind
        except ProcessLookupError:
            pass
        self.proc.wait()


PAGE_FACTS = """JSON.stringify({
  height: Math.ceil(document.documentElement.scrollHeight),
  tables: Array.from(document.querySelectorAll('table.data')).map(t => t.id),
  sections: Array.from(document.querySelectorAll('section')).map(s => s.id.replace(/^section-/, '')),
  failed: Array.from(document.querySelectorAll('.failed')).map(p => p.textContent),
  figures: Array.from(document.querySelectorAll('figure svg')).map(s => {
    const r = s.getBoundingClientRect();
    return {x: r.left + scrollX, y: r.top + scrollY, w: r.width, h: r.height,
            section: s.closest('section').id.replace(/^section-/, '')};
  })
})"""


def drawn_fraction(image, box):
    """The fraction of pixels in `box` (x, y, w, h) that are coloured: max - min of R, G, B above 60
    (the curves; the background, grid, frame and text are white, grey or black)."""
    x, y, w, h = (int(round(v)) for v in box)
    crop = image.crop((x, y, x + w, y + h)).convert("RGB")
    pixels = list(crop.getdata())
    coloured = sum(1 for r, g, b in pixels if max(r, g, b) - min(r, g, b) > 60)
    return coloured / len(pixels) if pixels else 0.0


def check(args):
    exe = next((shutil.which(c) for c in CHROMIUM if shutil.which(c)), None)
    if exe is None:
        print("report_browser: skipped: chromium is not installed (Debian: apt-get install chromium)")
        return 0
    from PIL import Image   # python3-pil: installed with chromium by .ci/install-deps.sh

    os.makedirs(args.out, exist_ok=True)
    page = os.path.abspath(os.path.join(args.out, "report.html"))
    scene = os.path.join(args.data, args.scene)
    subprocess.run([args.gyrokit, "report", scene, "--out", page], check=True, timeout=600)
    failures = []
    profile = tempfile.mkdtemp(prefix="gyrokit-chromium-")
    b = Browser(exe, profile)
    try:
        target = b.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = b.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            b.call(f"{domain}.enable", session=session)
        b.call("Emulation.setDeviceMetricsOverride",
               {"width": WIDTH, "height": 900, "deviceScaleFactor": 1, "mobile": False}, session=session)
        b.call("Page.navigate", {"url": "file://" + page}, session=session)
        b.wait_event("Page.loadEventFired", timeout=120)
        facts = json.loads(b.call("Runtime.evaluate", {"expression": PAGE_FACTS, "returnByValue": True},
                                  session=session)["result"]["value"])
        for e in b.events:
            m, p = e.get("method"), e.get("params", {})
            if m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                failures.append(f"console error: {p.get('args')}")
            elif m == "Runtime.exceptionThrown":
                failures.append(f"uncaught exception: {p.get('exceptionDetails', {}).get('text')}")
            elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
                failures.append(f"browser log error: {p['entry'].get('text')}")
            elif m == "Network.loadingFailed":
                failures.append(f"request failed: {p.get('errorText')}")
            elif m == "Network.requestWillBeSent":
                url = p.get("request", {}).get("url", "")
                if url != "file://" + page and not url.startswith("data:"):
                    failures.append(f"the page fetches {url}: it must hold everything itself")
        for f in facts["failed"]:
            failures.append(f"a section was not computed: {f}")
        for key in ("model", "map", "campbell", "modes", "stability", "api_unbalance", "level1", "run"):
            if key not in facts["sections"]:
                failures.append(f"section '{key}' is not in the DOM")
        for key in ("model", "critical_map", "summary", "critical_speeds",
                    "api_unbalance_summary", "api_unbalance_margins", "level1_summary", "level1_curve", "inputs"):
            if key not in facts["tables"]:
                failures.append(f"table '{key}' is not in the DOM (tables: {', '.join(facts['tables'])})")
        if not facts["figures"]:
            failures.append("no figure in the page")
        b.call("Emulation.setDeviceMetricsOverride",
               {"width": WIDTH, "height": facts["height"], "deviceScaleFactor": 1, "mobile": False}, session=session)
        shot = base64.b64decode(b.call("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True},
                                       session=session, timeout=120)["data"])
        image = Image.open(io.BytesIO(shot))
        for i, f in enumerate(facts["figures"]):
            frac = drawn_fraction(image, (f["x"], f["y"], f["w"], f["h"]))
            print(f"figure {i + 1} ({f['section']}): {f['w']:.0f} x {f['h']:.0f} px at y = {f['y']:.0f}, "
                  f"{100 * frac:.2f} % coloured")
            if frac < 0.003:
                failures.append(f"figure {i + 1} in section '{f['section']}' is blank ({100 * frac:.2f} % drawn)")
        pdf = base64.b64decode(b.call("Page.printToPDF", {"printBackground": True}, session=session,
                                      timeout=120)["data"])
        pages = pdf.count(b"/Type /Page") - pdf.count(b"/Type /Pages")
        print(f"printed: {len(pdf)} bytes of PDF, {pages} pages")
        if not pdf.startswith(b"%PDF") or pages < 2:
            failures.append(f"the page does not print ({pages} PDF pages)")
        if args.screenshot:
            image.crop((0, 0, WIDTH, min(image.height, 1800))).save(args.screenshot)
            print(f"wrote {args.screenshot}")
    finally:
        b.close()
        shutil.rmtree(profile, ignore_errors=True)
    print(f"{len(facts['sections'])} sections, {len(facts['tables'])} tables, {len(facts['figures'])} figures")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gyrokit", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--scene", default="three_disk_rotor.toml")
    ap.add_argument("--screenshot")
    return check(ap.parse_args())


if __name__ == "__main__":
    sys.exit(main())
