"""One self-contained HTML page per replay: viewer.html (script and styles
inline, no network access) with the replay's JSON, the raster
renderer's colours and the rules' words for their codes written into it."""
from __future__ import annotations

import html
import json
from pathlib import Path

from ..rules import END_NAMES, FOUL_NAMES
from .draw import BALL_COLORS, CUSHION_COLOR, FELT_COLOR, POCKET_COLOR, RAIL_COLOR, STYLE_BALL_COLORS
from .game_words import IN_HAND_WORDS
from .replay import Replay

TEMPLATE = Path(__file__).with_name("viewer.html")


def _script_safe(text: str) -> str:
    """JSON text that cannot end the <script> element holding it."""
    return text.replace("</", "<\\/").replace("<!--", "<\\!--")


def replay_html(replay: Replay, title: str | None = None) -> str:
    """The viewer page of ``replay`` as a string (a replay without shots is an error)."""
    if not isinstance(replay, Replay):
        raise TypeError(f"replay_html takes a Replay, got {type(replay).__name__}")
    if len(replay) == 0:
        raise ValueError("the replay has no shots: add at least one (Replay.add_log, record_env_shot or a "
                         "GameRecorder) before writing its page")
    if title is not None:
        replay.data.setdefault("meta", {})["title"] = title
    page = TEMPLATE.read_text()
    colors = json.dumps({"balls": {str(k): list(v) for k, v in BALL_COLORS.items()}, "felt": FELT_COLOR,
                         "styles": {s: {str(k): list(v) for k, v in c.items()} for s, c in STYLE_BALL_COLORS.items()},
                         "rail": RAIL_COLOR, "cushion": CUSHION_COLOR, "pocket": POCKET_COLOR})
    words = json.dumps({"foul": FOUL_NAMES, "end": END_NAMES, "in_hand": IN_HAND_WORDS})
    title = (replay.data.get("meta") or {}).get("title", "billiards_env replay")
    return (page.replace("__TITLE__", html.escape(str(title)))
            .replace("__PALETTE__", _script_safe(colors))
            .replace("__WORDS__", _script_safe(words))
            .replace("__REPLAY_JSON__", _script_safe(replay.to_json())))


def save_replay_html(replay_or_result, path, title: str | None = None, **from_sim) -> Path:
    """Write the viewer page of a ``Replay``, or of a ``simulate(...,
    record=True)`` result (then ``from_sim`` holds ``Replay.from_sim``'s
    arguments: ``table=`` (required), ``start_state=``, ``params=``,
    ``effects=``, ``index=``, ``info=``, ``meta=``). Returns the path."""
    rep = replay_or_result
    if not isinstance(rep, Replay):
        rep = Replay.from_sim(rep, **from_sim)
    elif from_sim:
        raise TypeError(f"arguments {sorted(from_sim)} apply only to a simulate() result, not to a Replay")
    path = Path(path)
    path.write_text(replay_html(rep, title))
    return path
