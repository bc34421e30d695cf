"""Driving the explorer in a real browser (Playwright + Debian's chromium): used by the
browser tests and by ``bench/app_latency.py``."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
import time
from contextlib import contextmanager

CHROMIUM = os.environ.get("LEUVEN_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-quic", "--no-first-run",
        "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage"]
OVERVIEW = "Model overview"
RECORDING = "Recording"

# signature of a plot's data, found by its (invisible) title: changes whenever its traces change
PLOT_SIGNATURE = """(title) => {
  for (const el of document.querySelectorAll('.js-plotly-plot')) {
    const t = el.querySelector('.gtitle');
    if (!t || !t.textContent.startsWith(title) || !el._fullData) continue;
    let s = 0, n = 0;
    for (const tr of el._fullData) { const y = Array.from(tr.y || []); n += y.length;
      for (let i = 0; i < y.length; i += 7) s += (+y[i]) * (i + 1); const x = Array.from(tr.x || []);
      for (let i = 0; i < x.length; i += 7) s += (+x[i]) * 1e3 * (i + 3); }
    return n + ':' + s;
  }
  return null;
}"""

# the traces of a plot: name, x, y (numbers), for assertions on what is drawn
PLOT_TRACES = """(title) => {
  for (const el of document.querySelectorAll('.js-plotly-plot')) {
    const t = el.querySelector('.gtitle');
    if (!t || !t.textContent.startsWith(title) || !el._fullData) continue;
    return el._fullData.map(tr => ({name: tr.name || '', xaxis: tr.xaxis || 'x', text: Array.from(tr.text || []),
      x: Array.from(tr.x || []).map(Number), y: Array.from(tr.y || []).map(Number)}));
  }
  return null;
}"""


@contextmanager
def running_server(*extra_args, state_dir: str | None = None, timeout: float = 60.0):
    """Start ``leuven-friction serve --port 0`` in a subprocess with its own session state
    directory; yield (url, state_dir)."""
    own = None
    if state_dir is None:
        own = tempfile.TemporaryDirectory(prefix="lf-state-")
        state_dir = own.name
    env = dict(os.environ, LEUVEN_FRICTION_STATE_DIR=state_dir)
    log_path = os.path.join(state_dir, "server.log")
    log = open(log_path, "a")  # a file, not a pipe: a chatty server never blocks on a full pipe
    proc = subprocess.Popen([sys.executable, "-m", "leuven_friction.app.cli", "serve", "--port", "0", *extra_args],
                            stdout=log, stderr=subprocess.STDOUT, text=True, env=env)
    url = None
    t0 = time.time()
    while time.time() - t0 < timeout and proc.poll() is None:
        m = re.search(r"explorer at (http://\S+)", open(log_path).read())
        if m:
            url = m.group(1)
            break
        time.sleep(0.05)
    if url is None:
        proc.kill()
        raise RuntimeError("server did not start:\n" + open(log_path).read())
    try:
        yield url, state_dir
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()
        if own is not None:
            own.cleanup()


@contextmanager
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        try:
            yield b
        finally:
            b.close()


def open_app(b, url: str, width: int = 1600, height: int = 1000):
    page = b.new_page(viewport={"width": width, "height": height}, accept_downloads=True)
    page.goto(url)
    page.wait_for_selector("text=Stribeck ⁺", timeout=60_000)
    wait_plot(page, OVERVIEW, None, timeout=60)
    dismiss_webgl_notice(page)
    return page


def dismiss_webgl_notice(page) -> None:
    """Headless chromium renders WebGL in software and viser says so in a notification that
    sits over the plot tabs; a person with a GPU never sees it. Close it."""
    for _ in range(50):
        note = page.locator(".mantine-Notification-root", has_text="Software WebGL")
        if note.count():
            note.first.locator("button").first.click()
            return
        time.sleep(0.1)


def plot_signature(page, title: str):
    return page.evaluate(PLOT_SIGNATURE, title)


def plot_traces(page, title: str):
    return page.evaluate(PLOT_TRACES, title)


def wait_plot(page, title: str, old, timeout: float = 30.0):
    """Wait until the plot titled ``title`` has data different from ``old``; return it."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        sig = plot_signature(page, title)
        if sig is not None and sig != old and not sig.startswith("0:"):
            return sig
        time.sleep(0.02)
    raise TimeoutError(f"plot {title!r} did not change within {timeout} s")


def _row(page, label: str):
    return page.locator("label", has_text=label).first.locator(
        "xpath=ancestor::div[contains(@class, 'mantine-Flex-root')][1]")


def text_box(page, label: str):
    """The text input of a parameter control, by its label (e.g. 'Fs⁺ (N·m)')."""
    return _row(page, label).locator("input").first


def slider(page, label: str):
    """The slider under a parameter's text box."""
    return _row(page, label).locator('xpath=following::*[@role="slider"][1]')


def upload_input(page, n: int = 0):
    return page.locator('input[type=file][id^="file_upload_"]').nth(n)


def alerts(page):
    return [t for t in page.get_by_role("alert").all_inner_texts() if "WebGL" not in t]


def measure_latency(page, label: str = "Fs⁺ (N·m)", changes: int = 20, title: str = OVERVIEW) -> list[float]:
    """Milliseconds from a slider key press to the overview plot showing new data, measured
    in the page's clock (performance.now): the JS side polls every animation frame."""
    page.evaluate("""(title) => {
        window.__lat = {title, last: null, changes: []};
        const sigf = """ + PLOT_SIGNATURE + """;
        const tick = () => { const s = sigf(window.__lat.title);
            if (s !== null && s !== window.__lat.last) { window.__lat.changes.push(performance.now()); window.__lat.last = s; }
            requestAnimationFrame(tick); };
        tick(); }""", title)
    knob = slider(page, label)
    out = []
    for i in range(changes):
        n0 = page.evaluate("window.__lat.changes.length")
        t_press = page.evaluate("performance.now()")
        knob.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
        t0 = time.time()
        while page.evaluate("window.__lat.changes.length") == n0:
            if time.time() - t0 > 20:
                raise TimeoutError("plot did not update after a slider change")
            time.sleep(0.005)
        out.append(page.evaluate(f"window.__lat.changes[{n0}]") - t_press)
        time.sleep(0.15)  # the browser merges slider updates closer than ~50 ms
    return out


def choose(page, label: str, option: str, exact_label: bool = True) -> None:
    """Pick ``option`` in the dropdown labelled ``label``."""
    lab = page.locator("label").filter(has_text=label)
    if exact_label:
        lab = page.locator("label", has_text=__import__("re").compile(f"^{__import__('re').escape(label)}$"))
    fid = lab.first.get_attribute("for")
    page.locator(f'[id="{fid}"]').click()
    page.get_by_role("option", name=option, exact=True).click()


def upload_for(page, button_text: str):
    """The hidden file input behind the upload button showing ``button_text``."""
    btn = page.locator("button", has_text=button_text).first
    for up in ("..", "../..", "../../.."):
        inp = btn.locator(f"xpath={up}//input[@type='file']")
        if inp.count():
            return inp.first
    raise LookupError(f"no file input next to {button_text!r}")


def layout_report(page, title: str = OVERVIEW) -> dict:
    """Page width against the window, and where the plot titled ``title`` ends."""
    return page.evaluate("""(title) => {
      let plot = null;
      for (const el of document.querySelectorAll('.js-plotly-plot')) {
        const t = el.querySelector('.gtitle'); if (t && t.textContent.startsWith(title)) plot = el; }
      const b = plot ? plot.getBoundingClientRect() : null;
      const tabs = [...document.querySelectorAll('[role=tab]')].map(e => e.getBoundingClientRect());
      const notes = [...document.querySelectorAll('.mantine-Notification-root')].map(e => e.getBoundingClientRect());
      return {scrollWidth: document.documentElement.scrollWidth, innerWidth: innerWidth, innerHeight: innerHeight,
              plot: b ? {left: b.left, right: b.right, top: b.top, bottom: b.bottom} : null,
              tabs: tabs.map(r => ({left: r.left, right: r.right, top: r.top, bottom: r.bottom})),
              notes: notes.map(r => ({left: r.left, right: r.right, top: r.top, bottom: r.bottom}))};
    }""", title)
