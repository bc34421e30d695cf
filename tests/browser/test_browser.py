"""The explorer in a real browser (Playwright driving Debian's chromium), used as a person would.

Screenshots go to ``artifacts/`` (kept by CI as test artifacts). One server per module; each
test opens its own page. Bounded: every wait has a timeout, the whole file runs in minutes.
"""

import os
import re
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("playwright")
from tests.browser.helpers import (  # noqa: E402
    CHROMIUM, OVERVIEW, RECORDING, browser, choose, layout_report, open_app, plot_signature, plot_traces, running_server,
    slider, text_box, upload_for, wait_plot,
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


def hysteresis_D(page) -> tuple[float, float]:
    """(displacement, friction) at point D of the drawn A→B→C→D loop (the marked points)."""
    tr = next(t for t in plot_traces(page, OVERVIEW) if t["name"] == "A–D")
    i = tr["text"].index("D")
    return tr["x"][i], tr["y"][i]


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
    # the reason names the field once (the notice had read "vs⁺: vs⁺: 'abc' is not a number")
    assert not re.search(r"(\S+⁺): \1:", page.inner_text("body")), page.inner_text("body")
    assert plot_signature(page, OVERVIEW) == after
    # the box goes back to the value the model still has: a refused entry is not left showing
    assert float(box.input_value().replace(",", ".")) == pytest.approx(1e-3), box.input_value()
    # large numbers in E notation and decimal commas
    fs_box = text_box(page, FS)
    fs_box.fill("2.5E2")
    fs_box.press("Enter")
    after2 = wait_plot(page, OVERVIEW, after)
    box.fill("0,005")
    box.press("Enter")
    wait_plot(page, OVERVIEW, after2)
    assert table_value(page, "Fs⁺", 250.0) == 250.0 and table_value(page, "vs⁺", 0.005) == 0.005
    # physically odd but valid: |Fc| > |Fs| is applied and warned about
    text_box(page, "Fc⁺ (N·m)").fill("300")
    text_box(page, "Fc⁺ (N·m)").press("Enter")
    wait_text(page, "friction would rise with speed", 15)
    assert table_value(page, "Fc⁺", 300.0) == 300.0
    shot(page, "number_entry")
    page.close()


def test_slider_moves_the_plot_and_the_box(chromium):
    # a server of its own: the model starts at the paper's (Table II), whatever other tests set
    with running_server() as (url, _):
        _slider_moves_the_plot_and_the_box(open_app(chromium, url))


def _slider_moves_the_plot_and_the_box(page):
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
    # D (30 N·m, past B: the loop is back on its virgin curve) lies where F_d runs between the
    # first and second knots (Table II: 16.4 and 75.1 N·m); raising F_d(z1) raises F_d all along
    # that segment, so the drawn loop reaches D's force at a smaller displacement
    x1, f1 = hysteresis_D(page)
    assert abs(f1 - 30.0) < 0.5 and abs(d0[1] - 30.0) < 0.5  # the applied force at D, whatever the curve
    assert x1 < d0[0] * (1.0 - 0.1 * (v1 - v0) / v0), (d0, (x1, f1), v0, v1)
    page.close()


# ---------------------------------------------------------------- the user's own recording
@pytest.fixture(scope="module")
def tribometer_file(tmp_path_factory):
    """A tribometer-like recording from the independent generator (synth/recordings.py):
    tab-separated, position in mm, friction in µN logged with the reaction sign, a normal-load
    column — and the position column named so that the loader cannot recognise it."""
    from synth.recordings import make_recording

    df, truth = make_recording("tribometer", seed=3)
    df = df.rename(columns={"Position [mm]": "Stage [mm]"})
    path = tmp_path_factory.mktemp("data") / "pin_on_disc_run7.tsv"
    df.to_csv(path, sep="\t", index=False)
    return path, truth


def table_value(page, label: str, expect: float | None = None, timeout: float = 30.0) -> float:
    """A value of the current-model table (Parameter sets tab). The table follows the model
    within a fraction of a second: with ``expect``, wait up to ``timeout`` for that value."""
    page.get_by_role("tab", name="Parameter sets").click()
    table = page.locator("xpath=//*[contains(text(), 'Current model')]/following::table[1]")
    row = table.locator("tr", has=page.locator("td", has_text=re.compile(f"^{re.escape(label)}$")))
    t0 = time.time()
    while True:
        v = float(row.first.locator("td").nth(1).inner_text().split("±")[0])
        if expect is None or v == pytest.approx(expect, rel=1e-4) or time.time() - t0 > timeout:
            return v
        time.sleep(0.1)


def test_upload_remap_fit_accept_diagnose_discard_reload(chromium, tribometer_file):
    path, truth = tribometer_file
    with running_server() as (url, _):
        page = open_app(chromium, url, 1280, 720)
        upload_for(page, "Upload recording").set_input_files(str(path))
        page.get_by_role("tab", name="Data").click()
        # plotted before any fit, with what was (not) recognised
        wait_plot(page, RECORDING, None)
        assert "Friction [uN]" in page.content() and "not found" in page.content()
        friction = next(t for t in plot_traces(page, RECORDING) if t["name"] == "friction")
        # µN converted to N: the generator's Coulomb level is of order 1 N, never 1e6
        assert 0.05 < np.percentile(np.abs(friction["y"]), 90) < 50
        assert "--columns" not in page.locator("body").inner_text()
        shot(page, "upload_unrecognised_1280")
        # remap: the position is the "Stage [mm]" column
        choose(page, "position", "Stage [mm]")
        page.get_by_role("button", name="Apply columns").click()
        wait_text(page, "displacement / joint angle", 60)
        sign_line = page.locator("text=friction sign").first.inner_text()
        assert "reaction" in sign_line  # the generator logged the reaction force; the page says so
        # the fit comes back as a proposal: numbers, gap, estimated/held
        wait_text(page, "Accept", 240)
        # its buttons come before its details: Accept is on the first screen of the controls
        accept = page.get_by_role("button", name="Accept").first.bounding_box()
        assert accept is not None and accept["y"] + accept["height"] <= 720, accept
        prop = page.locator("text=Gap").first.locator("xpath=ancestor::div[2]").inner_text()
        assert "Held" in page.locator("body").inner_text() and "Estimated" in page.locator("body").inner_text()
        gaps = [float(g) for g in re.findall(r"([0-9.]+(?:e-?\d+)?) N", prop)[:2]]
        assert len(gaps) == 2 and gaps[1] < gaps[0]  # the proposal explains the data better than the paper's robot
        shot(page, "proposal_1280")
        proposed_fc = float(page.locator("xpath=//*[contains(text(), 'proposed')]/ancestor::table[1]//tr[td[1][normalize-space()='Fc⁺']]/td[3]")
                            .first.inner_text().split("±")[0])
        # nothing changed before accepting
        assert table_value(page, "Fs⁺") == pytest.approx(36.0)
        page.get_by_role("button", name="Accept").click()
        time.sleep(1.0)
        fc = table_value(page, "Fc⁺", proposed_fc)
        assert fc == pytest.approx(proposed_fc, rel=1e-4)  # the accepted set is the proposal
        # in the generator's range of sliding friction (Fc..Fs), in N: units and sign came through
        true = truth.stribeck["positive"]
        assert 0.75 * true["Fc"] < fc < 1.25 * true["Fs"], (fc, true)
        assert "fit of pin_on_disc_run7.tsv" in page.locator("body").inner_text()
        # the controls now speak the data's units (N, m), not the paper's (N·m, rad)
        page.locator("label", has_text=re.compile(r"^Fs⁺ \(N\)$")).first.wait_for(timeout=10_000)
        assert float(text_box(page, "Fc⁺ (N)").input_value()) == pytest.approx(fc, rel=1e-4)
        page.get_by_role("tab", name="Model").click()
        time.sleep(1.0)
        shot(page, "after_accept_1280")

        # a long job can be cancelled, and says so
        page.get_by_role("button", name="Diagnose").click()
        page.get_by_role("button", name="Cancel diagnosis").click()
        wait_text(page, "Diagnosis cancelled", 120)
        assert page.get_by_role("button", name="Diagnose").first.is_enabled()
        # diagnose: the generator's tribometer ramps its normal load while the contact sticks
        # (friction ∝ load), which the accepted fit does not hold: normal_load is proposed. It has
        # no scale that must settle, so it is named with the "Require settling" box (ticked by
        # default) cleared as well; the diagnosis's own text says which policy it ran with
        settle = page.get_by_label("Require settling")
        assert settle.is_checked()
        settle.uncheck()
        page.get_by_role("button", name="Diagnose").click()
        page.wait_for_selector("text=Cancel diagnosis", timeout=30_000)
        # a second press does not start a second job: the button is disabled while it runs
        assert page.get_by_role("button", name="Diagnose").first.is_disabled()
        page.wait_for_selector("text=Cancel diagnosis", state="hidden", timeout=300_000)
        body = page.locator("body").inner_text()
        found = re.search(r"Found ([^\n]+?): see the proposal", body)
        assert found and found.group(1).startswith("normal_load"), body[-3000:]
        # with settling not required, anything named beside the load whose size the data do not
        # tell from none is said to be so (a softening here, h within 2 σ of 0)
        as_written = re.search(r"As written: [^\n]*", body)
        assert as_written, body[-3000:]
        softening = as_written.group(0).partition("cyclic_softening: ")[2]
        assert not softening or "(not determined: h = " in softening, as_written.group(0)
        # the proposal gives the effect's values as written (they have no controls)
        # (after any stiffness effect held with it: a presliding range following the load, say)
        written = re.search(r"As written: [^\n]*?normal_load: [^\n]*?alpha = ([0-9.]+)", body)
        assert written and 0.3 < float(written.group(1)) < 3.0, body[-3000:]
        # the diagnosis figures' data in one CSV, one header
        page.get_by_role("tab", name="Diagnose").click()
        shown = page.locator("body").inner_text()
        assert "Candidates, last round" in shown and "settling required" not in shown  # the box reached the diagnosis
        assert "diagnose --" not in shown  # the command line's options are the command line's, not the page's
        # the report's long lines wrap inside the tab: none runs past the block's right edge
        over = page.evaluate("""() => [...document.querySelectorAll('pre')].filter(e => e.offsetParent &&
            e.textContent.includes('Candidates, last round')).map(e => e.scrollWidth - e.clientWidth)""")
        assert over and max(over) <= 1, over
        with page.expect_download(timeout=30_000) as dl:
            page.get_by_role("button", name="Save plot data (CSV)").locator("visible=true").first.click()
        rows = Path(dl.value.path()).read_text().splitlines()
        assert rows[0].startswith("figure,trace") and sum(r.startswith("figure,") for r in rows) == 1
        assert {r.split(",")[0] for r in rows[1:]} >= {"diagnosis_1", "diagnosis_2"}
        page.get_by_role("button", name="Discard").click()
        time.sleep(0.5)
        assert table_value(page, "Fc⁺", fc) == pytest.approx(fc, rel=1e-4)  # discarded: the accepted fit stays
        shot(page, "after_diagnose_1280")

        # reload: the session comes back (accepted fit, recording, history)
        page.reload()
        page.wait_for_selector("text=Session restored", timeout=60_000)
        assert table_value(page, "Fc⁺", fc) == pytest.approx(fc, rel=1e-4)
        page.get_by_role("tab", name="Data").click()
        wait_plot(page, RECORDING, None, timeout=60)
        assert "pin_on_disc_run7.tsv" in page.locator("body").inner_text()
        page.close()


def test_load_yaml_in_the_page(chromium, server, tmp_path):
    from leuven_friction.identify.paramfile import params_to_yaml
    from leuven_friction.model import default_params
    from leuven_friction.model.params import with_value

    p = with_value(with_value(default_params(), "stribeck.positive.Fs", 50.0), "stribeck.positive.Fc", 41.5)
    f = tmp_path / "stage_axis.yaml"
    f.write_text(params_to_yaml(p))
    page = open_app(chromium, server[0])
    before = plot_signature(page, OVERVIEW)
    upload_for(page, "Load parameter YAML").set_input_files(str(f))
    wait_text(page, "Loaded", 30)
    wait_plot(page, OVERVIEW, before)
    assert text_box(page, FS).input_value() == "50"
    assert table_value(page, "Fc⁺", 41.5) == pytest.approx(41.5)
    # the history holds the start and the loaded file: compare, then restore the start
    page.get_by_role("tab", name="Parameter sets").click()
    start_title = page.locator("xpath=//label[text()='set']/following::input[1]").input_value()
    assert "loaded stage_axis.yaml" in start_title  # the newest set is selected
    page.locator("xpath=//label[text()='set']/following::input[1]").click()
    page.get_by_role("option", name=re.compile(r"^1\. start")).click()
    compare = page.locator("xpath=//*[contains(text(), 'Restore this set')]/following::table[1]").inner_text()
    assert "50" in compare and "36" in compare  # Fs⁺ now vs at the start
    page.get_by_role("button", name="Restore this set").click()
    time.sleep(1.0)
    assert table_value(page, "Fs⁺", 36.0) == pytest.approx(36.0)
    f2 = tmp_path / "stage_axis_again.yaml"  # (the same file twice is not a new upload for the browser)
    f2.write_text(f.read_text())
    upload_for(page, "Load parameter YAML").set_input_files(str(f2))
    wait_text(page, "Loaded stage_axis_again.yaml", 30)
    # a broken file is refused with its name, and changes nothing
    bad = tmp_path / "broken.yaml"
    bad.write_text("stribeck: [1, 2\n")
    upload_for(page, "Load parameter YAML").set_input_files(str(bad))
    wait_text(page, "broken.yaml", 30)
    assert table_value(page, "Fc⁺", 41.5) == pytest.approx(41.5)

    def said_of_broken() -> list:  # what the page says about broken.yaml, the browser's upload toast aside
        return [line for line in page.locator("body").inner_text().splitlines()
                if "broken.yaml" in line and not line.startswith("Uploading broken.yaml")]

    assert said_of_broken()
    # the next upload is of something else: the YAML's error goes, and the note at the top names
    # the recording now in the session
    t = np.arange(2000) * 2e-3
    q = 0.2 * np.sin(2 * np.pi * 0.5 * t)
    rec = tmp_path / "joint_after.csv"
    rec.write_text("time [s],position [rad],torque [N*m]\n"
                   + "".join(f"{a:.4f},{b:.8f},{3.0 * np.tanh(c / 0.01):.5f}\n" for a, b, c in zip(t, q, np.gradient(q, t))))
    upload_for(page, "Upload recording").set_input_files(str(rec))
    wait_text(page, "Recording joint_after.csv uploaded", 30)
    assert not said_of_broken(), said_of_broken()
    page.close()


@pytest.mark.parametrize("width, height", [(1600, 1000), (1280, 720)])
def test_layout_fits_the_screen(chromium, server, width, height):
    page = open_app(chromium, server[0], width, height)
    time.sleep(3.0)  # the plot panel widens once the browser layout settled
    r = layout_report(page)
    assert r["scrollWidth"] <= r["innerWidth"], r  # no horizontal scroll
    assert r["plot"] is not None and r["plot"]["bottom"] <= r["innerHeight"], r  # the four views above the fold
    assert r["plot"]["right"] <= r["innerWidth"] + 1
    assert r["plot"]["right"] - r["plot"]["left"] >= 0.55 * width  # large: most of the window
    # the controls keep their width: the upload button is whole and not covered
    clipped = page.evaluate("""() => { const b = [...document.querySelectorAll('button')].find(e => e.textContent.includes('Upload recording'));
        const r = b.getBoundingClientRect(); const e = document.elementFromPoint(r.right - 4, r.top + r.height / 2);
        return {width: r.width, whole: !!e && b.contains(e)}; }""")
    assert clipped["width"] >= 200 and clipped["whole"], clipped
    # our messages are on the page, not pop-ups over the tabs
    assert not r["notes"], r
    shot(page, f"layout_{width}x{height}")
    page.close()


def test_plot_saved_as_png_and_csv(chromium, server, tmp_path):
    import csv

    page = open_app(chromium, server[0])
    traces = plot_traces(page, OVERVIEW)
    with page.expect_download(timeout=30_000) as dl:
        page.get_by_role("button", name="Save plot data (CSV)").first.click()
    out = tmp_path / "overview.csv"
    dl.value.save_as(str(out))
    rows = list(csv.DictReader(out.open()))
    drawn = next(t for t in traces if t["name"] == "A–D")
    saved = [r for r in rows if r["trace"] == "A–D"]
    assert [float(r["y"]) for r in saved] == pytest.approx(drawn["y"], rel=1e-9)  # the numbers behind the plot
    # Plotly's own PNG button (the only one kept in the mode bar)
    page.locator(".js-plotly-plot").first.hover()
    with page.expect_download(timeout=30_000) as dl:
        page.locator('.js-plotly-plot .modebar-btn[data-title="Download plot as a PNG"]').first.click()
    png = tmp_path / "overview.png"
    dl.value.save_as(str(png))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    page.close()


def test_a_recognised_column_set_to_none_stays_none(chromium, tmp_path):
    # a tachometer the user does not trust: "(none)" for velocity is a choice, not a blank the
    # loader fills again with the column it recognises
    t = np.arange(3000) * 2e-3
    q = 0.2 * np.sin(2 * np.pi * 0.5 * t)
    v = np.gradient(q, t)
    tau = 3.0 * np.tanh(v / 0.01) + 0.5 * v + 0.01 * np.random.default_rng(0).normal(size=t.size)
    path = tmp_path / "joint_tacho.csv"
    path.write_text("time [s],position [rad],velocity [rad/s],torque [N*m]\n"
                    + "".join(f"{a:.4f},{b:.8f},{c:.6f},{d:.5f}\n" for a, b, c, d in zip(t, q, v, tau)))
    with running_server() as (url, _):
        page = open_app(chromium, url, 1280, 720)
        upload_for(page, "Upload recording").set_input_files(str(path))
        page.get_by_role("tab", name="Data").click()
        wait_plot(page, RECORDING, None)
        fid = page.locator("label", has_text=re.compile(r"^velocity$")).first.get_attribute("for")
        dropdown = page.locator(f'[id="{fid}"]')
        assert dropdown.input_value() == "velocity [rad/s]"  # recognised by its name
        choose(page, "velocity", "(none)")
        page.get_by_role("button", name="Apply columns").click(timeout=120_000)  # (after the first fit)
        wait_text(page, "ignored columns: velocity [rad/s]", 60)
        assert dropdown.input_value() == "(none)"
        page.close()


def test_diagnosis_report_reads_in_the_window(chromium, tribometer_file, tmp_path):
    """`diagnose --html` opened in the browser at 1280 px: no horizontal scroll (its text report
    wraps; one line of it had made the page 5,200 px wide), every figure drawn with data, and the
    step-by-step plot's labels inside the plot's own box."""
    from leuven_friction.app.cli import main

    path, _ = tribometer_file
    report = tmp_path / "report.html"
    assert main(["diagnose", str(path), "--columns", "position=Stage [mm]", "--html", str(report)]) == 0
    page = chromium.new_page(viewport={"width": 1280, "height": 900})
    page.goto(report.as_uri())
    page.wait_for_function("() => [...document.querySelectorAll('.js-plotly-plot')].length >= 4 && "
                           "[...document.querySelectorAll('.js-plotly-plot')].every(e => e._fullData)", timeout=30_000)
    r = page.evaluate("""() => {
      const plots = [...document.querySelectorAll('.js-plotly-plot')];
      const steps = plots.find(e => (e.querySelector('.gtitle') || {}).textContent.includes('step by step'));
      const box = steps.getBoundingClientRect();
      const ticks = [...steps.querySelectorAll('.xtick text')].map(t => t.getBoundingClientRect());
      return {scrollWidth: document.documentElement.scrollWidth, innerWidth: innerWidth,
              points: plots.map(e => e._fullData.reduce((n, t) => n + (t.x || []).length, 0)),
              box: {left: box.left, right: box.right, bottom: box.bottom},
              ticks: ticks.map(t => ({left: t.left, right: t.right, bottom: t.bottom}))};
    }""")
    assert r["scrollWidth"] <= r["innerWidth"], r
    assert all(n > 0 for n in r["points"]), r["points"]
    assert len(r["ticks"]) >= 2 and all(r["box"]["left"] <= t["left"] and t["right"] <= r["box"]["right"]
                                        and t["bottom"] <= r["box"]["bottom"] for t in r["ticks"]), r
    shot(page, "diagnosis_report_1280")
    page.close()


def test_an_unreadable_upload_keeps_the_recording_that_was_there(chromium, tmp_path):
    # a picture saved as .csv by mistake, then a table whose time goes backwards: each is refused
    # with its reason, and the recording uploaded before stays, plotted and ready to fit
    t = np.arange(3000) * 2e-3
    q = 0.2 * np.sin(2 * np.pi * 0.5 * t)
    tau = 3.0 * np.tanh(np.gradient(q, t) / 0.01)
    good = tmp_path / "joint_ok.csv"
    good.write_text("time [s],position [rad],torque [N*m]\n" + "".join(f"{a:.4f},{b:.8f},{c:.5f}\n" for a, b, c in zip(t, q, tau)))
    picture = tmp_path / "picture.csv"
    picture.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 20)
    back = tmp_path / "backwards.csv"
    back.write_text("time [s],position [rad],torque [N*m]\n" + "".join(f"{a:.4f},{b:.8f},{c:.5f}\n" for a, b, c in
                                                                     zip(np.r_[t[:50], t[40:100]], q, tau)))
    with running_server() as (url, _):
        page = open_app(chromium, url, 1280, 720)
        upload_for(page, "Upload recording").set_input_files(str(good))
        page.get_by_role("tab", name="Data").click()
        wait_plot(page, RECORDING, None)
        for bad, why in ((picture, "not a text file"), (back, "does not increase")):
            upload_for(page, "Upload recording").set_input_files(str(bad))
            wait_text(page, why, 60)
            body = page.locator("body").inner_text()
            said = [ln for ln in body.splitlines() if why in ln and bad.name in ln]
            assert said and "joint_ok.csv is kept" in said[0], body[-2000:]
            assert page.get_by_role("button", name="Fit").first.is_enabled()
            assert plot_traces(page, RECORDING), "the recording's plot is gone"
        page.close()
