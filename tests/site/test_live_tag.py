"""`{% live %}` marks a page's live regions; on a live re-render it records them for the push.

The cast: a plain page view (a request as a browser sends it) and a live re-render (the request
apps.kit.live makes for a push, flagged `sentinel_live`).
"""

from __future__ import annotations

import pytest
from django.http import HttpRequest
from django.template import Context, Template, TemplateSyntaxError

from apps.kit.live import render_update
from apps.kit.pages import Page
from apps.kit.templatetags.simtime import sim_ago, sim_now, sim_relative
from events import lifecycle
from tests.micromail.cast import CAST

FOLDERS = (
    '{% load live %}{% live "nav" id="folders" class=kind aria-label="Folders" hidden=no %}'
    "<a>Inbox</a>{% endlive %}"
)


def browser_request() -> HttpRequest:
    return HttpRequest()


def live_rerender() -> HttpRequest:
    request = HttpRequest()
    request.sentinel_live = True
    return request


def render(source: str, request: HttpRequest | None = None, **context) -> str:
    return Template(source).render(Context({"request": request, **context}))


def test_the_tag_renders_the_element_with_its_attributes():
    html = render(FOLDERS, browser_request(), kind='folders "main"', no=None)
    assert html == (
        '<nav id="folders" data-live class="folders &quot;main&quot;" aria-label="Folders">'
        "<a>Inbox</a></nav>"
    )


def test_a_true_attribute_is_written_bare():
    html = render('{% load live %}{% live "p" id="x" hidden=yes %}.{% endlive %}', yes=True)
    assert html == '<p id="x" data-live hidden>.</p>'


def test_a_page_view_records_nothing():
    request = browser_request()
    render(FOLDERS, request, kind="folders")
    assert not hasattr(request, "sentinel_live_regions")


def test_a_live_rerender_records_the_outermost_regions_in_page_order():
    request = live_rerender()
    html = render(
        '{% load live %}<main>{% live "section" id="list" %}<ul>{% live "li" id="row" %}1'
        '{% endlive %}</ul>{% endlive %}{% live "aside" id=pane_id %}2{% endlive %}</main>',
        request,
        pane_id="pane",
    )
    assert html == (
        '<main><section id="list" data-live><ul><li id="row" data-live>1</li></ul></section>'
        '<aside id="pane" data-live>2</aside></main>'
    )
    assert request.sentinel_live_regions == [
        (
            "list",
            '<section id="list" data-live hx-swap-oob="true"><ul>'
            '<li id="row" data-live>1</li></ul></section>',
        ),
        ("pane", '<aside id="pane" data-live hx-swap-oob="true">2</aside>'),
    ]


def test_a_region_without_an_id_fails_loudly():
    with pytest.raises(TemplateSyntaxError, match="needs an id"):
        Template('{% load live %}{% live "nav" class="folders" %}…{% endlive %}')


def test_a_region_whose_id_is_empty_fails_loudly():
    with pytest.raises(TemplateSyntaxError, match="id is empty"):
        render('{% load live %}{% live "nav" id=missing %}…{% endlive %}')


@pytest.mark.parametrize(
    "source, problem",
    [
        ('{% live id="folders" %}…{% endlive %}', "element name first"),
        ('{% live "nav" id="a" folders %}…{% endlive %}', "not name=value"),
        ('{% live "nav" id="a" data-live="1" %}…{% endlive %}', "written by the tag"),
    ],
)
def test_malformed_regions_fail_loudly(source, problem):
    with pytest.raises(TemplateSyntaxError, match=problem):
        Template("{% load live %}" + source)


def test_a_void_element_cannot_be_a_region():
    with pytest.raises(TemplateSyntaxError, match="end tag"):
        render('{% load live %}{% live "input" id="q" %}{% endlive %}')


# -- time filters tell the page when they change ------------------------------------------------


@pytest.fixture
def run(db):
    return CAST.start()


def page_at(run, now: float) -> Page:
    return Page(request=browser_request(), run=run, state=None, now=now)


def test_sim_ago_registers_when_its_text_changes(run):
    page = page_at(run, 130.0)
    assert sim_ago(0.0, page) == "2 min ago"
    assert page.next_change == 180.0
    assert sim_ago(0.0, 130.0) == "2 min ago"  # a plain `now` still works, registering nothing


def test_sim_relative_and_sim_now_register_too(run):
    page = page_at(run, 30.0)
    assert sim_relative(-7200.0, page) == "07:00"
    assert page.next_change == 15 * 3600  # midnight: it then reads "Yesterday 07:00"
    sim_now(page)
    assert page.next_change == 60.0  # the clock's minute turns first


def test_render_update_returns_the_recorded_regions_and_next_change(run):
    lifecycle.advance(run, 75.0)
    update = render_update(run, f"/r/{run.token}/micromail/?folder=inbox")
    assert [region_id for region_id, _ in update.regions] == [
        "sim-clock",
        "favorites",
        "folders",
        "message-list",
        "reading-pane",
    ]
    assert update.next_change == 120.0  # 09:02, and the preloaded mail turns "7 min ago"
    assert update.html.startswith('<time id="sim-clock" data-live hx-swap-oob="true"')
    assert update.message()["next_change"] == 120.0
