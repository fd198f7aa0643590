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
    """JSON requests to a server at ``url``: (status, body); ``app``: the server's app (its ``state.store``)."""

    def __init__(self, url: str, app=None):
        self.url, self.app = url.rstrip("/"), app

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

    def shot(self, gid: str, body: dict):
        """A person's turn on game ``gid``: ``body`` with the game's current ``turn`` (unless it names one)."""
        if "turn" not in body:
            status, got = self("GET", f"/api/games/{gid}")
            assert status == 200, got
            body = {"turn": got["state"]["turn"], **body}
        return self("POST", f"/api/games/{gid}/shot", body)


def start_server(**kw) -> tuple:
    """A play server on 127.0.0.1 (any free port): (uvicorn server, Client); ``kw``: ``serve``'s options."""
    from billiards_env.play.server import serve
    srv, url = serve(port=0, **kw)
    return srv, Client(url, srv.config.app)


@pytest.fixture(scope="module")
def server():
    from billiards_env.play.server import warm_up
    warm_up()
    srv, client = start_server(max_games=256)  # room for every game a module's tests start (none is dropped)
    yield client
    srv.should_exit = True
