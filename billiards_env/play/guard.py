"""The play server's door: what every request passes before the app sees it.

``Guard`` (an ASGI middleware) answers at once, with a JSON error and the
connection closed, a request for another host, a body that declares more
than ``MAX_BODY`` bytes, or one whose length is not a whole number; it then
reads the body itself, counting as it reads (never more than ``MAX_BODY``
+ one chunk), within ``BODY_TIMEOUT_S`` (a body shorter than it claims is
answered 408, not left waiting). ``parse_json`` turns a body into JSON
values no deeper than ``MAX_DEPTH`` and no number a float cannot hold.
Every answer here is ``{"error": "..."}`` naming the problem.
"""
from __future__ import annotations

import asyncio
import json
import math

from .session import PlayError

MAX_BODY = 16 * 1024      # bytes: the largest request body read (a shot is ~200; a new game ~100)
BODY_TIMEOUT_S = 10.0     # s: the whole body must arrive within this (16 KB takes milliseconds on any link)
MAX_DEPTH = 8             # JSON nesting: the API's deepest body is 2 ({"placement": [x, y]})
MAX_INT_DIGITS = 20       # digits of a JSON integer: the largest the API takes is a seed below 2**63 (19 digits)


class _TooLarge(Exception):
    pass


class _Gone(Exception):
    pass


# --- JSON answers at the ASGI level ----------------------------------------------------------
async def send_error(send, status: int, message: str, close: bool = True, headers=()) -> None:
    """A JSON ``{"error": message}`` answer; ``close``: the connection is closed after it (the body was not read)."""
    body = json.dumps({"error": message}).encode()
    head = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
    head += [(k.encode(), str(v).encode()) for k, v in headers]
    if close:
        head.append((b"connection", b"close"))
    await send({"type": "http.response.start", "status": status, "headers": head})
    await send({"type": "http.response.body", "body": body})


def _header(scope, name: bytes) -> list[bytes]:
    return [v for k, v in scope.get("headers", ()) if k.lower() == name]


def host_problem(scope, allowed) -> str | None:
    """Why the request's Host is refused (None: it is one of ``allowed``, or ``allowed`` is None)."""
    if allowed is None:
        return None
    hosts = _header(scope, b"host")
    host = hosts[0].decode("latin-1").lower() if hosts else ""
    name = host[1:host.find("]")] if host.startswith("[") else host.rsplit(":", 1)[0] if host.count(":") == 1 else host
    if name in allowed:
        return None
    return (f"this server answers requests for {' or '.join(allowed)} only, not Host {host[:60]!r} "
            "(a page elsewhere may not reach it through another name)")


def length_problem(scope, max_body: int) -> tuple[int, str] | None:
    """(status, why) when the declared Content-Length is not a whole number or is over ``max_body``."""
    values = _header(scope, b"content-length")
    if not values:
        return None
    if len(set(values)) > 1 or not values[0].strip().isdigit():
        shown = b", ".join(values).decode("latin-1")[:40]
        return 400, f"Content-Length {shown!r} is not one whole number of bytes"
    digits = values[0].strip().lstrip(b"0") or b"0"
    if len(digits) > len(str(max_body)) or int(digits) > max_body:
        shown = digits[:20].decode() + ("..." if len(digits) > 20 else "")
        return 413, f"the request body declares {shown} bytes; at most {max_body} are read"
    return None


async def read_body(receive, max_body: int) -> bytes:
    """The request body, read message by message; ``_TooLarge`` as soon as it passes ``max_body``."""
    chunks, size = [], 0
    while True:
        message = await receive()
        if message["type"] == "http.disconnect":
            raise _Gone()
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > max_body:
            raise _TooLarge()
        chunks.append(chunk)
        if not message.get("more_body", False):
            return b"".join(chunks)


def _replay(body: bytes, receive):
    """A ``receive`` that hands the app the body already read, then the client's own messages (disconnect)."""
    sent = False

    async def again():
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()
    return again


class Guard:
    """ASGI middleware: the host check and the bounded, timed body read (module docstring)."""

    def __init__(self, app, allowed_hosts=None, max_body: int = MAX_BODY, body_timeout: float = BODY_TIMEOUT_S):
        self.app, self.allowed = app, None if allowed_hosts is None else tuple(allowed_hosts)
        self.max_body, self.body_timeout = int(max_body), float(body_timeout)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        why = host_problem(scope, self.allowed)
        if why:
            return await send_error(send, 400, why)
        problem = length_problem(scope, self.max_body)
        if problem:
            return await send_error(send, *problem)
        try:
            body = await asyncio.wait_for(read_body(receive, self.max_body), self.body_timeout)
        except _TooLarge:
            return await send_error(send, 413, f"the request body is over {self.max_body} bytes; reading stopped there")
        except asyncio.TimeoutError:
            return await send_error(send, 408, f"the request body did not arrive within {self.body_timeout:g} s "
                                               "(shorter than its Content-Length?)")
        except _Gone:
            return None
        await self.app(scope, _replay(body, receive), send)


# --- the body as JSON ------------------------------------------------------------------------
def nesting_problem(text: str, limit: int = MAX_DEPTH) -> str | None:
    """Why ``text`` nests arrays or objects too deeply (None: at most ``limit`` levels), read in one pass
    that skips strings, so a deep body is refused before the JSON parser recurses into it."""
    depth, in_string, escaped = 0, False, False
    for ch in text:
        if in_string:
            escaped, in_string = (False, True) if escaped else (ch == "\\", ch != '"')
        elif ch == '"':
            in_string = True
        elif ch in "[{":
            depth += 1
            if depth > limit:
                return f"the request body nests arrays or objects more than {limit} deep"
        elif ch in "]}":
            depth -= 1
    return None


def _no_constant(name: str):
    raise PlayError(400, f"the request body has {name}, which is not a JSON number: numbers must be finite")


def _bounded_int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_INT_DIGITS:
        raise PlayError(400, f"the request body has an integer of {len(text.lstrip('-'))} digits; "
                             f"at most {MAX_INT_DIGITS} are taken")
    return int(text)


def _finite_float(text: str) -> float:
    v = float(text)
    if not math.isfinite(v):
        raise PlayError(400, f"the number {text[:40]} in the request body is beyond a float's range")
    return v


def parse_json(raw: bytes):
    """The body's JSON value ({} for an empty body), or PlayError(400) naming what is wrong with it."""
    if not raw.strip():
        return {}
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise PlayError(400, f"the request body is not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    why = nesting_problem(text)
    if why:
        raise PlayError(400, why)
    try:
        return json.loads(text, parse_constant=_no_constant, parse_int=_bounded_int, parse_float=_finite_float)
    except RecursionError:  # not reached under MAX_DEPTH; kept so no parse can end in a 500
        raise PlayError(400, "the request body nests too deeply to read") from None
    except ValueError as exc:
        raise PlayError(400, f"the request body is not valid JSON ({exc})") from None
