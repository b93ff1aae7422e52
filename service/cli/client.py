"""A small HTTP client of the service (used by the CLI and the demo)."""

from __future__ import annotations

import sys
import time
from typing import Any
from urllib.parse import quote

import httpx

from beltstudy.service.errors import Invalid, ServiceError, Unavailable

__all__ = ["ServiceClient", "study_path"]

#: The content type of each runs download the service answers with.
RUNS_TYPES = {"json": "application/json", "csv": "text/csv",
              "parquet": "application/vnd.apache.parquet"}


def study_path(study_id: str, *rest: str) -> str:
    """``/studies/<id>/<rest...>`` with the id as one path segment: an id as typed
    (``../health``, ``..``, ``x?y=1``) is percent-encoded, so it reaches the study routes and
    is answered as an unknown study, never as another route (``GET /health`` read as a study
    status was a KeyError traceback)."""
    seg = quote(study_id, safe="")
    if seg in (".", ".."):  # a dot segment an HTTP client would resolve away
        seg = seg.replace(".", "%2E")
    return "/".join(["/studies", seg, *rest])


#: Times ``submit`` sends a study again after a 503 with Retry-After.
SUBMIT_RETRIES = 3
#: Longest wait before sending again [s], whatever Retry-After asks.
RETRY_WAIT_MAX_S = 30.0


class ServiceClient:
    """Calls the REST API; 4xx/5xx answers raise :class:`ServiceError` with the message."""

    def __init__(self, url: str, token: str = "", timeout: float = 60.0):
        self.url = url.rstrip("/")
        if token and not all("!" <= ch <= "~" for ch in token):
            raise Invalid("--token / BELTSTUDY_TOKEN: a token is printable ASCII (letters, "
                          "digits and punctuation), without spaces, line breaks or other "
                          "characters; give the token the service was started with")
        headers = {"Authorization": f"Bearer {token}"} if token else {}
        try:
            parsed = httpx.URL(self.url)
            if parsed.scheme not in ("http", "https") or not parsed.host:
                raise httpx.InvalidURL("expected http:// or https:// and a host")
            self._http = httpx.Client(base_url=self.url, headers=headers, timeout=timeout)
        except httpx.InvalidURL as exc:
            raise Invalid(f"--url / BELTSTUDY_URL: {self.url!r} is not the service's address "
                          f"({exc}); give it as http://HOST:PORT, e.g. "
                          "http://127.0.0.1:8000") from None

    def close(self) -> None:
        self._http.close()

    def __enter__(self) -> ServiceClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _not_the_service(self, response: httpx.Response) -> ServiceError:
        """What something other than the service answered (an HTML page, a proxy's error),
        in one line naming the address, instead of its whole body or a JSON traceback."""
        kind = response.headers.get("content-type", "").split(";")[0].strip() or "no type"
        return ServiceError(
            f"the answer at {self.url} is not the beltstudy service's (HTTP "
            f"{response.status_code}, {kind}); check --url / BELTSTUDY_URL: the address "
            "'beltstudy serve' prints, e.g. http://127.0.0.1:8000", response.status_code)

    def _request(self, method: str, path: str, expect: str = "application/json",
                 **kw) -> httpx.Response:
        """The answer to ``method path``; an error answer, or one whose content type is not
        ``expect``, raises :class:`ServiceError` with one line."""
        try:
            response = self._http.request(method, path, **kw)
        except httpx.TransportError as exc:
            raise Unavailable(
                f"cannot reach the service at {self.url} ({type(exc).__name__}); start it with "
                "'beltstudy serve' or run the study in-process with 'beltstudy run'"
            ) from None
        if response.status_code >= 400:
            try:
                body = response.json()
                message = body.get("message") if isinstance(body, dict) else None
            except ValueError:
                message = None
            if not isinstance(message, str) or not message:
                raise self._not_the_service(response)
            message = " ".join(message.split())  # one line
            if response.status_code == 401:
                message += "; give the service's token with --token or BELTSTUDY_TOKEN"
            retry = response.headers.get("retry-after", "")
            raise ServiceError(f"{message} (HTTP {response.status_code})", response.status_code,
                               {"Retry-After": retry} if retry.isdigit() else None)
        kind = response.headers.get("content-type", "").split(";")[0].strip().lower()
        if kind != expect:
            raise self._not_the_service(response)
        if expect == "application/json":
            try:
                response.json()
            except ValueError:
                raise self._not_the_service(response) from None
        return response

    def health(self) -> dict:
        return self._request("GET", "/health").json()

    def submit(self, study: dict, retries: int = SUBMIT_RETRIES) -> tuple[dict, bool]:
        """POST a study; returns (status, created). A 503 with ``Retry-After`` (the service
        busy expanding other studies, or being stopped) is sent again after the time it asks,
        at most :data:`RETRY_WAIT_MAX_S` each, up to ``retries`` times, saying so on stderr:
        the CLI stopped at the first with exit status 2, though the answer said when to send
        it again (the same study is one study however often it is sent)."""
        for attempt in range(retries + 1):
            try:
                response = self._request("POST", "/studies", json=study)
                return response.json(), response.status_code == 202
            except ServiceError as exc:
                wait = (exc.headers or {}).get("Retry-After", "")
                if exc.status_code != 503 or not wait or attempt == retries:
                    raise
                wait_s = min(float(wait), RETRY_WAIT_MAX_S)
                print(f"{exc.message}: sending it again in {wait_s:g} s ({attempt + 1} of "
                      f"{retries})", file=sys.stderr, flush=True)
                time.sleep(wait_s)
        raise AssertionError("unreachable")  # pragma: no cover

    def status(self, study_id: str) -> dict:
        return self._request("GET", study_path(study_id)).json()

    def list(self) -> list[dict]:
        return self._request("GET", "/studies").json()["studies"]

    def runs(self, study_id: str, fmt: str = "json", **params: Any) -> bytes:
        response = self._request(
            "GET", study_path(study_id, "runs"), expect=RUNS_TYPES.get(fmt, "application/json"),
            params={"format": fmt, **params}
        )
        return response.content

    def compare(self, study_id: str, baseline: str | None, candidate: str | None,
                metrics: list[str]) -> dict:
        # a model left out (None) is left to the service's default, which says so
        params = {k: v for k, v in (("baseline", baseline), ("candidate", candidate))
                  if v is not None}
        if metrics:  # none: the service's default metrics (an empty value is refused)
            params["metrics"] = ",".join(metrics)
        return self._request("GET", study_path(study_id, "compare"), params=params).json()

    def uncertainty(self, study_id: str) -> dict:
        """A sampled study's distributions, exceedance probabilities and ranking."""
        return self._request("GET", study_path(study_id, "uncertainty")).json()

    def report(self, study_id: str) -> str:
        """The study's design report (self-contained HTML)."""
        return self._request("GET", study_path(study_id, "report"), expect="text/html").text

    def delete(self, study_id: str) -> dict:
        return self._request("DELETE", study_path(study_id)).json()
