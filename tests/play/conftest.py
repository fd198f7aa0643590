"""A play server on 127.0.0.1 started by the tests (a free port, in a thread), and the
headless Chromium of the viewer's browser tests (tests/rendering/conftest.py: skipped
without it, a failure under CI)."""
from __future__ import annotations

import json
import urllib.error
import urllib.request

import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")

from tests.rendering.conftest import browser  # noqa: E402,F401  (the shared headless Chromium)


class Client:
    """JSON requests to a server at ``url``: (status, body)."""

    def __init__(self, url: str):
        self.url = url.rstrip("/")

    def raw(self, method: str, path: str, data: bytes | None = None, headers=None, timeout=60):
        req = urllib.request.Request(self.url + path, method=method, data=data,
                                     headers=headers or {"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=timeout) as f:
                return f.status, f.read()
        except urllib.error.HTTPError as e:
            return e.code, e.read()

    def __call__(self, method: str, path: str, body=None):
        status, data = self.raw(method, path, None if body is None else json.dumps(body).encode())
        try:
            return status, json.loads(data)
        except ValueError:
            return status, data.decode()


@pytest.fixture(scope="module")
def server():
    from billiards_env.play.server import serve, warm_up
    warm_up()
    srv, url = serve(port=0, max_games=4)
    yield Client(url)
    srv.should_exit = True
