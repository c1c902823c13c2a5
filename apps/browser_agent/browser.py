"""The agent's browser: one Chromium page at 1280×800, driven through Playwright's sync API.

Each step the page is *observed*: its interactive elements in view are numbered (the
set-of-marks ids of Magentic-UI — `[12] button "Archive"`), tagged with a data attribute so a
tool can find them again by number, outlined and labelled on the screenshot, and listed in a
text description with the URL, the title and the start of the page's text as markdown.

The browser tools return one short line for the model. A tool that cannot do what was asked
(no element with that number, a navigation timeout) raises `BrowserError`, whose one-line
message the model reads as the tool's result: a mistake is something to recover from, never a
crash of the loop.
"""

from __future__ import annotations

import base64
import contextlib
import re
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TypeVar
from urllib.parse import urlsplit

from playwright.sync_api import (
    CDPSession,
    Locator,
    Page,
    Response,
    ViewportSize,
    sync_playwright,
)
from playwright.sync_api import Error as PlaywrightError

from apps.browser_agent.sim_clock import ClockReading, reading_from_headers
from apps.browser_agent.snapshot import html_to_markdown

CHROMIUM = "/usr/bin/chromium"  # Debian's; Playwright's own download is never used
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT: ViewportSize = {"width": 1280, "height": 800}
MARK_ATTRIBUTE = "data-sentinel-mark"
MAX_MARKS = 60  # elements listed per step: a dense page must not flood the prompt
SUMMARY_CHARS = 1500  # page text in each step's description
READ_PAGE_CHARS = 12000  # page text returned by read_page
ACTION_TIMEOUT_MS = 5000
NAVIGATION_TIMEOUT_MS = 30000
SETTLE_MS = 300  # after an action, time for scripts (HTMX swaps) to redraw before we look
TRANSCRIPT_SCALE = 0.5  # transcript JPEGs are 640 px wide
TRANSCRIPT_JPEG_QUALITY = 60

CATCH_UP_TIMEOUT_MS = 5000  # a fast-forward skip's push normally lands within milliseconds

T = TypeVar("T")

# The live page's config node (static/site/live.js keeps its data-seq and data-due current).
_DECLARED_DUE = """() => {
  const live = document.getElementById("sentinel-live");
  return live && live.dataset.due !== "" ? Number(live.dataset.due) : null;
}"""
# Caught up: the page shows at least log position `seq`, and its clock window starts after
# `now` (a render from before the skip would be due by then). A page of no run is as it is.
_CAUGHT_UP = """([seq, now]) => {
  const live = document.getElementById("sentinel-live");
  if (!live) return true;
  const due = live.dataset.due;
  return Number(live.dataset.seq) >= seq && (due === "" || Number(due) > now);
}"""


class BrowserError(Exception):
    """A tool could not do what the model asked; the message is the tool's result."""


@dataclass(frozen=True)
class Mark:
    number: int
    role: str
    name: str
    state: str  # value, checked, disabled: "" when there is nothing to say

    def __str__(self) -> str:
        text = f'[{self.number}] {self.role} "{self.name}"'
        return f"{text} {self.state}" if self.state else text


@dataclass(frozen=True)
class Observation:
    url: str
    title: str
    description: str
    png: bytes  # the viewport with its marks, for the model
    jpeg: bytes  # the same, small, for the transcript


# Numbers the interactive elements in the viewport, in document order, and returns them.
_MARK_ELEMENTS = """({attribute, limit}) => {
  document.querySelectorAll(`[${attribute}]`).forEach((el) => el.removeAttribute(attribute));
  const selector = [
    "a[href]", "button", "input:not([type=hidden])", "select", "textarea", "summary",
    "[role=button]", "[role=link]", "[role=checkbox]", "[role=radio]", "[role=switch]",
    "[role=tab]", "[role=menuitem]", "[role=option]", "[contenteditable=''], [contenteditable=true]",
  ].join(", ");
  const clean = (text) => (text || "").replace(/\\s+/g, " ").trim().slice(0, 100);
  const labelled = (el) => (el.getAttribute("aria-labelledby") || "").split(/\\s+/)
    .map((id) => document.getElementById(id)).filter(Boolean).map((n) => n.innerText).join(" ");
  const nameOf = (el) => clean(
    el.getAttribute("aria-label") || labelled(el) || (el.labels && el.labels[0] && el.labels[0].innerText)
    || el.getAttribute("title") || el.getAttribute("placeholder")
    || (["INPUT", "SELECT", "TEXTAREA"].includes(el.tagName) ? "" : el.innerText)
    || el.getAttribute("alt") || (el.querySelector("img[alt]") || {}).alt || el.getAttribute("name"));
  const roleOf = (el) => {
    if (el.getAttribute("role")) return el.getAttribute("role");
    if (el.tagName === "A") return "link";
    if (el.tagName === "INPUT") {
      const type = (el.getAttribute("type") || "text").toLowerCase();
      if (["checkbox", "radio"].includes(type)) return type;
      if (["submit", "button", "reset", "image"].includes(type)) return "button";
      return type === "text" ? "input" : `input ${type}`;
    }
    return el.tagName.toLowerCase();
  };
  const stateOf = (el) => {
    const parts = [];
    if (el.type === "checkbox" || el.type === "radio") parts.push(el.checked ? "checked" : "unchecked");
    else if (el.tagName === "SELECT") parts.push(`selected="${clean(el.selectedOptions[0]?.text)}"`);
    else if ((el.tagName === "INPUT" || el.tagName === "TEXTAREA") && el.value) parts.push(`value="${clean(el.value)}"`);
    if (el.disabled) parts.push("disabled");
    return parts.join(" ");
  };
  const marks = [];
  let hidden = 0;
  for (const el of document.querySelectorAll(selector)) {
    const r = el.getBoundingClientRect();
    if (r.width < 1 || r.height < 1 || r.bottom <= 0 || r.right <= 0
        || r.top >= innerHeight || r.left >= innerWidth) continue;
    // Not rendered for a person: display none, visibility hidden, or inside a closed
    // <details> (its content is laid out but skipped, content-visibility, so it has a box).
    if (!el.checkVisibility({contentVisibilityAuto: true, visibilityProperty: true})) continue;
    if (marks.length >= limit) { hidden += 1; continue; }
    const number = marks.length + 1;
    el.setAttribute(attribute, String(number));
    marks.push({number, role: roleOf(el), name: nameOf(el), state: stateOf(el),
                box: [r.left, r.top, r.width, r.height]});
  }
  return {marks, hidden, scrollY: Math.round(scrollY), left: scrollX, top: scrollY,
          height: Math.round(document.documentElement.scrollHeight)};
}"""

# Draws each mark's outline and number over the page, for the screenshots only.
_DRAW_MARKS = """(marks) => {
  const layer = document.createElement("div");
  layer.id = "sentinel-marks-layer";
  layer.style.cssText = "position:fixed;inset:0;pointer-events:none;z-index:2147483647";
  for (const m of marks) {
    const [x, y, w, h] = m.box;
    const box = document.createElement("div");
    box.style.cssText = `position:absolute;left:${x}px;top:${y}px;width:${w}px;height:${h}px;`
      + "outline:2px solid #e5007a;box-sizing:border-box";
    const label = document.createElement("span");
    label.textContent = String(m.number);
    label.style.cssText = "position:absolute;left:-2px;top:-14px;font:bold 11px/13px sans-serif;"
      + "background:#e5007a;color:#fff;padding:0 3px";
    box.appendChild(label);
    layer.appendChild(box);
  }
  document.documentElement.appendChild(layer);
}"""

# Marks the elements and draws them in one round trip to the page: each is a few milliseconds
# of the agent's every step, more on a loaded machine.
_MARK_AND_DRAW = f"""(marking) => {{
  const found = ({_MARK_ELEMENTS})(marking);
  ({_DRAW_MARKS})(found.marks);
  return found;
}}"""

# Takes the marks off again, and reads the title in the same round trip.
_REMOVE_MARKS = """() => {
  document.getElementById("sentinel-marks-layer")?.remove();
  return document.title;
}"""


def first_line(error: BaseException) -> str:
    """Playwright's messages run to many lines (call logs); the model gets the first."""
    text = str(error).strip().splitlines()
    return re.sub(r"^\w+\.\w+: ", "", text[0]) if text else type(error).__name__


class Browser:
    """A Chromium page the agent sees and acts on; also the page wait_for watches."""

    def __init__(self, page: Page, *, contact_url: str = "") -> None:
        self.page = page
        self._contact_path = urlsplit(contact_url).path.rstrip("/") if contact_url else ""
        self._marks: dict[int, Mark] = {}
        self._clock: ClockReading | None = None  # the last run clock a response reported
        self._devtools: CDPSession | None = None  # opened at the first screenshot, then kept
        page.on("response", self._heard)

    @classmethod
    @contextmanager
    def launch(cls, *, contact_url: str = "", executable: str = CHROMIUM) -> Iterator[Browser]:
        with sync_playwright() as playwright:
            chromium = playwright.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
            try:
                page = chromium.new_page(viewport=VIEWPORT)
                page.set_default_timeout(ACTION_TIMEOUT_MS)
                page.set_default_navigation_timeout(NAVIGATION_TIMEOUT_MS)
                yield cls(page, contact_url=contact_url)
            finally:
                chromium.close()

    def _heard(self, response: Response) -> None:
        # A page and its fragments all report. This handler runs when Playwright next yields,
        # which may be long after the answer came: the reading is dated by the browser's own
        # timing of the request (its moment on the server's clock), not by when we heard it.
        reading = reading_from_headers(response.headers, _sent_at(response))
        if reading is not None and (self._clock is None or reading.heard >= self._clock.heard):
            self._clock = reading

    def clock_reading(self) -> ClockReading | None:
        """The run's clock as the last page of the run that answered reported it."""
        return self._clock

    # --- what the model sees -------------------------------------------------------------

    def observe(self) -> Observation:
        """Number the elements in view, describe the page and take both screenshots."""
        self._settle()
        marking = {"attribute": MARK_ATTRIBUTE, "limit": MAX_MARKS}
        try:
            found = self.page.evaluate(_MARK_AND_DRAW, marking)
        except PlaywrightError:  # the page navigated while we looked: look once more
            self._settle()
            found = self.page.evaluate(_MARK_AND_DRAW, marking)
        marks = [Mark(m["number"], m["role"], m["name"], m["state"]) for m in found["marks"]]
        self._marks = {mark.number: mark for mark in marks}
        try:
            png = self._capture({"format": "png", "optimizeForSpeed": True})
            # Playwright cannot scale a screenshot; the protocol can. Its clip is in page
            # coordinates, so the viewport is where the page is scrolled to.
            viewport = {"x": found["left"], "y": found["top"], **VIEWPORT}
            jpeg = self._capture(
                {
                    "format": "jpeg",
                    "quality": TRANSCRIPT_JPEG_QUALITY,
                    "clip": {**viewport, "scale": TRANSCRIPT_SCALE},
                }
            )
        finally:
            title = self.page.evaluate(_REMOVE_MARKS)
        lines = [
            f"URL: {self.page.url}",
            f"Title: {title}",
            f"Scrolled to {found['scrollY']} px of a page {found['height']} px tall "
            f"(the viewport is {VIEWPORT['height']} px).",
            "Interactive elements in view (pass the number as `target`):",
            *(str(mark) for mark in marks),
        ]
        if not marks:
            lines.append("(none)")
        if found["hidden"]:
            lines.append(f"({found['hidden']} more in view, not listed: scroll or read_page)")
        summary = truncate(without_link_targets(self.markdown()), SUMMARY_CHARS)
        lines += ["", "Page text (start; read_page gives all of it, links included):", summary]
        return Observation(self.page.url, title, "\n".join(lines), png, jpeg)

    def _capture(self, params: dict) -> bytes:
        """A screenshot of the viewport through Chromium's DevTools protocol, on the page's one
        kept session: unlike Playwright's, it can scale (the transcript's small JPEG) and encode
        for speed (`optimizeForSpeed`: the same pixels, a PNG a fifth larger, in half the
        time — a look is on the path from seeing a change to acting on it)."""
        if self._devtools is None:
            self._devtools = self.page.context.new_cdp_session(self.page)
        return base64.b64decode(self._devtools.send("Page.captureScreenshot", params)["data"])

    def _settle(self) -> None:
        with contextlib.suppress(PlaywrightError):  # a slow page is described as it is now
            self.page.wait_for_load_state("load", timeout=NAVIGATION_TIMEOUT_MS)
        self.page.wait_for_timeout(SETTLE_MS)

    # --- WatchedPage, for wait_for --------------------------------------------------------

    def markdown(self) -> str:
        return html_to_markdown(self.page.content())

    def reload(self) -> None:
        self.page.reload(wait_until="domcontentloaded")

    # --- WatchedLivePage, for a fast-forward run's clock (apps.browser_agent.fast_forward) -

    def next_change(self) -> float | None:
        """When the page next changes with the clock, as the site's live pages declare it
        (`#sentinel-live[data-due]`, kept current by every push); None on any other page."""
        with contextlib.suppress(PlaywrightError):  # navigating: nothing declared
            due = self.page.evaluate(_DECLARED_DUE)
            return float(due) if isinstance(due, int | float) else None
        return None

    def catch_up(self, seq: int, now: float) -> None:
        """Return once the page shows log position `seq` at simulated time `now` (its pushes
        arrive within milliseconds); a page that does not catch up in time is reloaded."""
        try:
            self.page.wait_for_function(
                _CAUGHT_UP, arg=[seq, now], timeout=CATCH_UP_TIMEOUT_MS, polling=20
            )
        except PlaywrightError:
            with contextlib.suppress(PlaywrightError):
                self.reload()

    # --- the browser tools ----------------------------------------------------------------

    def visit_url(self, url: str) -> str:
        parts = urlsplit(url)
        if parts.scheme not in ("http", "https"):
            raise BrowserError(f"cannot visit {url!r}: only http:// and https:// URLs")
        if self._contact_path and parts.path.rstrip("/") == self._contact_path:
            # Opening the contact page counts as reporting: only the contact tool may do it.
            raise BrowserError("that is the contact page: report with the contact tool instead")
        self._attempt(lambda: self.page.goto(url, wait_until="domcontentloaded"))
        return f"opened {self.page.url}"

    def click(self, target: int) -> str:
        mark, locator = self._element(target)
        self._attempt(lambda: locator.click())
        return f"clicked {mark}"

    def type(self, target: int, text: str, submit: bool = False) -> str:
        mark, locator = self._element(target)
        if mark.role == "select":
            self._attempt(lambda: _choose_option(locator, text))  # BrowserError passes through
        else:
            self._attempt(lambda: locator.fill(text))
        if submit:
            self._attempt(lambda: locator.press("Enter"))
        return f"typed {text!r} into {mark}" + (" and pressed Enter" if submit else "")

    def press_key(self, key: str) -> str:
        self._attempt(lambda: self.page.keyboard.press(key))
        return f"pressed {key}"

    def scroll(self, direction: str) -> str:
        if direction not in ("up", "down"):
            raise BrowserError(f"direction must be 'up' or 'down', got {direction!r}")
        step = int(VIEWPORT["height"] * 0.8) * (1 if direction == "down" else -1)
        # The wheel at the centre scrolls whatever is under it, a list pane as well as the page.
        self.page.mouse.move(VIEWPORT["width"] / 2, VIEWPORT["height"] / 2)
        self._attempt(lambda: self.page.mouse.wheel(0, step))
        return f"scrolled {direction}"

    def go_back(self) -> str:
        before = self.page.url
        response = self._attempt(lambda: self.page.go_back(wait_until="domcontentloaded"))
        if response is None and self.page.url == before:
            raise BrowserError("there is no earlier page to go back to")
        return f"went back to {self.page.url}"

    def read_page(self) -> str:
        return truncate(self.markdown(), READ_PAGE_CHARS)

    def submit_contact_form(self, contact_url: str, message: str) -> str:
        """Open the contact page, write `message` in its form and submit it, as a person would.
        Returns the page's answer; raises BrowserError when the site refused the message."""
        self._attempt(lambda: self.page.goto(contact_url, wait_until="domcontentloaded"))
        form = self.page.locator("form").filter(has=self.page.locator("textarea[name=message]"))
        if form.count() == 0:
            raise BrowserError(f"no message form at {contact_url}")
        self._attempt(lambda: form.first.locator("textarea[name=message]").fill(message))
        submit = form.first.locator("button[type=submit], input[type=submit], button:not([type])")
        try:
            with self.page.expect_response(lambda r: r.request.method == "POST") as answer:
                submit.first.click()
            self.page.wait_for_load_state("domcontentloaded")
        except PlaywrightError as error:
            raise BrowserError(f"the contact form could not be sent: {first_line(error)}") from None
        text = " ".join(self.page.locator("body").inner_text().split())[:200]
        if not answer.value.ok:
            raise BrowserError(f"the contact form was refused ({answer.value.status}): {text}")
        return text

    # --- helpers --------------------------------------------------------------------------

    def _element(self, target: int) -> tuple[Mark, Locator]:
        mark = self._marks.get(target)
        locator = self.page.locator(f"[{MARK_ATTRIBUTE}='{target}']")
        if mark is None or locator.count() == 0:
            raise BrowserError(
                f"no element [{target}] on the page now; use a number from the latest description"
            )
        return mark, locator.first

    def _attempt(self, action: Callable[[], T]) -> T:
        try:
            return action()
        except PlaywrightError as error:
            raise BrowserError(first_line(error)) from None


def _sent_at(response: Response) -> float:
    """When the browser sent `response`'s request (its time.monotonic()): the moment the server
    read its clock for the answer, within the request's transfer time."""
    timing = response.request.timing
    offset = next((t for t in (timing["requestStart"], timing["responseStart"]) if t >= 0), None)
    now = time.monotonic()
    if offset is None or timing["startTime"] <= 0:
        return now
    return min(now, now - (time.time() * 1000 - timing["startTime"] - offset) / 1000)


def _choose_option(select: Locator, text: str) -> None:
    # Matched here rather than by select_option(label=…), which waits its whole timeout for an
    # option that may never exist.
    options = select.evaluate("s => Array.from(s.options, (o) => [o.label.trim(), o.value])")
    wanted = text.strip().lower()
    for label, value in options:
        if wanted in (label.lower(), value.lower()):
            select.select_option(value=value)
            return
    labels = ", ".join(repr(label) for label, _ in options)
    raise BrowserError(f"no option {text!r} in this select; its options are {labels}")


_IMAGE = re.compile(r"!\[[^\]]*\]\([^)]*\)")
_LINK = re.compile(r"\[([^\]]*)\]\([^)]*\)")


def without_link_targets(markdown: str) -> str:
    """Markdown with links as their text and images dropped: a step's summary is for reading,
    and URLs (long, with the run's token) would crowd the text out of its budget."""
    return _LINK.sub(r"\1", _IMAGE.sub("", markdown))


def truncate(text: str, limit: int) -> str:
    if len(text) <= limit:
        return text
    return text[:limit] + f"\n… ({len(text) - limit} more characters not shown)"
