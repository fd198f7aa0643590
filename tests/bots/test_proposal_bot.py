"""The proposal network's players (bots.learned.proposal_bot, proposal_net) and their shot space
(bots.planner.shot_space, proposals): the space round-trips, the network's distribution, the search over the hand
prior, the errors, and the shipped players by name without torch."""
from __future__ import annotations

import numpy as np
import pytest

from billiards_env.bots import make_bot
from billiards_env.bots.learned import proposal_bot as PB
from billiards_env.bots.learned import proposal_net as PN
from billiards_env.bots.planner import proposals as PR
from billiards_env.bots.planner import shot_space as SS
from billiards_env.rules import DEFAULT_GAME, GAMES, IN_HAND_ANYWHERE
from billiards_env.testing.positions import game_table

BALLS = {0: (0.40, 0.60), 1: (0.70, 1.40), 2: (1.00, 2.20), 3: (0.30, 1.90), 5: (0.90, 0.90), 9: (0.62, 2.40)}
FAST_NAME = "billiards_env.bots.learned.proposal_bot:exit_fast"
SEARCH_NAME = "billiards_env.bots.learned.proposal_bot:exit_search"


def hand_player(**kw):
    return PB.ProposalPlayer("hand", seed=0, nets={DEFAULT_GAME: (None, {})}, **kw)


@pytest.mark.parametrize("hand", [False, True])
def test_the_shot_space_round_trips(hand):
    """Every legal proposal of a table (with and without ball in hand), decoded to a plan and encoded back, is
    itself; the joint index splits into its (slot, turn, variant)."""
    core = game_table(DEFAULT_GAME, BALLS, hand=IN_HAND_ANYWHERE if hand else 0)
    view = core.view([0])
    bot = hand_player()
    layout = SS.Layout(view, [0], bot.la)
    sp = layout.space
    joint = SS.legal_proposals(layout, 0)
    off_centre = np.arange(sp.T) != SS.CENTRE
    assert len(joint) > sp.V * 10 and layout.mask[0][:, off_centre].any() == hand
    c = SS.decode(layout, np.zeros(len(joint), np.int64), joint)
    back = SS.encode(layout, np.zeros(len(joint), np.int64), bot.plan(c, np.arange(len(joint))))
    np.testing.assert_array_equal(back, joint)
    np.testing.assert_array_equal(sp.index(*sp.split(joint)), joint)


def test_the_networks_distribution_sums_to_one_over_the_legal_proposals():
    view = game_table(DEFAULT_GAME, BALLS).view([0])
    layout = SS.Layout(view, [0], hand_player().la)
    out = np.random.default_rng(0).normal(size=layout.mask.shape[:2] + (1 + layout.space.T + layout.space.V,))
    lp = PN.joint_logp(out, layout.mask)
    legal = np.zeros(lp.shape, bool)
    legal[0, SS.legal_proposals(layout, 0)] = True
    assert np.isfinite(lp[legal]).all() and np.isneginf(lp[~legal]).all()
    assert abs(np.exp(lp[legal]).sum() - 1) < 1e-9
    for seed in range(20):       # the fast player's factored argmax is the distribution's mode
        out = np.random.default_rng(seed).normal(size=out.shape) * 3
        assert PN.best_proposal(out, layout.mask)[0] == np.argmax(PN.joint_logp(out, layout.mask)[0])


def test_the_search_over_the_hand_prior_pots_an_open_ball():
    """The 1 hangs in the foot-right corner; without noise the search plays a pot of the 1 that drops it and keeps
    the table, and its policy target gives most of its mass to pots."""
    core = game_table(DEFAULT_GAME, {0: (0.70, 1.50), 1: (1.15, 2.40), 9: (0.30, 1.00)})
    view = core.view([0])
    bot = hand_player(budget=PR.SearchBudget(k=24, first=6), record=True)
    plan = bot.act(view)
    pv = view.preview(plan, [0])
    assert pv.pocket[0, 1] >= 0 and not pv.record.turn_over[0] and pv.record.legal[0]
    t = bot.trace[-1]
    assert t["y"].sum() + t["y_rest"].sum() == pytest.approx(1.0)
    pots = np.asarray(t["joint"]) // (len(SS.TURNS) * SS.SPEED_BINS * SS.HEIGHT_BINS) < SS.space_of(view).start[SS.SAFE]
    assert t["y"][pots].sum() > 0.5


def test_players_refuse_what_they_cannot_play(tmp_path):
    games = PB.games()
    assert DEFAULT_GAME in games
    assert all(GAMES[g].words.pockets and not GAMES[g].own_bots for g in games)
    carom = next(g for g, s in GAMES.items() if not s.words.pockets)
    with pytest.raises(ValueError, match="without pockets"):
        hand_player().act(game_table(carom, {0: (0.5, 0.5), 1: (0.7, 1.0), 2: (0.9, 2.0)}).view([0]))
    empty = PB.ProposalPlayer(PB.FAST, root=tmp_path, budget=None)
    with pytest.raises(ValueError, match="expert_iteration.py"):
        empty.network(DEFAULT_GAME)
    with pytest.raises(ValueError, match="needs a network"):
        hand_player(budget=None).act(game_table(DEFAULT_GAME, BALLS).view([0]))


def test_shipped_players_load_by_name_without_torch_and_replay_identically(played_twice_without_torch):
    """The shipped 9-ball networks, by name (``module:factory``), in a process where importing torch fails: a
    seeded pairing against ghost played twice gives the same winners and shot counts."""
    out = played_twice_without_torch([(DEFAULT_GAME, FAST_NAME)], n_racks=2, max_shots=40)
    first, second = out[DEFAULT_GAME]
    assert first == second and sum(first[1]) > 4
    out = played_twice_without_torch([(DEFAULT_GAME, SEARCH_NAME)], n_racks=1, max_shots=30)
    first, second = out[DEFAULT_GAME]
    assert first == second and sum(first[1]) > 2


def test_shipped_cards_say_how_they_were_trained():
    fast, search = make_bot(FAST_NAME), make_bot(SEARCH_NAME)
    assert fast.budget is None and search.budget == PB.CARD
    assert make_bot(PB.FAST).budget is None and make_bot(PB.SEARCH).budget == PB.CARD      # the registry's names
    net, card = PB.shipped(PB.SEARCH, DEFAULT_GAME)
    assert isinstance(search.budget_of(card), PR.SearchBudget)
    for name in (PB.FAST, PB.SEARCH):
        net, card = PB.shipped(name, DEFAULT_GAME)
        assert card["game"] == DEFAULT_GAME and len(card["break"]) == 4
        assert card["training"]["rounds"] >= 1 and card["training"]["wall_seconds"] > 0
