#!/usr/bin/env python3
"""Check the HTML edition of the reports in a real headless Chromium.

Loads ``reports/index.html`` from disk in Chromium, waits until every image
is decoded, then

* fails if an ``<img>`` did not load (``naturalWidth == 0``), if the page
  holds math that could not be rendered (``.math-error`` elements), if a
  resource would be fetched from outside the page (an ``src`` that is not a
  ``data:`` URI), or if the console reports an error or an exception;
* takes screenshots into ``tools/screenshots/`` (git-ignored): the page in
  viewport-sized steps as a reader scrolls it (``page-NN.png``), and every
  figure on its own (``figure-NN.png``).

Chromium is driven over the DevTools protocol through ``--remote-debugging-pipe``
(JSON messages on file descriptors 3 and 4), so the check needs nothing
beyond the standard library and the Debian ``chromium`` package, which the
script installs with apt-get when ``/usr/bin/chromium`` is missing.  The
browser runs with a fresh, empty profile and with every background network
feature off.

Exit status: 0 when the page passes, 1 when a check fails, 2 when Chromium
cannot be installed or started.

Usage::

    python tools/check_html.py [reports/index.html] [--out tools/screenshots]
"""

from __future__ import annotations

import argparse
import base64
import fcntl
import json
import math
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
    "--hide-scrollbars",
    "--mute-audio",
    "--force-device-scale-factor=1",
]


class CheckError(Exception):
    """The browser could not be installed, started or driven."""


# --------------------------------------------------------------------------- browser
def find_chromium(install: bool = True) -> str:
    """Path of the Chromium binary, installing the Debian packages if it is missing."""
    for candidate in ("/usr/bin/chromium", shutil.which("chromium"), shutil.which("chromium-browser")):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    if not install:
        raise CheckError("chromium is not installed (apt-get install -y chromium chromium-driver)")
    print("chromium not found; installing the Debian packages chromium and chromium-driver", file=sys.stderr)
    cmd = "apt-get update && apt-get install -y chromium chromium-driver"
    if os.geteuid() != 0:
        if not shutil.which("sudo"):
            raise CheckError(f"chromium is missing and this user cannot install it; run as root: {cmd}")
        cmd = f"sudo sh -c '{cmd}'"
    status = subprocess.call(cmd, shell=True, stdout=sys.stderr)
    if status != 0 or not os.access("/usr/bin/chromium", os.X_OK):
        raise CheckError(f"installing chromium failed (exit status {status}): {cmd}")
    return "/usr/bin/chromium"


class Browser:
    """A headless Chromium spoken to over the DevTools protocol on a pipe."""

    def __init__(self, binary: str, *, width: int, height: int, timeout: float = 60.0):
        self.timeout = timeout
        self.events: list = []
        self._next_id = 0
        self._replies: queue.Queue = queue.Queue()
        self._profile = tempfile.mkdtemp(prefix="check-html-profile-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def wire_fds():  # in the child: the protocol reads fd 3 and writes fd 4
            a = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD, 10)
            b = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [binary, *CHROMIUM_FLAGS, f"--user-data-dir={self._profile}", f"--window-size={width},{height}", "--remote-debugging-pipe", "about:blank"]
        self._log = tempfile.TemporaryFile()
        self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=self._log, stderr=self._log, close_fds=False, preexec_fn=wire_fds)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        self.session = None

    def _read(self):
        buf = b""
        while True:
            try:
                chunk = os.read(self._from_browser, 1 << 16)
            except OSError:
                chunk = b""
            if not chunk:
                self._replies.put(None)
                return
            buf += chunk
            while b"\0" in buf:
                raw, buf = buf.split(b"\0", 1)
                self._replies.put(json.loads(raw))

    def send(self, method: str, params: dict | None = None, *, session: bool = True) -> dict:
        """Send one command and wait for its reply; events seen meanwhile are kept."""
        self._next_id += 1
        msg = {"id": self._next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self._to_browser, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._get(deadline, method)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise CheckError(f"{method} failed: {reply['error'].get('message')}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_event(self, method: str) -> dict:
        for i, event in enumerate(self.events):
            if event.get("method") == method:
                return self.events.pop(i)
        deadline = time.monotonic() + self.timeout
        while True:
            event = self._get(deadline, method)
            if event.get("method") == method:
                return event
            self.events.append(event)

    def _get(self, deadline: float, what: str) -> dict:
        left = deadline - time.monotonic()
        try:
            item = self._replies.get(timeout=max(left, 0.0))
        except queue.Empty:
            raise CheckError(f"timed out after {self.timeout:.0f} s waiting for {what}") from None
        if item is None:
            self._log.seek(0)
            tail = self._log.read().decode(errors="replace")[-2000:]
            raise CheckError(f"chromium exited while waiting for {what}:\n{tail}")
        return item

    def open_page(self) -> None:
        target = self.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True}, session=False)["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            self.send(f"{domain}.enable")

    def evaluate(self, expression: str):
        result = self.send("Runtime.evaluate", {"expression": expression, "awaitPromise": True, "returnByValue": True})
        if "exceptionDetails" in result:
            raise CheckError(f"page script failed: {result['exceptionDetails'].get('text')}")
        return result["result"].get("value")

    def screenshot(self, path: Path, clip: dict | None = None) -> None:
        params = {"format": "png"}
        if clip:
            params.update(clip=dict(clip, scale=1), captureBeyondViewport=True)
        data = self.send("Page.captureScreenshot", params)["data"]
        path.write_bytes(base64.b64decode(data))

    def close(self) -> None:
        try:
            if self.proc.poll() is None:
                try:
                    self.send("Browser.close", session=False)
                except CheckError:
                    pass
                try:
                    self.proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    self.proc.kill()
                    self.proc.wait()
        finally:
            for fd in (self._to_browser, self._from_browser):
                try:
                    os.close(fd)
                except OSError:
                    pass
            shutil.rmtree(self._profile, ignore_errors=True)


# --------------------------------------------------------------------------- checks
INSPECT = r"""
(async () => {
  await Promise.all([...document.images].map(img => img.decode().catch(() => null)));
  const box = el => { const r = el.getBoundingClientRect();
    return {x: r.left + scrollX, y: r.top + scrollY, width: r.width, height: r.height}; };
  return {
    title: document.title,
    height: document.documentElement.scrollHeight,
    images: [...document.images].map((img, i) => ({
      index: i + 1, alt: img.alt, src: img.getAttribute('src').slice(0, 48),
      naturalWidth: img.naturalWidth, naturalHeight: img.naturalHeight, box: box(img)})),
    mathErrors: [...document.querySelectorAll('.math-error')].map(e => e.textContent),
    math: document.querySelectorAll('.math svg').length,
    external: [...document.querySelectorAll('[src]')].map(e => e.getAttribute('src'))
      .filter(s => !s.startsWith('data:')),
    sections: [...document.querySelectorAll('section.page')].map(s => s.id),
  };
})()
"""


def console_errors(events: list) -> list:
    """Console errors, uncaught exceptions and failed loads among DevTools events."""
    out = []
    for e in events:
        method, p = e.get("method"), e.get("params", {})
        if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console." + p["type"] + ": " + " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", [])))
        elif method == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            out.append("exception: " + (d.get("exception", {}).get("description") or d.get("text", "")))
        elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            entry = p["entry"]
            out.append(f"{entry.get('source')}: {entry.get('text')} {entry.get('url', '')}".strip())
    return out


def check(html: Path, out: Path, *, width: int = 1280, height: int = 900, figures: bool = True, max_pages: int = 60) -> int:
    html = html.resolve()
    if not html.is_file():
        print(f"FAIL: {html} does not exist (run `strapdown report` first)", file=sys.stderr)
        return 1
    out.mkdir(parents=True, exist_ok=True)
    for old in list(out.glob("page-*.png")) + list(out.glob("figure-*.png")):
        old.unlink()
    browser = Browser(find_chromium(), width=width, height=height)
    try:
        browser.open_page()
        browser.send("Emulation.setDeviceMetricsOverride", {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
        browser.send("Page.navigate", {"url": html.as_uri()})
        browser.wait_event("Page.loadEventFired")
        info = browser.evaluate(INSPECT)
        frame = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))"
        pages = min(max_pages, max(1, math.ceil(info["height"] / height)))
        for k in range(pages):
            browser.evaluate(f"window.scrollTo({{top: {k * height}, behavior: 'instant'}}); {frame}")
            browser.screenshot(out / f"page-{k + 1:02d}.png")
        if figures:
            browser.evaluate(f"window.scrollTo({{top: 0, behavior: 'instant'}}); {frame}")
            for img in info["images"]:
                b = img["box"]
                if b["width"] > 0 and b["height"] > 0:
                    browser.screenshot(out / f"figure-{img['index']:02d}.png", {k: b[k] for k in ("x", "y", "width", "height")})
        browser.evaluate("new Promise(r => setTimeout(r, 100))")
        errors = console_errors(browser.events)
    finally:
        browser.close()

    failures = []
    for img in info["images"]:
        if img["naturalWidth"] == 0:
            failures.append(f"figure {img['index']} ({img['alt'] or 'no alt text'}, src {img['src']!r}) did not load")
    failures += [f"math not rendered: {t}" for t in info["mathErrors"]]
    failures += [f"external resource (the page must be self-contained): {s}" for s in info["external"]]
    failures += [f"browser error: {e}" for e in errors]

    shots = sorted(p.name for p in out.glob("*.png"))
    print(f"{html.name}: {info['title']!r}, {len(info['sections'])} pages ({', '.join(info['sections'])}), "
          f"{len(info['images'])} figures, {info['math']} equations, {info['height']} px tall")
    if pages * height < info["height"]:
        print(f"note: only the first {pages} viewport screenshots were taken (--max-pages)")
    print(f"{len(shots)} screenshots in {out}: {', '.join(shots)}")
    if failures:
        print(f"FAIL: {len(failures)} problem(s) in {html}:", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        return 1
    print("OK: every figure loaded, every equation rendered, no browser errors")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("html", nargs="?", type=Path, default=ROOT / "reports" / "index.html", help="page to check (default: reports/index.html)")
    parser.add_argument("--out", type=Path, default=ROOT / "tools" / "screenshots", help="screenshot directory (default: tools/screenshots)")
    parser.add_argument("--width", type=int, default=1280, help="viewport width [px]")
    parser.add_argument("--height", type=int, default=900, help="viewport height [px]")
    parser.add_argument("--max-pages", type=int, default=60, help="most viewport screenshots to take")
    parser.add_argument("--no-figures", action="store_true", help="skip the per-figure screenshots")
    args = parser.parse_args(argv)
    try:
        return check(args.html, args.out, width=args.width, height=args.height, figures=not args.no_figures, max_pages=args.max_pages)
    except CheckError as exc:
        print(f"ERROR: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
