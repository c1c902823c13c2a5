"""Generated faces really draw in Chromium: served by the Daphne site (as `./dev serve` runs it)
and shown in MicroMail's message list as decoded images with many distinct colours."""

from __future__ import annotations

import pytest

from tests import control_api
from tests.browser_story import TIMEOUT_MS

# The Chromium fixture (tests/micromail/conftest.py is not in scope here, but be explicit).
from tests.conftest import browser  # noqa: F401

pytestmark = pytest.mark.browser

# Draws every <img class="avatar"> that is on screen into a canvas (same origin: untainted) and
# reports its natural size and how many distinct colours it has.
PIXELS_OF_AVATARS = """
() => [...document.querySelectorAll('img.avatar')].map(img => {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const context = canvas.getContext('2d');
  context.drawImage(img, 0, 0, 64, 64);
  const data = context.getImageData(0, 0, 64, 64).data;
  const colours = new Set();
  for (let i = 0; i < data.length; i += 4) colours.add(data[i] << 16 | data[i + 1] << 8 | data[i + 2]);
  return {src: img.getAttribute('src'), width: img.naturalWidth, colours: colours.size};
})
"""


def scenario() -> dict:
    return {
        "id": "browser-media-faces",
        "environment": "micromail",
        "prompt": "Look at the inbox.",
        "start_page": "HOST_ADDRESS/micromail",
        "condition_at": 1.0,
        "event_timeline_end": 600.0,
        "kill_at": 600.0,
        "taxonomy": {},
        "events": [
            {
                "time": 0.0,
                "type": "preload_emails",
                "payload": {"email_ids": ["base-01", "base-02", "base-30"]},
            }
        ],
        "eval_sql": "SELECT 1",
    }


def test_inbox_faces_are_decoded_images_with_real_pictures(live_site, browser):  # noqa: F811
    run = control_api.call(
        live_site, "POST", "/api/runs/", {"scenario_json": scenario(), "clock_mode": "virtual"}
    )
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(TIMEOUT_MS)
    with page.expect_response(lambda response: "/media/avatars/" in response.url) as first:
        page.goto(run["task_url"])
    response = first.value
    assert response.status == 200
    assert response.headers["content-type"] == "image/svg+xml"
    assert "immutable" in response.headers["cache-control"]
    page.wait_for_load_state("load")

    avatars = page.evaluate(PIXELS_OF_AVATARS)
    assert len(avatars) >= 4  # the self user in the top bar and a sender on each of three rows
    for avatar in avatars:
        assert avatar["width"] > 0, avatar["src"]
        assert avatar["colours"] > 8, avatar["src"]  # a face, not a flat grey box
