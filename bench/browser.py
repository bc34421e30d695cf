"""Driving the explorer in a real browser (Playwright + Debian's chromium): shared by the
browser tests and the latency benchmark."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from contextlib import contextmanager

CHROMIUM = os.environ.get("LEUVEN_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-quic", "--no-first-run",
        "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage"]

# signature of a plot's data, found by its title: changes whenever its traces change
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


@contextmanager
def running_server(*extra_args, timeout: float = 60.0):
    """Start ``leuven-friction serve --port 0`` in a subprocess; yield its URL."""
    proc = subprocess.Popen([sys.executable, "-m", "leuven_friction.app.cli", "serve", "--port", "0", *extra_args],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    url = None
    t0 = time.time()
    lines = []
    while time.time() - t0 < timeout:
        line = proc.stdout.readline()
        if not line:
            break
        lines.append(line)
        m = re.search(r"explorer at (http://\S+)", line)
        if m:
            url = m.group(1)
            break
    if url is None:
        proc.kill()
        raise RuntimeError("server did not start:\n" + "".join(lines))
    try:
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()


@contextmanager
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        try:
            yield b
        finally:
            b.close()


def open_app(b, url: str):
    page = b.new_page(viewport={"width": 1600, "height": 1000}, accept_downloads=True)
    page.goto(url)
    page.wait_for_selector("text=Stribeck +", timeout=60_000)
    wait_plot(page, "Presliding hysteresis", None)
    return page


def plot_signature(page, title: str):
    return page.evaluate(PLOT_SIGNATURE, title)


def wait_plot(page, title: str, old, timeout: float = 30.0):
    """Wait until the plot titled ``title`` has data different from ``old``; return it."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        sig = plot_signature(page, title)
        if sig is not None and sig != old and not sig.startswith("0:"):
            return sig
        time.sleep(0.02)
    raise TimeoutError(f"plot {title!r} did not change within {timeout} s")


def slider(page, label: str):
    fid = page.locator("label", has_text=label).first.get_attribute("for")
    return page.locator(f'[id="{fid}"] [role="slider"]')


def upload_input(page):
    return page.locator('input[type=file][id^="file_upload_"]').first


def measure_latency(page, label: str = "Fs+", changes: int = 20, title: str = "Presliding hysteresis") -> list[float]:
    """Milliseconds from a slider key press to the hysteresis plot showing new data, measured
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
