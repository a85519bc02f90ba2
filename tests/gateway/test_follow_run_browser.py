"""During a real `coopdrive run follow --realtime --gateway PORT`: the /ws stream and the HMI in Chromium.

The file's tests share one run (conftest.follow_run). Polling with generous deadlines: a loaded 2-core machine
runs the run's processes and a browser here. The browser test saves its screenshot in its own temporary folder, so
that a test run leaves the checkout as it was; with COOPDRIVE_UPDATE_SCREENSHOT=1 it writes the README's picture,
docs/hmi-screenshot.png.
"""

import json
import os
import shutil
import time
from pathlib import Path

import pytest
from websockets.sync.client import connect

from tests.system_packages import require

pytestmark = pytest.mark.whole_run

STARTUP_DEADLINE_S = 90.0
DATA_DEADLINE_S = 30.0
RECV_TIMEOUT_S = 10.0
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]
TABLET = {"width": 1280, "height": 800}
BROWSER_TIMEOUT_MS = 30_000
README_SCREENSHOT = Path(__file__).resolve().parents[2] / "docs" / "hmi-screenshot.png"
UPDATE_SCREENSHOT_VARIABLE = "COOPDRIVE_UPDATE_SCREENSHOT"
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def following(state: dict) -> bool:
    ego, scene = state.get("ego_state"), state.get("scene")
    return (ego is not None and ego["message"]["speed_mps"] > 0
            and scene is not None and scene["message"]["has_forward_mio"])


@pytest.fixture(scope="module")
def run(follow_run):
    follow_run.poll_json("/state", following, STARTUP_DEADLINE_S, "a moving ego with a forward MIO in /state")
    return follow_run


def test_the_stream_carries_several_frames_with_a_changing_ego_speed(run):
    frames = []
    deadline = time.monotonic() + DATA_DEADLINE_S
    with connect(f"ws://127.0.0.1:{run.port}/ws", open_timeout=RECV_TIMEOUT_S) as ws:
        while len(frames) < 10 or len({f["speed_mps"] for f in frames}) < 3:
            assert time.monotonic() < deadline, f"no changing speed within {DATA_DEADLINE_S} s: {frames[-3:]}"
            frames.append(json.loads(ws.recv(timeout=RECV_TIMEOUT_S)))
    seqs = [f["seq"] for f in frames]
    assert seqs == sorted(seqs) and len(set(seqs)) == len(seqs)
    latest = frames[-1]
    assert latest["speed_mps"] > 0 and latest["gap_m"] > 0 and latest["time_gap_s"] > 0
    assert any(o["forward_mio"] and o["x_m"] > 0 for o in latest["objects"])
    assert latest["planner_state"] and latest["scenario"] == "follow" and latest["mode"] is not None
    assert latest["health"]["scene"] is True


def test_the_hmi_draws_the_lead_vehicle_moves_the_gap_gauge_and_shows_a_refused_mode_change(run, tmp_path):
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=require("chromium"), args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport=TABLET)
            page.set_default_timeout(BROWSER_TIMEOUT_MS)
            page.goto(f"http://127.0.0.1:{run.port}/")
            page.wait_for_function(
                "window.hmi && window.hmi.drawn.objects.some(o => o.forward_mio && o.x_m > 0)",
                timeout=BROWSER_TIMEOUT_MS)
            lead = page.evaluate("window.hmi.drawn.objects.find(o => o.forward_mio)")
            assert 0 < lead["x_m"] < 150 and 0 < lead["alpha"] <= 1
            assert page.get_attribute("#birdseye", "data-forward-mio") == str(lead["id"])
            assert page.get_attribute("#connection", "data-state") == "live"
            assert page.text_content("#planner-state") == page.evaluate("window.hmi.frame.planner_state") != ""

            first_gap = page.get_attribute("#gap", "data-value")
            assert first_gap and float(first_gap) > 0
            page.wait_for_function(f"document.getElementById('gap').dataset.value !== '{first_gap}'",
                                   timeout=BROWSER_TIMEOUT_MS)

            page.fill("#token", "")
            page.click("#mode-button")
            page.wait_for_function("document.getElementById('command-result').dataset.outcome === 'refused'",
                                   timeout=BROWSER_TIMEOUT_MS)
            refusal = page.text_content("#command-result")
            assert "Refused (401)" in refusal and "bearer token" in refusal
            assert page.evaluate("window.hmi.lastCommand.status") == 401
            assert "unavailable" in page.text_content("#availability") or "available" in page.text_content(
                "#availability")
            screenshot = tmp_path / README_SCREENSHOT.name
            page.screenshot(path=str(screenshot))
        finally:
            browser.close()
    assert screenshot.read_bytes().startswith(PNG_SIGNATURE)
    if os.environ.get(UPDATE_SCREENSHOT_VARIABLE) == "1":
        shutil.copyfile(screenshot, README_SCREENSHOT)
