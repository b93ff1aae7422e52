"""A small HTTP client of the service (used by the CLI and the demo)."""

from __future__ import annotations

from typing import Any

import httpx

from beltstudy.service.errors import Invalid, ServiceError, Unavailable

__all__ = ["ServiceClient"]


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

    def _request(self, method: str, path: str, **kw) -> httpx.Response:
        try:
            response = self._http.request(method, path, **kw)
        except httpx.TransportError as exc:
            raise Unavailable(
                f"cannot reach the service at {self.url} ({type(exc).__name__}); start it with "
                "'beltstudy serve' or run the study in-process with 'beltstudy run'"
            ) from None
        if response.status_code >= 400:
            try:
                message = response.json().get("message") or response.text
            except ValueError:
                message = response.text
            raise ServiceError(f"{message} (HTTP {response.status_code})", response.status_code)
        return response

    def health(self) -> dict:
        return self._request("GET", "/health").json()

    def submit(self, study: dict) -> tuple[dict, bool]:
        """POST a study; returns (status, created)."""
        response = self._request("POST", "/studies", json=study)
        return response.json(), response.status_code == 202

    def status(self, study_id: str) -> dict:
        return self._request("GET", f"/studies/{study_id}").json()

    def list(self) -> list[dict]:
        return self._request("GET", "/studies").json()["studies"]

    def runs(self, study_id: str, fmt: str = "json", **params: Any) -> bytes:
        response = self._request(
            "GET", f"/studies/{study_id}/runs", params={"format": fmt, **params}
        )
        return response.content

    def compare(self, study_id: str, baseline: str, candidate: str, metrics: list[str]) -> dict:
        params = {"baseline": baseline, "candidate": candidate}
        if metrics:  # none: the service's default metrics (an empty value is refused)
            params["metrics"] = ",".join(metrics)
        return self._request("GET", f"/studies/{study_id}/compare", params=params).json()

    def uncertainty(self, study_id: str) -> dict:
        """A sampled study's distributions, exceedance probabilities and ranking."""
        return self._request("GET", f"/studies/{study_id}/uncertainty").json()

    def report(self, study_id: str) -> str:
        """The study's design report (self-contained HTML)."""
        return self._request("GET", f"/studies/{study_id}/report").text

    def delete(self, study_id: str) -> dict:
        return self._request("DELETE", f"/studies/{study_id}").json()
