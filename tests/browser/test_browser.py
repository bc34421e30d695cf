"""The explorer in a real browser (Playwright driving Debian's chromium), used as a person would.

Screenshots go to ``artifacts/`` (kept by CI as test artifacts). One server per module; each
test opens its own page. Bounded: every wait has a timeout, the whole file runs in minutes.
"""

import os
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("playwright")
from tests.browser.helpers import (  # noqa: E402
    CHROMIUM, OVERVIEW, RECORDING, browser, open_app, plot_signature, plot_traces, running_server, slider, text_box,
    upload_input, wait_plot,
)

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(not os.path.exists(CHROMIUM) and not os.environ.get("CI"), reason="chromium not installed"),
]

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "artifacts"
FS = "Fs⁺ (N·m)"
VS = "vs⁺ (rad/s)"


@pytest.fixture(scope="module")
def server():
    with running_server() as (url, state_dir):
        yield url, state_dir


@pytest.fixture(scope="module")
def chromium():
    with browser() as b:
        yield b


def shot(page, name):
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / f"{name}.png"))


def status_text(page) -> str:
    return page.locator("body").inner_text()


def wait_text(page, text: str, timeout: float = 60.0):
    page.wait_for_selector(f"text={text}", timeout=timeout * 1000)


def hysteresis_D(page) -> float:
    """Friction at point D of the drawn A→B→C→D loop (the marked points)."""
    tr = next(t for t in plot_traces(page, OVERVIEW) if t["name"] == "A–D")
    return tr["y"][tr["text"].index("D")]


def test_scientific_notation_in_a_number_box(chromium, server):
    """`1e-3`, `2.5E5` and `0,005` are read exactly; `abc` is refused with a message and not applied."""
    page = open_app(chromium, server[0])
    box = text_box(page, VS)
    before = plot_signature(page, OVERVIEW)
    box.fill("1e-3")
    box.press("Enter")
    after = wait_plot(page, OVERVIEW, before)
    # the Stribeck curve now falls from Fs to Fc around |v| = 1e-3: S(1e-3) is halfway-ish, S(1e-2) ≈ Fc
    strib = [t for t in plot_traces(page, OVERVIEW) if t["name"] == "leuven (v > 0)"][0]
    v, S = np.array(strib["x"]), np.array(strib["y"])
    Fs, Fc = 36.0, 27.0
    s_at = lambda x: np.interp(x, v, S) - 7.7 * x  # noqa: E731  (minus the viscous part)
    assert abs(s_at(1e-3) - (Fc + (Fs - Fc) * np.exp(-1.0))) < 0.05
    assert abs(s_at(3e-2) - (Fc + (Fs - Fc) * np.exp(-np.sqrt(30)))) < 0.05
    assert box.input_value() == "1e-3"
    # refused input: a message, the model (and plot) unchanged
    box.fill("abc")
    box.press("Enter")
    wait_text(page, "'abc' is not a number", 15)
    time.sleep(0.5)
    assert plot_signature(page, OVERVIEW) == after
    # large numbers in E notation and decimal commas
    fs_box = text_box(page, FS)
    fs_box.fill("2.5E2")
    fs_box.press("Enter")
    after2 = wait_plot(page, OVERVIEW, after)
    box.fill("0,005")
    box.press("Enter")
    wait_plot(page, OVERVIEW, after2)
    page.get_by_role("tab", name="Parameter sets").click()
    table = page.locator("table").first.inner_text()
    assert "250" in table and "0.005" in table
    shot(page, "number_entry")
    page.close()


def test_slider_moves_the_plot_and_the_box(chromium, server):
    page = open_app(chromium, server[0])
    box = text_box(page, "F_d(z1) (N·m)") if page.get_by_text("F_d(z1)").count() else None
    page.get_by_text("Transition curve knots").click()
    time.sleep(0.3)
    box = text_box(page, "F_d(z1) (N·m)")
    v0 = float(box.input_value())
    d0 = hysteresis_D(page)
    before = plot_signature(page, OVERVIEW)
    knob = slider(page, "F_d(z1) (N·m)")
    knob.focus()
    for _ in range(15):
        knob.press("ArrowRight")
        time.sleep(0.03)
    wait_plot(page, OVERVIEW, before)
    time.sleep(1.0)
    v1 = float(box.input_value())
    assert v1 > v0  # the box follows the slider
    # a stiffer first segment: the loop reaches D at a smaller displacement, same force
    tr = next(t for t in plot_traces(page, OVERVIEW) if t["name"] == "A–D")
    assert abs(tr["y"][tr["text"].index("D")] - d0) < 1e-6 * max(1.0, abs(d0)) + 0.5
    page.close()
