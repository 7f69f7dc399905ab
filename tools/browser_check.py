"""Open HTML pages in headless Chromium, screenshot them, check images and links.

Talks to Chromium over the DevTools protocol on a pipe (``--remote-debugging-pipe``: the
browser reads JSON messages, each ended by NUL, on fd 3 and writes on fd 4), so it needs
nothing but Debian's ``chromium`` package and the standard library.

For each page: every ``<img>`` must have loaded (``complete`` and ``naturalWidth > 0``), no
request may fail (missing CSS, script, image), and every internal link (``file:`` URLs) must
point to an existing file and, with a ``#fragment``, to an element with that id or name.
External links (http, mailto) are counted, not followed (no network here).

    python tools/browser_check.py site/index.html report/index.html --screenshots shots/
    python tools/browser_check.py --links-only site/      # every page's links, no browser
"""

from __future__ import annotations

import argparse
import base64
import html.parser
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urldefrag, urlparse

__all__ = [
    "Chromium",
    "PageReport",
    "check_links",
    "check_page",
    "find_chromium",
    "site_link_errors",
]

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "chrome")

_COLLECT_JS = """
(async () => {
  const imgs = Array.from(document.images);
  await Promise.all(imgs.map(i => i.complete ? null :
    new Promise(r => { i.addEventListener('load', r); i.addEventListener('error', r); })));
  return JSON.stringify({
    title: document.title,
    images: imgs.map(i => ({src: i.currentSrc || i.src, complete: i.complete,
                            naturalWidth: i.naturalWidth})),
    links: Array.from(document.querySelectorAll('a[href]')).map(a => a.href),
    height: Math.max(document.documentElement.scrollHeight, document.body.scrollHeight),
  });
})()
"""


def find_chromium() -> str | None:
    """Path of a Chromium binary (``$CHROMIUM`` first), or None."""
    env = os.environ.get("CHROMIUM")
    if env and shutil.which(env):
        return shutil.which(env)
    for name in CANDIDATES:
        path = shutil.which(name)
        if path:
            return path
    return None


class ChromiumError(RuntimeError):
    """The browser did not answer, or answered with an error."""


class Chromium:
    """A headless Chromium driven over the DevTools pipe (use as a context manager)."""

    def __init__(self, binary: str | None = None, *, timeout: float = 60.0):
        binary = binary or find_chromium()
        if binary is None:
            raise ChromiumError("no Chromium binary found (apt-get install chromium)")
        self.timeout = timeout
        self._profile = tempfile.mkdtemp(prefix="onbottom-chromium-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def child_fds() -> None:  # runs in the child: fd 3 = our writes, fd 4 = its writes
            import fcntl

            a = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD, 10)  # out of the way of 3 and 4
            b = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [
            binary,
            "--headless",
            "--remote-debugging-pipe",
            "--disable-gpu",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-extensions",
            "--disable-dev-shm-usage",
            "--allow-file-access-from-files",
            f"--user-data-dir={self._profile}",
            "about:blank",
        ]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            args.insert(1, "--no-sandbox")  # Chromium refuses to run as root with a sandbox
        self.proc = subprocess.Popen(
            args,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            preexec_fn=child_fds,
            pass_fds=(3, 4),  # the child's copies made by child_fds (others are closed)
        )
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._buf = b""
        self._id = 0
        self._events: list[dict] = []

    # -- protocol -------------------------------------------------------------------------
    def _read_message(self, deadline: float) -> dict:
        import select

        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise ChromiumError("timed out waiting for Chromium")
            ready, _, _ = select.select([self._from_browser], [], [], left)
            if not ready:
                continue
            chunk = os.read(self._from_browser, 1 << 20)
            if not chunk:
                raise ChromiumError("Chromium closed the pipe")
            self._buf += chunk
        msg, self._buf = self._buf.split(b"\0", 1)
        return json.loads(msg)

    def send(self, method: str, params: dict | None = None, session: str | None = None) -> dict:
        """Send one command and return its result (events received meanwhile are kept)."""
        self._id += 1
        msg: dict = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_browser, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise ChromiumError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self._events.append(reply)

    def wait_event(self, method: str, session: str | None, timeout: float) -> dict:
        """Wait for an event (one already received counts)."""
        deadline = time.monotonic() + timeout
        while True:
            for i, ev in enumerate(self._events):
                if ev.get("method") == method and ev.get("sessionId") == session:
                    return self._events.pop(i)
            self._events.append(self._read_message(deadline))

    def events(self, method: str, session: str | None) -> list[dict]:
        """Events of one kind received so far (removed from the queue)."""
        hit = [
            e for e in self._events if e.get("method") == method and e.get("sessionId") == session
        ]
        self._events = [e for e in self._events if e not in hit]
        return hit

    def close(self) -> None:
        """Close the browser and remove its profile folder."""
        try:
            self.send("Browser.close")
        except (ChromiumError, OSError):
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self._profile, ignore_errors=True)

    def __enter__(self) -> Chromium:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # -- pages ----------------------------------------------------------------------------
    def open(self, url: str, *, width: int = 1280, height: int = 900) -> tuple[str, dict]:
        """Open ``url`` in a new tab, wait for its load event; return (session, page info)."""
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})[
            "sessionId"
        ]
        self.send("Page.enable", session=session)
        self.send("Network.enable", session=session)
        self.send(
            "Emulation.setDeviceMetricsOverride",
            {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False},
            session=session,
        )
        nav = self.send("Page.navigate", {"url": url}, session=session)
        if nav.get("errorText"):
            raise ChromiumError(f"cannot open {url}: {nav['errorText']}")
        self.wait_event("Page.loadEventFired", session, self.timeout)
        res = self.send(
            "Runtime.evaluate",
            {"expression": _COLLECT_JS, "awaitPromise": True, "returnByValue": True},
            session=session,
        )
        info = json.loads(res["result"]["value"])
        info["failed_requests"] = [
            e["params"].get("errorText", "") + " " + e["params"].get("requestId", "")
            for e in self.events("Network.loadingFailed", session)
            if not e["params"].get("canceled")
        ]
        urls = {
            e["params"]["requestId"]: e["params"]["request"]["url"]
            for e in self.events("Network.requestWillBeSent", session)
        }
        info["failed_requests"] = [
            f"{urls.get(r.split()[-1], '?')}: {' '.join(r.split()[:-1])}"
            for r in info["failed_requests"]
        ]
        return session, info

    def screenshot(self, session: str, path: str | Path, full_height: int | None = None) -> Path:
        """Save a PNG of the page (up to ``full_height`` CSS pixels tall)."""
        params: dict = {"format": "png"}
        if full_height:
            params["captureBeyondViewport"] = True
            params["clip"] = {
                "x": 0,
                "y": 0,
                "width": 1280,
                "height": min(int(full_height), 12000),
                "scale": 1,
            }
        data = self.send("Page.captureScreenshot", params, session=session)["data"]
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(base64.b64decode(data))
        return path


# ---------------------------------------------------------------------------------------------
# links


class _Anchors(html.parser.HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.hrefs: list[str] = []
        self.srcs: list[str] = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("id", "name"):
            if a.get(key):
                self.ids.add(a[key])
        if tag == "a" and a.get("href"):
            self.hrefs.append(a["href"])
        if tag == "img" and a.get("src"):
            self.srcs.append(a["src"])


_ANCHOR_CACHE: dict[Path, _Anchors] = {}


def _anchors(path: Path) -> _Anchors:
    if path not in _ANCHOR_CACHE:
        p = _Anchors()
        p.feed(path.read_text(encoding="utf-8", errors="replace"))
        _ANCHOR_CACHE[path] = p
    return _ANCHOR_CACHE[path]


def check_links(links: list[str]) -> tuple[list[str], int]:
    """Broken internal (``file:``) links among absolute URLs, and the number of external ones."""
    broken, external = [], 0
    for link in links:
        url, frag = urldefrag(link)
        scheme = urlparse(url).scheme
        if scheme in ("http", "https", "mailto", "ftp", "data", "javascript"):
            external += 1
            continue
        if scheme != "file":
            broken.append(f"{link} (scheme {scheme!r})")
            continue
        path = Path(unquote(urlparse(url).path))
        if path.is_dir():
            path = path / "index.html"
        if not path.exists():
            broken.append(f"{link} (no such file)")
            continue
        if frag and path.suffix in (".html", ".htm") and unquote(frag) not in _anchors(path).ids:
            broken.append(f"{link} (no element with id {frag!r})")
    return broken, external


def site_link_errors(root: str | Path) -> list[str]:
    """Check every ``<a href>`` and ``<img src>`` of every HTML page under ``root`` (no browser)."""
    root = Path(root).resolve()
    errors = []
    for page in sorted(root.rglob("*.html")):
        if page.name == "404.html" and page.parent == root:
            continue  # served by a web server for any path: its links are absolute
        a = _anchors(page)
        urls = []
        for ref in a.hrefs + a.srcs:
            if ref.startswith("#"):
                urls.append(page.as_uri() + ref if len(ref) > 1 else page.as_uri())
            elif urlparse(ref).scheme:
                urls.append(ref)
            else:
                target, frag = urldefrag(ref)
                resolved = (page.parent / unquote(target)).resolve() if target else page
                urls.append(resolved.as_uri() + (f"#{frag}" if frag else ""))
        broken, _ = check_links(urls)
        errors += [f"{page.relative_to(root)}: {b}" for b in broken]
    return errors


# ---------------------------------------------------------------------------------------------
# one call per page


@dataclass
class PageReport:
    """What a page showed in the browser."""

    url: str
    title: str = ""
    screenshot: Path | None = None
    images: list[dict] = field(default_factory=list)
    broken_images: list[str] = field(default_factory=list)
    broken_links: list[str] = field(default_factory=list)
    n_links: int = 0
    n_external: int = 0
    failed_requests: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """No broken image, link or request."""
        return not (self.broken_images or self.broken_links or self.failed_requests)

    def problems(self) -> list[str]:
        """Human-readable list of what is wrong."""
        return (
            [f"image did not load: {s}" for s in self.broken_images]
            + [f"broken link: {s}" for s in self.broken_links]
            + [f"request failed: {s}" for s in self.failed_requests]
        )


def check_page(browser: Chromium, page: str | Path, screenshot: str | Path | None) -> PageReport:
    """Open ``page`` (a file path or URL), screenshot it, check its images and links."""
    url = Path(page).resolve().as_uri() if "://" not in str(page) else str(page)
    session, info = browser.open(url)
    rep = PageReport(url=url, title=info["title"], images=info["images"])
    rep.broken_images = [
        i["src"] for i in info["images"] if not (i["complete"] and i["naturalWidth"] > 0)
    ]
    rep.broken_links, rep.n_external = check_links(info["links"])
    rep.n_links = len(info["links"])
    rep.failed_requests = info["failed_requests"]
    if screenshot is not None:
        rep.screenshot = browser.screenshot(session, screenshot, full_height=info["height"])
    return rep


def main(argv: list[str] | None = None) -> int:
    """Command line: check pages; exit 1 if anything is broken."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("pages", nargs="+", help="HTML files (or a folder with --links-only)")
    ap.add_argument("--screenshots", type=Path, default=None, help="folder for PNG screenshots")
    ap.add_argument("--links-only", action="store_true", help="static link check of folders")
    args = ap.parse_args(argv)
    bad = 0
    if args.links_only:
        for root in args.pages:
            errs = site_link_errors(root)
            print(f"{root}: {len(errs)} broken links")
            for e in errs:
                print("  " + e)
            bad += len(errs)
        return 1 if bad else 0
    with Chromium() as browser:
        for i, page in enumerate(args.pages):
            shot = None if args.screenshots is None else args.screenshots / f"page_{i}.png"
            rep = check_page(browser, page, shot)
            print(
                f"{page}: {len(rep.images)} images, {rep.n_links} links"
                f" ({rep.n_external} external), screenshot {rep.screenshot}"
            )
            for p in rep.problems():
                print("  " + p)
            bad += not rep.ok
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
