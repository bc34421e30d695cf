"""The explorer in a real browser (Playwright driving Debian's chromium).

Screenshots go to ``artifacts/`` (kept by CI as test artifacts)."""

import os
import time
from pathlib import Path

import pytest

pytest.importorskip("playwright")
from bench.browser import CHROMIUM, browser, open_app, plot_signature, running_server, slider, upload_input, wait_plot  # noqa: E402

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(not os.path.exists(CHROMIUM) and not os.environ.get("CI"), reason="chromium not installed"),
]

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "artifacts"
HYST = "Presliding hysteresis"


@pytest.fixture(scope="module")
def app_url():
    with running_server() as url:
        yield url


@pytest.fixture(scope="module")
def chromium():
    with browser() as b:
        yield b


def shot(page, name):
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / f"{name}.png"))


def alerts(page):
    return [t for t in page.get_by_role("alert").all_inner_texts() if "WebGL" not in t]


def test_page_loads_with_plots(chromium, app_url):
    page = open_app(chromium, app_url)
    assert page.locator("label", has_text="Fs+").count() >= 1
    assert page.locator("label", has_text="σ2−").count() >= 1  # negative-side sliders exist (folder collapsed)
    sig = plot_signature(page, HYST)
    assert sig is not None and int(sig.split(":")[0]) > 100  # two models' A→B→C→D paths drawn
    shot(page, "app_loaded")
    page.close()


def test_slider_changes_hysteresis_plot(chromium, app_url):
    page = open_app(chromium, app_url)
    before = plot_signature(page, HYST)
    knob = slider(page, "F1")  # the first transition-curve knot: the initial stiffness
    page.get_by_text("Transition curve knots").click()
    time.sleep(0.3)
    knob.focus()
    for _ in range(40):
        knob.press("ArrowRight")
    after = wait_plot(page, HYST, before)
    assert after != before
    shot(page, "after_slider")
    page.close()


def test_upload_fits_and_export_yaml_loads_back(chromium, app_url, tmp_path):
    from leuven_friction.identify.paramfile import load_params

    page = open_app(chromium, app_url)
    upload_input(page).set_input_files(str(ROOT / "sample_data" / "session_mixed.csv"))
    page.wait_for_selector("text=Fit done", timeout=120_000)
    page.get_by_role("tab", name="Fit").click()
    page.wait_for_selector("text=Transition curve F_d", timeout=30_000)
    # the parameter table in the controls shows ± uncertainties
    table = page.locator("table").first.inner_text()
    assert "±" in table
    shot(page, "after_fit")
    with page.expect_download(timeout=30_000) as dl:
        page.get_by_role("button", name="Export YAML").click()
    out = tmp_path / "exported.yaml"
    dl.value.save_as(str(out))
    p = load_params(out)
    # the fitted values came back: Table I within a few of the stated standard deviations
    assert abs(p.stribeck.negative.Fc + 52.0) < 5 * p.uncertainty["stribeck.negative.Fc"]
    assert p.provenance["estimator"].startswith("Markov")
    page.close()


def test_malformed_csv_shows_error_and_page_keeps_working(chromium, app_url, tmp_path):
    page = open_app(chromium, app_url)
    bad = tmp_path / "broken.csv"
    bad.write_text("time,position,torque\n0,0,1\n1,abc,2\n" + "".join(f"{i},{i},1\n" for i in range(2, 20)))
    upload_input(page).set_input_files(str(bad))
    page.wait_for_selector("text=Fit failed", timeout=30_000)
    msgs = " ".join(alerts(page))
    assert "broken.csv" in msgs and "row 3" in msgs
    shot(page, "malformed_csv")
    before = plot_signature(page, HYST)
    knob = slider(page, "Fs+")
    knob.focus()
    for _ in range(30):
        knob.press("ArrowLeft")
    assert wait_plot(page, HYST, before) != before  # still alive
    page.close()


def test_two_tabs_do_not_share_uploads(chromium, app_url):
    a = open_app(chromium, app_url)
    b = open_app(chromium, app_url)
    upload_input(a).set_input_files(str(ROOT / "sample_data" / "constant_velocity.csv"))
    a.wait_for_selector("text=Fit done", timeout=120_000)
    time.sleep(1.0)
    assert b.get_by_text("Fit done").count() == 0
    b.get_by_role("tab", name="Fit").click()
    assert b.get_by_text("Upload a CSV recording").count() == 1
    a.close()
    b.close()


def test_latency_benchmark_runs(chromium, app_url):
    """Measured, not asserted against a wall-clock limit: the numbers go to artifacts/."""
    import json

    import numpy as np

    from bench.browser import measure_latency

    page = open_app(chromium, app_url)
    lat = measure_latency(page, changes=22)[2:]
    assert len(lat) == 20 and all(v > 0 for v in lat)
    ARTIFACTS.mkdir(exist_ok=True)
    (ARTIFACTS / "app_latency.json").write_text(json.dumps(
        {"median_ms": float(np.median(lat)), "p95_ms": float(np.percentile(lat, 95)), "samples_ms": lat}, indent=2))
    page.close()


def test_diagnose_tab_names_the_effect(chromium, app_url):
    page = open_app(chromium, app_url)
    upload_input(page).set_input_files(str(ROOT / "sample_data" / "effect_position_periodic.csv"))
    page.wait_for_selector("text=Fit done", timeout=120_000)
    page.get_by_role("button", name="Diagnose").click()
    page.wait_for_selector("text=Effect found", timeout=180_000)
    page.get_by_role("tab", name="Diagnose").click()
    page.wait_for_selector("text=Missing effect: position_periodic", timeout=30_000)
    wait_plot(page, "Measured and simulated friction", None)
    shot(page, "diagnose_tab")
    page.close()
