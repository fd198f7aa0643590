"""The play server: a person plays the two-player games against the bots
(or another person at the same screen) in a browser, on the library's own
simulator and rules (docs/play.md). ``create_app`` builds the web app
(Starlette, the ``play`` extra); ``Session`` is one game; ``server.main``
is ``billiards-play`` / ``scripts/play.py``."""
from .session import HUMAN, PlayError, Session

__all__ = ["HUMAN", "PlayError", "Session", "create_app"]


def create_app(*args, **kwargs):
    """The web app (``play.app.create_app``; needs starlette: pip install 'billiards_env[play]')."""
    from .app import create_app as make
    return make(*args, **kwargs)
