"""Each game's own words in rulings (``rendering.game_words``, read from the games' registry): snooker names its
balls by colour and a nomination as a nomination, three-cushion a shot as a point or none; and through the
simulator, a snooker frame's and a three-cushion game's recorded rulings read so."""
from __future__ import annotations

import numpy as np
import pytest

from billiards_env.bots import make_bot
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.play import play_round
from billiards_env.rendering.game_replay import GameRecorder
from billiards_env.rendering.game_words import balls_words, ruling_words, words_of

NAMES = ["Player 1", "Player 2"]


def _shot(**kw):
    base = dict(shooter=0, before={"break": False}, after={"to_move": 0, "fouls": [0, 0], "ball_in_hand": "none",
                                                           "shots": 3}, legal=True, turn_over=False,
                game_over=False, pocketed=[], respotted=[])
    return {**base, **kw}


def test_snooker_names_balls_by_colour_and_nominations_as_nominations():
    w = words_of("snooker")
    assert balls_words([1, 5, 19], w) == "two reds and the blue"
    text = ruling_words(_shot(game_name="snooker", nominated=20, pocketed=[20], respotted=[20]), NAMES)
    assert "(nominated: the pink)" in text and "pots the pink" in text and "The pink is respotted" in text
    assert "called" not in text


def test_three_cushion_reads_points():
    made = ruling_words(_shot(game_name="three_cushion", points=1), NAMES)
    missed = ruling_words(_shot(game_name="three_cushion", points=0, turn_over=True), NAMES)
    assert made == "Player 1 shoots: a point. Player 1 stays at the table."
    assert missed == "Player 1 shoots: no point. Player 2 to shoot."
    assert "pots" not in made + missed


def test_pool_games_keep_numbers_and_called_pockets():
    text = ruling_words(_shot(game_name="eight_ball", called_pocket="foot left corner", pocketed=[8],
                              game_over=True, winner=0, end="8 pocketed"), NAMES)
    assert text.startswith("Player 1 shoots (called: foot left corner), pots the 8")


@pytest.mark.parametrize("game,bot,word", [("snooker", "snooker", "nominated: the "), ("three_cushion", "carom", "point")])
def test_recorded_rulings_through_the_simulator(game, bot, word):
    opts = {"rule_options": {"target": 2}} if game == "three_cushion" else {}
    core = GameCore(GameConfig(game=game, noise="tournament", **opts), 1, record=True)
    core.streams.seed([0], [3])
    core.reset_tables([0])
    rec = GameRecorder(core, [0], players=NAMES)
    bots = [make_bot(bot, 0), make_bot(bot, 1)]
    for _ in range(14):
        out = play_round(core, bots, np.arange(1), {"bots": 0.0})
        if out["terminated"][0] or out["truncated"][0]:
            break
    rulings = [s["info"]["game"]["ruling"] for rep in rec.games(0) for s in rep.data["shots"]]
    assert any(word in r for r in rulings), rulings
    if game == "three_cushion":
        assert not any("pots" in r for r in rulings)


def test_snooker_replace_after_a_miss_reads_as_a_replacement():
    text = ruling_words(_shot(game_name="snooker", shooter=1, passed=True, replaced=True, turn_over=True), NAMES)
    assert text == "Player 2 has the balls replaced: Player 1 plays again."
