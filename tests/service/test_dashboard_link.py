"""The Dask dashboard's address in /health is where it listens: on the service's host."""

from __future__ import annotations

from beltstudy.service.dask import executor as ex
from beltstudy.service.settings import Settings


class FakeCluster:
    """What LocalCluster says when its dashboard binds to ``dashboard_address``: a link on
    its scheduler's address (loopback), whatever host the dashboard listens on."""

    def __init__(self, dashboard_address=None, **kwargs):
        self.dashboard_address = dashboard_address
        port = int(dashboard_address.rsplit(":", 1)[1]) or 39603
        self.dashboard_link = f"http://127.0.0.1:{port}/status"

    def close(self, timeout=None):
        pass


def _link(monkeypatch, host: str, port: int = 0) -> tuple[str | None, str]:
    monkeypatch.setattr(ex, "LocalCluster", FakeCluster)
    monkeypatch.setattr(ex, "Client", lambda cluster, **kwargs: cluster)
    executor = ex.Executor(Settings(host=host, dashboard=True, dashboard_port=port))
    cluster = executor._connect()[0]
    return executor.dashboard, cluster.dashboard_address


def test_the_dashboard_link_names_the_host_it_binds_to(monkeypatch):
    link, bound = _link(monkeypatch, "127.0.0.2")
    assert bound == "127.0.0.2:0"
    assert link == "http://127.0.0.2:39603/status"  # not the scheduler's 127.0.0.1
    assert _link(monkeypatch, "10.1.2.3", 8787)[0] == "http://10.1.2.3:8787/status"
    assert _link(monkeypatch, "::1", 8787)[0] == "http://[::1]:8787/status"


def test_a_dashboard_on_every_interface_keeps_a_link_that_opens(monkeypatch):
    # 0.0.0.0 is no address to open: the loopback link reaches it
    assert _link(monkeypatch, "0.0.0.0")[0] == "http://127.0.0.1:39603/status"
    assert _link(monkeypatch, "127.0.0.1")[0] == "http://127.0.0.1:39603/status"
