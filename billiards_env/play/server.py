"""``billiards-play`` / ``python scripts/play.py``: start the play server
(uvicorn) on the loopback address and open the page in the browser."""
from __future__ import annotations

import argparse
import json
import sys
import threading
import time
import webbrowser

from ..rules import DEFAULT_GAME

LOOPBACK = "127.0.0.1"
DEFAULT_PORT = 8765
LOOPBACK_HOSTS = ("127.0.0.1", "localhost")  # the Host names answered on loopback (a rebound name is refused)


def json_http_protocol():
    """uvicorn's HTTP/1.1 protocol (h11) with its own answer to a request it cannot parse (a malformed request
    line or header, a Content-Length that is not a number) given as JSON like every other error answer."""
    import h11
    from uvicorn.protocols.http.h11_impl import H11Protocol

    class JsonErrorsH11(H11Protocol):
        def connection_made(self, transport):
            super().connection_made(transport)
            self.parse_problem, parse = None, self.conn.next_event

            def next_event():  # keeps h11's own reason for the answer
                try:
                    return parse()
                except h11.RemoteProtocolError as exc:
                    self.parse_problem = str(exc)
                    raise
            self.conn.next_event = next_event

        def send_400_response(self, msg: str) -> None:
            why = getattr(self, "parse_problem", None) or msg
            body = json.dumps({"error": f"the request is not valid HTTP/1.1 ({why[:200]})"}).encode()
            head = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
                    (b"connection", b"close")]
            for event in (h11.Response(status_code=400, headers=head, reason=b"Bad Request"), h11.Data(data=body),
                          h11.EndOfMessage()):
                self.transport.write(self.conn.send(event))
            self.transport.close()
    return JsonErrorsH11


def warm_up(games=(DEFAULT_GAME,)) -> float:
    """Compile the simulator's and bots' kernels before the first person's shot (numba caches them on disk,
    so this is seconds on a first run and fast afterwards): seconds taken."""
    from .session import HUMAN, Session
    t0 = time.perf_counter()
    for g in games:
        s = Session("warm-up", g, [HUMAN, "ghost"], 0)
        s.human_shot({"aim": 1.5707963267948966, "speed": 8.0, "player": 0})
        s.bot_shot()
    return time.perf_counter() - t0


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="billiards-play", description=__doc__.split("\n\n")[0])
    ap.add_argument("--host", default=LOOPBACK, help=f"address to listen on (default {LOOPBACK}: this machine only; "
                                                     "another address lets other machines play on it)")
    ap.add_argument("--port", type=int, default=DEFAULT_PORT, help=f"port (default {DEFAULT_PORT}; 0: any free port)")
    ap.add_argument("--no-browser", action="store_true", help="do not open the page in a browser")
    ap.add_argument("--max-games", type=int, default=None,
                    help="games kept in memory (default play.store.MAX_GAMES); a game in play is never dropped")
    ap.add_argument("--bot", action="append", default=[], metavar="MODULE:FACTORY",
                    help="offer a bot of your own as well (docs/bots.md); repeatable")
    ap.add_argument("--no-warm-up", action="store_true", help="skip compiling the kernels before serving")
    return ap


def serve(host: str = LOOPBACK, port: int = DEFAULT_PORT, max_games: int | None = None, log_level: str = "warning",
          extra_bots=(), **limits):
    """A started uvicorn server in a background thread: (server, url). ``server.should_exit = True`` stops it.
    ``limits``: ``create_app``'s ``idle_s``, ``finished_idle_s``, ``body_timeout`` (tests shorten them)."""
    import uvicorn

    from .app import MAX_GAMES, create_app
    trusted = LOOPBACK_HOSTS if host in (LOOPBACK, "localhost") else None  # on loopback: no rebound names
    app = create_app(MAX_GAMES if max_games is None else max_games, extra_bots, allowed_hosts=trusted, **limits)
    config = uvicorn.Config(app, host=host, port=port, log_level=log_level, lifespan="off",
                            http=json_http_protocol())
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    while not server.started:
        if not thread.is_alive():
            raise RuntimeError(f"the play server could not start on {host}:{port} (is the port in use?)")
        time.sleep(0.02)
    bound = server.servers[0].sockets[0].getsockname()[1]
    return server, f"http://{'127.0.0.1' if host in ('0.0.0.0', LOOPBACK) else host}:{bound}/"


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError:
        print("the play server needs starlette and uvicorn: pip install 'billiards_env[play]'", file=sys.stderr)
        return 2
    if not args.no_warm_up:
        print("compiling the simulator and the bots (fast after the first run)...", flush=True)
        print(f"ready in {warm_up():.1f} s", flush=True)
    try:
        server, url = serve(args.host, args.port, args.max_games, extra_bots=args.bot)
    except (ValueError, TypeError, RuntimeError) as exc:
        print(f"billiards-play: {exc}", file=sys.stderr)
        return 2
    print(f"billiards_env play server at {url} (Ctrl-C stops it)", flush=True)
    if not args.no_browser:
        webbrowser.open(url)
    try:
        while server.started and not server.should_exit:
            time.sleep(0.5)
    except KeyboardInterrupt:
        server.should_exit = True
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
