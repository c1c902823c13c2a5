"""Reading a page's forms as a browser does, to submit the one marked for an action.

`find_submission(html, page_url, action, values)` looks for the `<form>` or submit button marked
`data-action="<action>"`, and returns what pressing it sends: the URL (a button's `formaction`
wins over the form's `action`), the method, and the form's successful controls — hidden and
pre-filled inputs (the CSRF token among them), checked boxes, selected options, textareas,
plus the pressed button's name and value — with `values` typed over them.

Typing is checked as a person is limited: a value can only go into a field the form has; a
hidden field cannot be changed; a select or a checkbox only takes a value it offers; a value a
button sends is given by pressing that button. When several marked forms or buttons are on the
page (MicroMail's "Archive" and each "Move to" item all move), the first that can take
`values` is used.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from html.parser import HTMLParser
from urllib.parse import urljoin

TEXT_LIKE_SKIPPED = ("submit", "image", "button", "reset", "file")
CHECKABLE = ("checkbox", "radio")


@dataclass
class Control:
    """An input, select or textarea (buttons are `Button`s)."""

    tag: str  # input | select | textarea
    attrs: dict[str, str]
    options: list[tuple[str, bool]] = field(default_factory=list)  # select: (value, selected)
    text: str = ""  # textarea content

    @property
    def name(self) -> str:
        return self.attrs.get("name", "")

    @property
    def type(self) -> str:
        return self.attrs.get("type", "text").lower() if self.tag == "input" else self.tag

    @property
    def disabled(self) -> bool:
        return "disabled" in self.attrs

    def values(self) -> list[str]:
        """What it sends as it stands (no value for an unchecked box)."""
        if self.type in CHECKABLE:
            return [self.attrs.get("value", "on")] if "checked" in self.attrs else []
        if self.tag == "select":
            chosen = [value for value, selected in self.options if selected]
            if not chosen and self.options and "multiple" not in self.attrs:
                chosen = [self.options[0][0]]
            return chosen
        if self.tag == "textarea":
            return [self.text]
        return [self.attrs.get("value", "")]

    def offers(self) -> list[str] | None:
        """The only values a person can give it (None: anything can be typed)."""
        if self.type == "hidden":
            return [self.attrs.get("value", "")]
        if self.type in CHECKABLE:
            return [self.attrs.get("value", "on")]
        if self.tag == "select":
            return [value for value, _ in self.options]
        return None


@dataclass
class Button:
    attrs: dict[str, str]
    form: int | str | None  # index of the enclosing form, or the id in its `form` attribute


@dataclass
class Form:
    attrs: dict[str, str]
    controls: list[Control] = field(default_factory=list)
    buttons: list[Button] = field(default_factory=list)


class FormParser(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.forms: list[Form] = []
        self.buttons: list[Button] = []
        self._current: int | None = None
        self._select: Control | None = None
        self._option: dict | None = None
        self._textarea: Control | None = None
        self._controls: list[tuple[int | str, Control]] = []  # (owner, control), in page order

    def _owner(self, attrs: dict[str, str]) -> int | str | None:
        return attrs.get("form") or self._current

    def _add_control(self, control: Control) -> None:
        owner = self._owner(control.attrs)
        if owner is not None:
            self._controls.append((owner, control))

    def handle_starttag(self, tag: str, attr_list: list) -> None:
        attrs = {name: value if value is not None else "" for name, value in attr_list}
        if tag == "form":
            self.forms.append(Form(attrs))
            self._current = len(self.forms) - 1
        elif tag == "input":
            kind = attrs.get("type", "text").lower()
            if kind in ("submit", "image"):
                self.buttons.append(Button(attrs, self._owner(attrs)))
            elif kind not in TEXT_LIKE_SKIPPED:
                self._add_control(Control("input", attrs))
        elif tag == "button":
            if attrs.get("type", "submit").lower() == "submit":
                self.buttons.append(Button(attrs, self._owner(attrs)))
        elif tag == "select":
            self._select = Control("select", attrs)
            self._add_control(self._select)
        elif tag == "option" and self._select is not None:
            self._option = {
                "value": attrs.get("value"),
                "selected": "selected" in attrs,
                "text": "",
            }
        elif tag == "textarea":
            self._textarea = Control("textarea", attrs)
            self._add_control(self._textarea)

    def handle_endtag(self, tag: str) -> None:
        if tag == "form":
            self._current = None
        elif tag == "option":
            self._end_option()
        elif tag == "select":
            self._end_option()
            self._select = None
        elif tag == "textarea" and self._textarea is not None:
            # As in a browser, one newline right after <textarea> is not part of the value.
            text = self._textarea.text
            self._textarea.text = text[1:] if text.startswith("\n") else text
            self._textarea = None

    def handle_data(self, data: str) -> None:
        if self._option is not None:
            self._option["text"] += data
        elif self._textarea is not None:
            self._textarea.text += data

    def _end_option(self) -> None:
        if self._option is not None and self._select is not None:
            option = self._option
            value = option["value"] if option["value"] is not None else option["text"].strip()
            self._select.options.append((value, option["selected"]))
        self._option = None

    def result(self) -> list[Form]:
        by_id = {form.attrs["id"]: i for i, form in enumerate(self.forms) if "id" in form.attrs}
        for owner, control in self._controls:
            index = by_id.get(owner) if isinstance(owner, str) else owner
            if index is not None:
                self.forms[index].controls.append(control)
        for button in self.buttons:
            index = by_id.get(button.form) if isinstance(button.form, str) else button.form
            if index is not None:
                self.forms[index].buttons.append(button)
        return self.forms


def parse_forms(html: str) -> list[Form]:
    parser = FormParser()
    parser.feed(html)
    parser.close()
    return parser.result()


@dataclass(frozen=True)
class Submission:
    """What pressing a form's button sends."""

    method: str  # "get" | "post"
    url: str
    data: dict[str, list[str]]


class NoSuchForm(LookupError):
    """No form or button on the page is marked for the action, or none can take the values."""


def _pressed(form: Form, action: str) -> list[Button | None]:
    """The submit buttons that perform `action` in `form`: a button marked for it, or (for a
    form marked for it) its first submit button, or none at all (submitted with Enter)."""
    if form.attrs.get("data-action") == action:
        return [form.buttons[0] if form.buttons else None]
    return [b for b in form.buttons if b.attrs.get("data-action") == action]


def _refusal(
    form: Form, button: Button | None, values: Mapping[str, str | list[str]]
) -> str | None:
    """Why a person could not type `values` into `form` and press `button` (None: they can).
    A value the button itself sends (a "Move to" menu item: `folder=junk`) is chosen by
    pressing that button, so only the button sending it can give it."""
    for name, typed in values.items():
        if button is not None and button.attrs.get("name") == name:
            if typed != button.attrs.get("value", ""):
                return f"its button sends {name}={button.attrs.get('value', '')!r}, not {typed!r}"
            continue
        controls = [c for c in form.controls if c.name == name and not c.disabled]
        if not controls:
            return f"it has no field {name!r}"
        offered = [c.offers() for c in controls]
        if any(o is None for o in offered):
            continue
        allowed = {value for o in offered for value in o}
        for value in [typed] if isinstance(typed, str) else typed:
            if value not in allowed:
                return f"field {name!r} only takes {sorted(allowed)}, not {value!r}"
    return None


def _submission(
    form: Form, button: Button | None, page_url: str, values: Mapping[str, str | list[str]]
) -> Submission:
    data: dict[str, list[str]] = {}
    for control in form.controls:
        if control.name and not control.disabled and control.values():
            data.setdefault(control.name, []).extend(control.values())
    button_attrs = button.attrs if button is not None else {}
    for name, typed in values.items():
        if name != button_attrs.get("name"):
            data[name] = [typed] if isinstance(typed, str) else list(typed)
    if button_attrs.get("name"):
        data.setdefault(button_attrs["name"], []).append(button_attrs.get("value", ""))
    target = button_attrs.get("formaction") or form.attrs.get("action") or page_url
    method = button_attrs.get("formmethod") or form.attrs.get("method") or "get"
    return Submission(method.lower(), urljoin(page_url, target), data)


def find_submission(
    html: str, page_url: str, action: str, values: Mapping[str, str | list[str]]
) -> Submission:
    """The submission of the first form marked for `action` that can take `values`."""
    refusals = []
    for form in parse_forms(html):
        for button in _pressed(form, action):
            refusal = _refusal(form, button, values)
            if refusal is None:
                return _submission(form, button, page_url, values)
            refusals.append(f"form → {form.attrs.get('action', page_url)}: {refusal}")
    if not refusals:
        raise NoSuchForm(f'no form or submit button marked data-action="{action}" on {page_url}')
    raise NoSuchForm(
        f'no form marked data-action="{action}" on {page_url} can take {dict(values)}: '
        + "; ".join(refusals)
    )
