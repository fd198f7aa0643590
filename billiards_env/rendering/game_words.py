"""A two-player game's state and rulings in words, for people: the status
panel of ``game.render_game``, the game replays (``game_replay``) and the
viewer page. The rules keep small integer codes (``rules.records``); this
module is where they become words, so no page shows a raw code."""
from __future__ import annotations

import numpy as np

from ..rules import END_NAMES, FOUL_NAMES, GAMES, GameWords
from ..rules import records as R

IN_HAND_WORDS = {R.IN_HAND_NONE: "none", R.IN_HAND_ANYWHERE: "anywhere",
                 R.IN_HAND_KITCHEN: "behind the head string", R.IN_HAND_D: "in the D"}
GROUP_WORDS = {R.GROUP_OPEN: "open", R.GROUP_SOLIDS: "solids", R.GROUP_STRIPES: "stripes"}


def _word(table: dict, code, what: str) -> str:
    """The word of ``code`` in ``table``; a code the table lacks is named as such, never dropped."""
    code = int(code)
    return table.get(code, f"{what} code {code}")


def in_hand_words(code) -> str:
    return _word(IN_HAND_WORDS, code, "ball-in-hand")


def group_words(code) -> str:
    return _word(GROUP_WORDS, code, "group")


def foul_words(code) -> str:
    return _word(FOUL_NAMES, code, "foul")


def end_words(code) -> str:
    return _word(END_NAMES, code, "end")


def game_words(name: str) -> str:
    """The game's title ("9-ball", "snooker"): its registry entry's (``rules.games``)."""
    spec = GAMES.get(name)
    return spec.title if spec is not None else name.replace("_", "-")


def words_of(name: str) -> GameWords:
    """The game's vocabulary (``rules.games.GameWords``); numbered pool balls for an unknown game."""
    spec = GAMES.get(name)
    return spec.words if spec is not None else GameWords()


def call_words(name: str) -> str:
    """What a shooter must call when the game asks for a call."""
    return words_of(name).call or "call the shot"


def pocket_names(pockets) -> list[str]:
    """Names of a table's pockets [P, 3] (x, y, r) by where they lie: the
    head (y = 0, the breaking end) or foot end, left (x < width / 2) or
    right, corner or side (a carom table has none)."""
    p = np.asarray(pockets, dtype=np.float64).reshape(-1, 3)
    if len(p) == 0:
        return []
    lo, hi = p[:, 1].min(), p[:, 1].max()
    mid_x = (p[:, 0].min() + p[:, 0].max()) / 2
    out = []
    for x, y, _ in p:
        side = "left" if x < mid_x else "right"
        if np.isclose(y, lo):
            out.append(f"head {side} corner")
        elif np.isclose(y, hi):
            out.append(f"foot {side} corner")
        else:
            out.append(f"{side} side")
    return out


def balls_words(balls, words: GameWords | None = None) -> str:
    """'the 3', 'the 3 and the 7', 'the 1, the 2 and the 9'; by colour where the game names its balls so
    ('the red, the red and the blue' reads 'two reds and the blue')."""
    words = words or GameWords()
    names = [words.ball(x) for x in balls]
    if words.colours:  # several balls of one colour (snooker's reds) counted
        counted = {}
        for n in names:
            counted[n] = counted.get(n, 0) + 1
        names = [n if k == 1 else f"{_number(k)} {n[4:]}s" for n, k in counted.items()]
    if len(names) <= 1:
        return "".join(names)
    return ", ".join(names[:-1]) + " and " + names[-1]


def _number(k: int) -> str:
    return {2: "two", 3: "three", 4: "four", 5: "five"}.get(k, str(k))


def ball_ids(core, k: int, shooter: int | None = None):
    """Which ball lies in each slot of table ``k``, in games where each player
    has their own cue ball (three-cushion): slot 0 is always the ball of the
    player to move (``shooter``; default the core's), and ball 0 (white) is
    the starter's, so the slots of the second player's innings hold balls
    [1, 0, 2]. None in the other games (slot i is ball i)."""
    if not core.rules.own_cue_balls:
        return None
    s = int(core.game.shooter[k]) if shooter is None else int(shooter)
    return [0, 1, 2] if s == int(core.game.breaker[k]) else [1, 0, 2]


def player_labels(n: int = 2) -> list[str]:
    """How the rulings name the players: 'Player 1', 'Player 2'."""
    return [f"Player {i + 1}" for i in range(n)]


def ruling_words(shot: dict, names: list[str]) -> str:
    """One or two sentences on a recorded shot of a game (the ``game`` entry
    of a replay's shot: ``shooter``, ``before``/``after`` states, the
    record fields and ``pocketed``, ``respotted``, ``declared``, ``called_pocket``; ``off_table``, the balls
    driven off the table, where there are any)."""
    s = int(shot["shooter"])
    who, other = names[s], names[1 - s]
    before, after = shot["before"], shot["after"]
    if shot.get("replaced"):  # snooker, after a foul and a miss
        return f"{who} has the balls replaced: {other} plays again."
    if shot.get("passed"):
        return f"{who} passes the shot back: {other} shoots."
    words = words_of(shot.get("game_name", ""))
    lead = f"{who} breaks" if before.get("break") else (f"{who} pushes out" if shot.get("push_out") else
                                                        f"{who} shoots")
    if shot.get("nominated") is not None:
        called = f" (nominated: {words.ball(shot['nominated'])})"
    else:
        called = f" (called: {shot['called_pocket']})" if shot.get("called_pocket") else ""
    if not words.pockets:  # a carom game: a point made or not
        pts = int(shot.get("points", 0))
        pots = f": {'a point' if pts == 1 else f'{pts} points'}" if pts > 0 else ": no point"
    else:
        pots = f", pots {balls_words(shot['pocketed'], words)}" if shot["pocketed"] else ", pots nothing"
    if shot.get("off_table"):  # balls driven off the table (only with the airborne effect)
        pots += f", drives {balls_words(shot['off_table'], words)} off the table"
    text = lead + called + pots
    if not words.pockets and not shot.get("game_over"):
        text += f". {who} stays at the table." if not shot["turn_over"] else f". {other} to shoot."
    elif shot.get("game_over"):
        w = int(shot["winner"])
        text += f": {shot['end']}. {names[w]} wins." if w >= 0 else f": {shot['end']}."
    elif not shot["legal"]:
        text += f": foul ({shot['foul']})"
        f = int(after["fouls"][s])
        text += f", {who}'s {_ordinal(f)} foul in a row. " if f > 1 else ". "
        hand = after["ball_in_hand"]
        text += f"{names[after['to_move']]} to shoot" + (f", ball in hand {hand}." if hand != "none" else ".")
    elif shot.get("push_out"):
        text += f". {other} may play from here or pass the shot back."
    elif not shot["turn_over"]:
        text += f": legal. {who} stays at the table."
    else:
        text += f": legal. {other} to shoot."
    if shot.get("respotted"):
        again = balls_words(shot["respotted"], words)
        text += f" {again[:1].upper()}{again[1:]} {'is' if len(shot['respotted']) == 1 else 'are'} respotted."
    groups_before, groups_after = before.get("groups"), after.get("groups")
    if groups_after and groups_before != groups_after and groups_after[s] != "open":
        text += f" {who} takes {groups_after[s]}, {other} {groups_after[1 - s]}."
    if shot.get("truncated") and not shot.get("game_over"):
        text += f" The game is cut at {after['shots']} shots: a draw."
    return text.strip()


def _ordinal(n: int) -> str:
    return {1: "first", 2: "second", 3: "third"}.get(n, f"{n}th")
