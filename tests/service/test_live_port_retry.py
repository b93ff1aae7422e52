"""The live-service fixture starts its server again on another port when the free port it
picked was taken before the server bound it (another service's Dask workers bind ports of
their own): a service test failed with 'the service exited with status 2' when another
process held the port."""
from __future__ import annotations

import socket

from beltstudy.service.cli import demo


def test_a_taken_port_is_retried_on_another(live_service, monkeypatch):
    held = socket.socket()
    held.bind(("127.0.0.1", 0))
    # bound, not listening: the server's bind fails at once and nothing answers on it
    taken = held.getsockname()[1]
    picks = iter([taken])
    real = demo.free_port
    monkeypatch.setattr(demo, "free_port", lambda: next(picks, None) or real())
    try:
        svc = live_service()
    finally:
        held.close()
    assert svc.port != taken
    assert svc.client.health()["status"] in ("ok", "ready")
