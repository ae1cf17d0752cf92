#!/usr/bin/env python3
"""Checks web pages hdot wrote in a real browser: headless Chromium driven
over its DevTools protocol on a pipe (--remote-debugging-pipe; no network,
no driver, nothing but the Python standard library).

    scripts/check_pages.py [--screenshot DIR [--full-page]] [--max-bytes N] PAGE.html...

For each page: no console error or uncaught exception; no horizontal
overflow at 1280 px and at 400 px wide; a simulation page's canvas differs
between two times of the animation (the canvas read back at the scrubber's
start and middle); every chart and plot (<svg>) has a non-zero rendered
size at both widths; on a page of the notes (its <main> carries
data-equations, the count of equations of the document model) as many
<math> elements as that count, each with a non-zero rendered size at both
widths; the file is smaller than --max-bytes (default 2 MB).
With --screenshot, a PNG of each page at both widths goes to DIR: what
the window shows (900 px high), or with --full-page the whole page.

Chromium is looked up as $HDOT_CHROMIUM, chromium, chromium-browser. When
it is missing the check is skipped with a note (exit 0), except under
CI=true, where it fails.
"""

import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

WIDTHS = (1280, 400)
TIMEOUT_S = 60


def find_chromium():
    for name in (os.environ.get("HDOT_CHROMIUM"), "chromium", "chromium-browser"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


class Browser:
    """One headless Chromium, spoken to over fds 3 (commands) and 4 (replies)."""

    def __init__(self, exe, profile):
        to_child_r, self.to_child = os.pipe()
        self.from_child, from_child_w = os.pipe()
        flags = [
            "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
            "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync",
            "--disable-extensions", "--hide-scrollbars", "--mute-audio",
            "--remote-debugging-pipe", "--user-data-dir=" + profile,
            "about:blank",
        ]

        def fds():
            os.dup2(to_child_r, 3)
            os.dup2(from_child_w, 4)

        self.proc = subprocess.Popen(
            [exe] + flags, pass_fds=(3, 4), preexec_fn=fds,
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )
        os.close(to_child_r)
        os.close(from_child_w)
        self.buf = b""
        self.next_id = 0
        self.events = []

    def close(self):
        try:
            self.call("Browser.close")
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()

    def _read(self, deadline):
        while b"\0" not in self.buf:
            if time.time() > deadline:
                raise TimeoutError("no answer from chromium")
            chunk = os.read(self.from_child, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed its pipe")
            self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method, session=None, **params):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params}
        if session:
            msg["sessionId"] = session
        os.write(self.to_child, json.dumps(msg).encode() + b"\0")
        deadline = time.time() + TIMEOUT_S
        while True:
            reply = self._read(deadline)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_event(self, method, session):
        deadline = time.time() + TIMEOUT_S
        for i, e in enumerate(self.events):
            if e.get("method") == method and e.get("sessionId") == session:
                return self.events.pop(i)
        while True:
            e = self._read(deadline)
            if e.get("method") == method and e.get("sessionId") == session:
                return e
            self.events.append(e)


def console_errors(events, session):
    out = []
    for e in events:
        if e.get("sessionId") != session:
            continue
        p = e.get("params", {})
        m = e.get("method")
        if m == "Runtime.exceptionThrown":
            d = p["exceptionDetails"]
            out.append("exception: " + d.get("exception", {}).get("description", d.get("text", "?")))
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console.error: " + " ".join(str(a.get("value", a.get("description"))) for a in p["args"]))
        elif m == "Log.entryAdded" and p["entry"]["level"] == "error":
            out.append("log: " + p["entry"]["text"])
    return out


def evaluate(b, s, expr):
    r = b.call("Runtime.evaluate", s, expression=expr, awaitPromise=True, returnByValue=True)
    if "exceptionDetails" in r:
        raise RuntimeError(f"{expr}: {r['exceptionDetails']}")
    return r["result"].get("value")


# Two frames of the animation, read back from the canvas: paused, scrubbed
# to the start, then to the middle.
CANVAS_AT_TWO_TIMES = """(async () => {
  const c = document.getElementById("view"), s = document.getElementById("scrub");
  if (!c || !s) return null;
  const play = document.getElementById("play");
  if (play.textContent === "Pause") play.click();
  const at = (v) => { s.value = v; s.dispatchEvent(new Event("input")); return c.toDataURL(); };
  const a = at(0), b = at(Math.floor(Number(s.max) / 2));
  return [a.length, b.length, a === b];
})()"""

# The notes' equations: the count the page states, the <math> elements
# found, and those rendered with no width or height.
MATH = """(() => {
  const m = document.querySelector("main[data-equations]");
  if (!m) return null;
  const all = [...document.querySelectorAll("math")];
  const empty = all.filter(e => { const r = e.getBoundingClientRect(); return !(r.width > 0 && r.height > 0); })
    .slice(0, 3).map(e => (e.getAttribute("alttext") || "").slice(0, 60));
  return [Number(m.dataset.equations), all.length, empty];
})()"""

# Charts and plots drawn with no width or height (a broken inline SVG).
SVGS = """(() => [...document.querySelectorAll("svg")]
  .filter(e => { const r = e.getBoundingClientRect(); return !(r.width > 0 && r.height > 0); })
  .length)()"""

SETTLE = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(r, 100))))"

OVERFLOW = """(() => {
  const d = document.documentElement;
  const wide = [...document.querySelectorAll("body *")]
    .filter(e => e.getBoundingClientRect().right > d.clientWidth + 1)
    .slice(0, 3).map(e => e.tagName + (e.id ? "#" + e.id : ""));
  return [d.scrollWidth, d.clientWidth, wide];
})()"""


def screenshot(b, s, width, full):
    """A PNG of the window, or of the whole page when `full`."""
    if not full:
        return b.call("Page.captureScreenshot", s, format="png", captureBeyondViewport=False)["data"]
    size = b.call("Page.getLayoutMetrics", s)["cssContentSize"]
    clip = {"x": 0, "y": 0, "width": width, "height": size["height"], "scale": 1}
    return b.call("Page.captureScreenshot", s, format="png", captureBeyondViewport=True, clip=clip)["data"]


def check_page(b, path, max_bytes, shots, full):
    problems = []
    size = os.path.getsize(path)
    if size >= max_bytes:
        problems.append(f"{size} bytes, over the budget of {max_bytes}")
    target = b.call("Target.createTarget", url="about:blank")["targetId"]
    s = b.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
    for domain in ("Page", "Runtime", "Log"):
        b.call(domain + ".enable", s)
    for width in WIDTHS:
        b.call("Emulation.setDeviceMetricsOverride", s, width=width, height=900,
               deviceScaleFactor=1, mobile=False)
        b.call("Page.navigate", s, url="file://" + os.path.abspath(path))
        b.wait_event("Page.loadEventFired", s)
        evaluate(b, s, SETTLE)
        scroll, client, wide = evaluate(b, s, OVERFLOW)
        if scroll > client:
            problems.append(f"horizontal overflow at {width} px: {scroll} > {client} ({', '.join(wide)})")
        if shots:
            png = screenshot(b, s, width, full)
            name = os.path.splitext(os.path.basename(path))[0] + f"-{width}.png"
            with open(os.path.join(shots, name), "wb") as f:
                f.write(base64.b64decode(png))
        flat = evaluate(b, s, SVGS)
        if flat:
            problems.append(f"{flat} <svg> rendered with no size at {width} px")
        maths = evaluate(b, s, MATH)
        if maths is not None:
            expected, found, empty = maths
            if found != expected:
                problems.append(f"{found} <math> elements, but the document model has {expected} equations")
            if empty:
                problems.append(f"math rendered with no size at {width} px: {'; '.join(empty)}")
        if width == WIDTHS[0]:
            two = evaluate(b, s, CANVAS_AT_TWO_TIMES)
            if two is not None and two[2]:
                problems.append("the canvas is the same at two times of the animation")
    problems += console_errors(b.events, s)
    b.call("Target.closeTarget", targetId=target)
    return problems


def main(argv):
    shots, full, max_bytes, pages = None, False, 2 << 20, []
    it = iter(argv)
    for a in it:
        if a == "--screenshot":
            shots = next(it)
            os.makedirs(shots, exist_ok=True)
        elif a == "--full-page":
            full = True
        elif a == "--max-bytes":
            max_bytes = int(next(it))
        else:
            pages.append(a)
    if not pages:
        print(__doc__)
        return 2
    exe = find_chromium()
    if exe is None:
        if os.environ.get("CI") == "true":
            print("check_pages: chromium is missing (CI=true: the browser test must run; scripts/setup installs it)")
            return 1
        print("check_pages: skipped: chromium is not installed (scripts/setup installs it as root)")
        return 0
    passed, failed = 0, 0
    with tempfile.TemporaryDirectory(prefix="hdot-chromium-") as profile:
        b = Browser(exe, profile)
        try:
            for page in pages:
                problems = check_page(b, page, max_bytes, shots, full)
                if problems:
                    failed += 1
                    print(f"FAIL {page}")
                    for p in problems:
                        print(f"  {p}")
                else:
                    passed += 1
                    print(f"ok   {page}")
        finally:
            b.close()
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
