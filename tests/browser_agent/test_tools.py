"""The reference agent's browser tools on a real page: a small static shop (conftest.py) in
Debian's Chromium, the judge of wait_for a scripted model.

One Chromium serves the whole module, as one serves an agent's whole task: every test starts by
opening the shop page afresh, its own tools and model around it. Launching Chromium is most of
what each test would otherwise cost. (Nothing here touches the database: Playwright's sync API
keeps an event loop running in this thread while the browser is open, where the ORM refuses.)
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from apps.browser_agent.browser import Browser
from apps.browser_agent.model import ChatModel, CostLedger, make_client
from apps.browser_agent.tools import TaskClock, Toolbox
from tests.browser_agent.conftest import StaticSite, serving_static_site

pytestmark = pytest.mark.browser


@pytest.fixture(scope="module")
def shop() -> Iterator[StaticSite]:
    with serving_static_site() as site:
        yield site


@pytest.fixture
def static_site(shop) -> StaticSite:
    """The module's shop, with nothing received through its contact form yet."""
    shop.messages.clear()
    return shop


@pytest.fixture(scope="module")
def agent_browser(shop) -> Iterator[Browser]:
    with Browser.launch(contact_url=shop.contact_url) as browser:
        yield browser


@pytest.fixture
def make_toolbox(agent_browser, static_site, scripted_model):
    """`make_toolbox(kind, wall_left)`: the tools on the shop page, the judge a scripted model."""
    server = scripted_model({"model": "scripted-1", "agent": [], "judge": {"yes_when_any": ["Pressed"]}})  # fmt: skip
    client = make_client(base_url=server.base_url, api_key="not-needed")
    agent_browser.visit_url(static_site.url + "/")

    def make(kind: str = "wait_for", wall_left=lambda: None) -> Toolbox:
        return Toolbox(
            agent_browser,
            ChatModel(client, "scripted-1", CostLedger("scripted-1")),
            kind=kind,
            contact_url=static_site.contact_url,
            clock=TaskClock(10.0),  # wait_for's 10 s between questions take 1 wall second
            wall_left=wall_left,
        )

    return make


@pytest.fixture
def toolbox(make_toolbox) -> Toolbox:
    return make_toolbox()


def test_the_description_numbers_the_elements_in_view(toolbox):
    seen = toolbox.browser.observe()
    assert seen.title == "Shop"
    for line in (
        '[1] link "Other page"',
        '[2] button "Press me"',
        '[3] input "Search"',
        '[4] select "Colour" selected="Red"',
    ):
        assert line in seen.description.splitlines()
    assert "# Shop" in seen.description
    assert seen.png[:4] == b"\x89PNG" and seen.jpeg[:2] == b"\xff\xd8"


def marked(toolbox) -> list[str]:
    """The numbered elements of a fresh look, as the model reads them."""
    return [line for line in toolbox.browser.observe().description.splitlines() if line[:1] == "["]


def test_only_what_a_person_can_see_is_numbered(toolbox):
    """A closed menu's items are laid out but not shown, a `visibility: hidden` button neither:
    no number, no mark drawn over the page, until the menu is opened."""
    assert marked(toolbox)[4:] == ['[5] summary "More"']
    toolbox.dispatch("click", {"target": 5})
    assert marked(toolbox)[4:] == ['[5] summary "More"', '[6] button "Gift wrap"']


def test_the_tools_act_on_numbered_elements(toolbox):
    toolbox.browser.observe()
    assert toolbox.dispatch("click", {"target": 2}).text == 'clicked [2] button "Press me"'
    toolbox.dispatch("type", {"target": "[3]", "text": "lamps"})
    toolbox.dispatch("type", {"target": 4, "text": "Blue"})
    after = toolbox.browser.observe().description
    assert "Pressed!" in after
    assert '[3] input "Search" value="lamps"' in after
    assert '[4] select "Colour" selected="Blue"' in after
    assert toolbox.dispatch("click", {"target": 1}).ends_task is None
    assert toolbox.browser.observe().title == "Other"
    assert toolbox.dispatch("go_back", {}).text.startswith("went back to")


@pytest.mark.parametrize(
    ("tool", "arguments", "result"),
    [
        ("click", {"target": 99}, "error: no element [99] on the page now; use a number from the latest description"),
        ("click", {"target": "the button"}, 'error: target must be an element number from the page description, got "the button"'),
        ("click", {"element": 2}, 'error: click takes target; got {"element": 2}'),
        ("type", {"target": 4, "text": "Green"}, "error: no option 'Green' in this select; its options are 'Red', 'Blue'"),
        ("scroll", {"direction": "left"}, "error: direction must be 'up' or 'down', got 'left'"),
        ("visit_url", {"url": "ftp://x"}, "error: cannot visit 'ftp://x': only http:// and https:// URLs"),
        ("sleep", {"seconds": 5}, "error: there is no tool 'sleep'; use one of the tools offered"),
        ("wait_for", {"condition": "x", "timeout": -1}, "error: timeout must be a finite number of seconds ≥ 0, got -1"),
        ("contact", {"message": " "}, "error: message must not be empty"),
    ],
)  # fmt: skip
def test_a_mistake_is_the_tools_result_not_a_crash(toolbox, tool, arguments, result):
    toolbox.browser.observe()
    assert toolbox.dispatch(tool, arguments).text == result


def test_contact_goes_through_the_form_and_only_the_contact_tool_may(toolbox, static_site):
    refused = toolbox.dispatch("visit_url", {"url": static_site.contact_url})
    assert refused.text == "error: that is the contact page: report with the contact tool instead"
    assert static_site.messages == []
    done = toolbox.dispatch("contact", {"message": "The button was pressed."})
    assert (done.text, done.ends_task) == ("contacted: Thank you.", "contacted the user")
    assert static_site.messages == ["The button was pressed."]


def test_wait_for_watches_the_page_with_the_model_as_judge(toolbox, monkeypatch):
    browser, looks = toolbox.browser, []

    def markdown() -> str:
        """The page as wait_for reads it; the button is pressed right after its first look (a
        timer started before wait_for could fire before that look on a loaded machine)."""
        looks.append(Browser.markdown(browser))
        if len(looks) == 1:
            browser.page.evaluate("document.getElementById('out').textContent = 'Pressed!'")
        return looks[-1]

    monkeypatch.setattr(browser, "markdown", markdown)
    result = toolbox.dispatch("wait_for", {"condition": "the button is pressed", "timeout": 300})
    assert "Pressed!" not in looks[0]
    assert result.text.startswith("met: true — a new change mentions 'Pressed'")
    assert toolbox.judge.model.ledger.total.calls >= 1


def test_a_sleep_never_outlasts_the_wall_budget(make_toolbox):
    toolbox = make_toolbox("sleep", wall_left=lambda: 0.0)
    assert toolbox.dispatch("sleep", {"seconds": 600}).text == (
        "slept 0 of 600 s: the time budget is spent"
    )
