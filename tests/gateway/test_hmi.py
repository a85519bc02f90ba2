"""The HMI in Chromium against a gateway fed by an in-memory bus: a mode request with a token, and reconnection."""


import pytest

from conftest import OPERATOR_TOKEN, TOKENS
from coopdrive.runtime.testing import MemoryContext
from coopdrive.services.gateway.service import GatewayService
from tests.system_packages import needs, require

CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]
TABLET = {"width": 1280, "height": 800}
TIMEOUT_MS = 30_000

pytestmark = needs("chromium")


@pytest.fixture
def page():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=require("chromium"), args=CHROMIUM_ARGS)
        try:
            page = browser.new_page(viewport=TABLET)
            page.set_default_timeout(TIMEOUT_MS)
            yield page
        finally:
            browser.close()


def test_with_the_operator_s_token_the_mode_request_is_sent_and_published(make_gateway, feed, page):
    gateway = make_gateway(tokens=TOKENS)
    feed(gateway.ctx)
    page.goto(f"http://127.0.0.1:{gateway.port}/")
    page.wait_for_function("window.hmi.frames > 0")
    assert "cooperative: unavailable — slow enough to engage" in page.text_content("#availability")
    stations = page.text_content("#stations")
    assert "#4242 active" in stations and "signed, verified, trusted" in stations
    assert "#666 lost" in stations and "signed, not verified, not trusted (untrusted)" in stations
    # a station only ever refused was never a partner: no "lost" alert for it
    assert not any("666" in alert["text"] for alert in page.evaluate("window.hmi.alerts"))
    page.fill("#token", OPERATOR_TOKEN)
    page.select_option("#mode-select", "cooperative")
    page.click("#mode-button")
    page.wait_for_function("document.getElementById('command-result').dataset.outcome === 'sent'")
    assert "currently unavailable: slow enough to engage" in page.text_content("#command-result")
    [(topic, request)] = gateway.ctx.published
    assert (topic, request.requested_by, request.reason) == ("gateway/mode_request", "alice",
                                                              "operator request from the HMI")


def test_the_hmi_reconnects_by_itself_when_the_gateway_comes_back(make_gateway, feed, page):
    gateway = make_gateway()
    feed(gateway.ctx, speed_mps=10.0)
    page.goto(f"http://127.0.0.1:{gateway.port}/")
    page.wait_for_function("window.hmi.connected && window.hmi.frames > 0")
    gateway.service.stop()
    page.wait_for_function("!window.hmi.connected")
    ctx = MemoryContext()
    revived = GatewayService(GatewayService.Config(port=gateway.port), ctx)
    revived.start()
    try:
        feed(ctx, speed_mps=20.0)
        page.wait_for_function("window.hmi.connected && window.hmi.frame.speed_mps === 20.0")
        assert page.get_attribute("#connection", "data-state") == "live"
        assert any("Connection to the vehicle lost" in a["text"] for a in page.evaluate("window.hmi.alerts"))
    finally:
        revived.stop()
