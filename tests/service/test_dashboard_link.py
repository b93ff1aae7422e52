"""The Dask dashboard's address in /health is where it listens: on the service's host."""

from __future__ import annotations

import httpx
import pytest

from beltstudy.service.dask import executor as ex
from beltstudy.service.settings import Settings


@pytest.mark.parametrize(("host", "link"), [
    ("127.0.0.2", "http://127.0.0.2:39603/status"),   # not the scheduler's 127.0.0.1
    ("10.1.2.3", "http://10.1.2.3:39603/status"),
    ("::1", "http://[::1]:39603/status"),
    ("0.0.0.0", "http://127.0.0.1:39603/status"),     # a wildcard is no address to open:
    ("127.0.0.1", "http://127.0.0.1:39603/status"),   # the loopback link reaches it
])
def test_the_dashboard_link_names_the_host_it_binds_to(host, link):
    """Dask's link names the scheduler's loopback address whatever host the dashboard binds."""
    assert ex._dashboard_link("http://127.0.0.1:39603/status", host) == link


def test_a_real_dashboard_on_another_loopback_host_opens_at_the_link():
    """A real LocalCluster with its dashboard on 127.0.0.2: the link the service reports
    answers there (Dask's own link, on 127.0.0.1, would not)."""
    executor = ex.Executor(Settings(host="127.0.0.2", dashboard=True, dashboard_port=0,
                                    workers=1))
    client, cluster = executor._connect()
    try:
        assert executor.dashboard.startswith("http://127.0.0.2:")
        assert httpx.get(executor.dashboard, timeout=30).status_code == 200
    finally:
        ex._close_quietly(client, cluster, 10.0)
