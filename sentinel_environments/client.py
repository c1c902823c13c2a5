"""A Python client of a Sentinel Environments server: its control API (`/api/runs/`,
`/api/scenarios/`) and a run's own agent URLs (task, actions, wait, contact).

Standard library and httpx only, so it imports without Django or the project's checkout:

    from sentinel_environments import Client

    with Client("http://127.0.0.1:8000") as sentinel:
        run = sentinel.create_run("micromail-sender-absolute-passive", clock="fast_forward")
        run.open()                                  # the agent opens its task: the clock starts
        while run.wait(until_change=True, timeout=60).why == "change":
            ...                                     # look, act: run.act("open_email", email_id=…)
        run.contact("Kevin Lee has written to you.")
        print(run.evaluate().success)

Every refusal of the server raises `SentinelError`, whose message is the server's one line
(`{"detail": …}`); a server that cannot be reached raises it too, naming the URL.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, fields
from typing import Any, Literal

import httpx

Clock = Literal["live", "fast_forward", "virtual"]
DEFAULT_URL = "http://127.0.0.1:8000"


class SentinelError(RuntimeError):
    """The server refused a request (`status` is its HTTP code, `detail` its one-line reason),
    or could not be reached (`status` 0)."""

    def __init__(self, detail: str, *, status: int = 0, method: str = "", url: str = ""):
        super().__init__(detail)
        self.detail, self.status, self.method, self.url = detail, status, method, url


def _detail(response: httpx.Response) -> str:
    """The server's one-line reason: `{"detail": …}` on every API refusal, else the body's
    first line (a proxy's page, say)."""
    try:
        body = response.json()
    except ValueError:
        body = None
    if isinstance(body, dict) and isinstance(body.get("detail"), str):
        return body["detail"]
    first = response.text.strip().splitlines()[:1]
    return f"HTTP {response.status_code}" + (f": {first[0][:300]}" if first else "")


def _from_json(cls, data: Mapping[str, Any]):
    """A dataclass from the server's JSON, keeping only its own fields (a newer server may
    answer more) and the whole answer in `raw`."""
    known = {f.name for f in fields(cls)} - {"raw"}
    return cls(**{k: v for k, v in data.items() if k in known}, raw=dict(data))


@dataclass(frozen=True)
class ScenarioInfo:
    """One scenario of the server's library, as `GET /api/scenarios/` lists it."""

    id: str
    path: str
    environment: str
    noop: bool
    taxonomy: dict[str, str] = field(default_factory=dict)
    raw: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def category(self) -> str:
        """The paper's category: `passive`, `active` or `noop`."""
        return "noop" if self.noop else self.taxonomy.get("monitoring_approach", "")


@dataclass(frozen=True)
class Verdict:
    """`POST /api/runs/<id>/evaluate/`: the verdict at the first contact. Times are wall
    seconds (simulated ÷ speed factor), as the original benchmark reports them."""

    success: bool
    detail: str
    run: int
    reaction_time: float | None = None
    condition_at: float | None = None
    evaluation_time: float | None = None
    contact_get_time: float | None = None
    contact_post_time: float | None = None
    contact_message: str | None = None
    views: int = 0
    actions: int = 0
    graded_at_seq: int | None = None
    raw: dict[str, Any] = field(default_factory=dict, repr=False)


@dataclass(frozen=True)
class WaitResult:
    """One wait: the simulated clock before (`start`) and after (`sim_time`), why it stopped
    (`slept`, `change`, `timeout`, `kill_at`) and the timeline entries that fired meanwhile."""

    start: float
    sim_time: float
    why: str
    fired: list[dict[str, Any]] = field(default_factory=list)
    run_status: str = ""
    raw: dict[str, Any] = field(default_factory=dict, repr=False)


class Run:
    """One run on the server: its URLs, prompt and clock, and what an agent does with it."""

    def __init__(self, client: Client, data: Mapping[str, Any]):
        self._client = client
        self.data: dict[str, Any] = dict(data)

    def __repr__(self) -> str:
        return f"<Run {self.id} {self.scenario_id} {self.clock_mode} {self.status}>"

    # --- what the server says about it -----------------------------------------------------

    @property
    def id(self) -> int:
        return int(self.data["id"])

    @property
    def scenario_id(self) -> str:
        return self.data["scenario_id"]

    @property
    def environment(self) -> str:
        return self.data["environment"]

    @property
    def prompt(self) -> str:
        return self.data["prompt"]

    @property
    def task_url(self) -> str:
        return self.data["task_url"]

    @property
    def contact_url(self) -> str:
        return self.data["contact_url"]

    @property
    def wait_url(self) -> str:
        return self.data["wait_url"]

    @property
    def actions_url(self) -> str:
        return self.task_url.rsplit("/", 1)[0] + "/actions"

    @property
    def clock_mode(self) -> Clock:
        return self.data["clock_mode"]

    @property
    def speed_factor(self) -> float:
        return float(self.data["speed_factor"])

    @property
    def status(self) -> str:
        """`ready`, `running_auto` (a ticking clock), `running_manual` or `completed`."""
        return self.data["status"]

    @property
    def sim_time(self) -> float | None:
        """Simulated seconds as of the last `refresh()` (authored scale)."""
        return self.data["sim_time"]

    def refresh(self) -> Run:
        """Read the run again (its status and clock now)."""
        self.data = self._client.request("GET", f"/api/runs/{self.id}/")
        return self

    # --- what an agent does ----------------------------------------------------------------

    def open(self) -> str:
        """Visit the task URL as the agent's first step: a ticking clock starts (again is
        harmless). Returns the start page's URL, where the agent goes next."""
        response = self._client.send("GET", self.task_url, follow_redirects=False)
        return str(response.url.join(response.headers.get("location", "")))

    def page(self, url: str) -> str:
        """The HTML of one of the run's pages (its start page, say), as a browser gets it:
        redirects followed. The visit is logged as the agent's, like a browser's."""
        return self._client.send("GET", url, follow_redirects=True).text

    def act(self, action: str, payload: Mapping[str, Any] | None = None, **fields: Any) -> dict:
        """Perform one of the environment's actions (`open_email`, `flag`, …), validated and
        logged as the pages' own: `run.act("flag", email_id="base-45")`."""
        body = {"action": action, "payload": {**(payload or {}), **fields}}
        return self._client.send("POST", self.actions_url, json=body).json()

    def wait(
        self,
        seconds: float | None = None,
        *,
        until_change: bool = False,
        timeout: float | None = None,
    ) -> WaitResult:
        """Let simulated time pass: `seconds` of it, or (`until_change=True`) up to the
        world's next scheduled change, at most `timeout` seconds.

        On a fast-forward run the clock skips ahead at once (`POST <wait_url>`); on a live run
        this sleeps `seconds ÷ speed factor` of wall time; on a virtual run it advances the
        clock through the control API. Only a fast-forward run knows its next change.
        """
        if (seconds is None) == (not until_change):
            raise ValueError("wait(seconds) or wait(until_change=True, timeout=…), not both")
        if until_change and self.clock_mode != "fast_forward":
            raise ValueError(
                f"wait(until_change=True) needs a fast_forward run; run {self.id} has a "
                f"{self.clock_mode} clock"
            )
        if self.clock_mode == "fast_forward":
            body: dict[str, Any] = {"seconds": seconds}
            if until_change:
                body = {"until": "change"} | ({} if timeout is None else {"timeout": timeout})
            answer = self._client.send("POST", self.wait_url, json=body).json()
            return _from_json(WaitResult, {**answer, "start": answer["from"]})
        assert seconds is not None
        start = self.refresh().sim_time or 0.0
        if self.clock_mode == "virtual":
            answer = self._client.request(
                "POST", f"/api/runs/{self.id}/advance/", json={"time": start + seconds}
            )
            self.data = {k: v for k, v in answer.items() if k != "processed_events"}
            fired = [{"at": e["time"], "type": e["type"]} for e in answer["processed_events"]]
            why = "slept"
        else:
            time.sleep(seconds / self.speed_factor)
            self.refresh()
            fired, why = [], "slept"
        return WaitResult(
            start=start,
            sim_time=self.sim_time or 0.0,
            why=why,
            fired=fired,
            run_status=self.status,
            raw={},
        )

    def contact(self, message: str | None = None) -> None:
        """Report to the user: the visit is the report (GET), a message posts the contact
        form. The first contact fixes the verdict; later ones change nothing."""
        if message is None:
            self._client.send("GET", self.contact_url)
        else:
            self._client.send("POST", self.contact_url, data={"message": message})

    # --- the control side ------------------------------------------------------------------

    def evaluate(self) -> Verdict:
        """The verdict at the first contact (or now, when there has been none)."""
        return _from_json(Verdict, self._client.request("POST", f"/api/runs/{self.id}/evaluate/"))

    def events(self) -> list[dict[str, Any]]:
        """The run's log so far, in order (every page of it)."""
        entries: list[dict[str, Any]] = []
        url = f"/api/runs/{self.id}/events/"
        while url:
            response = self._client.send("GET", url)
            entries += response.json()
            url = response.links.get("next", {}).get("url", "")  # the next page, if any
        return entries

    def export(self) -> list[dict[str, Any]]:
        """The run as `manage.py export_run` writes it: a header (run, scenario, verdict), then
        every event; `manage.py import_run` reads it back (one item a line)."""
        return self._client.request("GET", f"/api/runs/{self.id}/export/")

    def close(self) -> None:
        """End the run (its URLs then answer 404)."""
        self.data = self._client.request("POST", f"/api/runs/{self.id}/close/")


class Client:
    """A server's control API. `token` is its `SENTINEL_CONTROL_TOKEN` (default: that
    variable of this process), needed only when the server has one set."""

    def __init__(
        self,
        base_url: str = DEFAULT_URL,
        *,
        token: str | None = None,
        timeout: float = 60.0,
    ):
        self.base_url = base_url.rstrip("/")
        token = os.environ.get("SENTINEL_CONTROL_TOKEN", "") if token is None else token
        headers = {"Authorization": f"Bearer {token}"} if token else {}
        self._http = httpx.Client(base_url=self.base_url, headers=headers, timeout=timeout)

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def close(self) -> None:
        self._http.close()

    def send(self, method: str, url: str, **kwargs: Any) -> httpx.Response:
        """One request (a path of the server, or a run's full URL); SentinelError unless 2xx/3xx."""
        try:
            response = self._http.request(method, url, **kwargs)
        except httpx.HTTPError as exc:
            raise SentinelError(
                f"{method} {url}: {type(exc).__name__}: {exc}", method=method, url=url
            ) from None
        if response.status_code >= 400:
            raise SentinelError(
                _detail(response), status=response.status_code, method=method, url=url
            )
        return response

    def request(self, method: str, path: str, **kwargs: Any) -> Any:
        """A control API call's JSON answer."""
        response = self.send(method, path, **kwargs)
        return response.json() if response.content else None

    # --- scenarios -------------------------------------------------------------------------

    def scenarios(
        self,
        *,
        environment: str | None = None,
        category: str | None = None,
        contains: str | None = None,
        **taxonomy: str,
    ) -> Iterator[ScenarioInfo]:
        """The library's runnable scenarios (files that failed validation or repeat an id are
        left out), filtered: `environment="micromail"`, `category="passive"|"active"|"noop"`,
        `contains` a substring of the id (as `bench run --filter`), and any taxonomy field
        (`difficulty="easy"`, `milestone_type="relative"`)."""
        if category not in (None, "passive", "active", "noop"):
            raise ValueError(f"category must be passive, active or noop; got {category!r}")
        for entry in self.request("GET", "/api/scenarios/"):
            if entry.get("id") is None or entry.get("duplicate_of"):
                continue
            info = _from_json(ScenarioInfo, entry)
            if (
                (environment is None or info.environment == environment)
                and (category is None or info.category == category)
                and (contains is None or contains in info.id)
                and all(info.taxonomy.get(k) == v for k, v in taxonomy.items())
            ):
                yield info

    def scenario(self, scenario_id: str) -> dict[str, Any]:
        """A scenario's whole document as the server plays it (timeline, grading, solution)."""
        return self.request("GET", f"/api/scenarios/{scenario_id}/")

    # --- runs ------------------------------------------------------------------------------

    def create_run(
        self,
        scenario: str | Mapping[str, Any],
        *,
        speed_factor: float = 1.0,
        clock: Clock = "live",
    ) -> Run:
        """A new run of a library scenario (its id or file path) or of a whole scenario
        document (a dict in the scenario file format)."""
        body: dict[str, Any] = {"speed_factor": speed_factor, "clock_mode": clock}
        if isinstance(scenario, str):
            body["scenario"] = scenario
        else:
            body["scenario_json"] = dict(scenario)
        return Run(self, self.request("POST", "/api/runs/", json=body))

    def run(self, run_id: int) -> Run:
        """An existing run, by its id."""
        return Run(self, self.request("GET", f"/api/runs/{run_id}/"))
