"""``champion`` (bots.planner): throw-corrected aims, successive halving, the searched break, loading and
determinism."""
import numpy as np

from billiards_env.bots import make_bot
from billiards_env.bots.planner import Champion
from billiards_env.bots.planner import candidates as CAND
from billiards_env.bots.planner.aim import corrected, departure
from billiards_env.bots.planner.breaks import NOMINAL, BreakSearch
from billiards_env.bots.planner.halving import halve
from billiards_env.bots.planner.windows import windows_of
from billiards_env.contract import ShotPlan
from billiards_env.contract.codec import MAX_ACTION_ELEVATION
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.physics.strike import Shots
from billiards_env.studies.matches import play_pairing
from billiards_env.testing.positions import game_table

R = 0.028575
OBJ = np.array([0.635, 1.0])         # the 1, on the long axis, 1.7 m from the foot-right corner (pocket 5)
CUE = np.array([0.76909, 0.47173])   # the cue ball placed for a 40-degree cut of it into pocket 5


def test_throw_corrected_aim_pots_where_the_ghost_ball_aim_misses():
    """A 40-degree cut at a soft speed: the ghost-ball aim through the measured window's centre throws the 1
    off the line by a few tenths of a degree and misses the corner from 1.7 m; the corrected aim pots it (both
    played through ``view.preview``, without noise)."""
    view = game_table("nine_ball", {0: tuple(CUE), 1: tuple(OBJ)}).view([0])
    want, half, _, dist = windows_of(view).aim(np.array([5]), OBJ[None])
    assert half[0] > 0.01
    ghost = OBJ - 2 * R * np.array([np.cos(want[0]), np.sin(want[0])])
    phi0 = np.arctan2(*(ghost - CUE)[::-1])
    speed, zero = np.array([2.04]), np.zeros(1)
    phi = corrected(view, CUE[None], OBJ[None], want, np.array([phi0]), speed, zero, zero)
    thrown = departure(view, CUE[None], OBJ[None], np.array([phi0]), speed, zero, zero)[0] - want[0]
    fixed = departure(view, CUE[None], OBJ[None], phi, speed, zero, zero)[0] - want[0]
    assert abs(thrown) > np.radians(0.5) and abs(fixed) < np.radians(0.02)
    pv = view.preview(ShotPlan.of(Shots(np.array([phi0, phi[0]]), 2.04, 0.0, 0.0)), np.zeros(2, int))
    assert pv.pocket[0, 1] < 0            # the ghost-ball aim misses
    assert pv.pocket[1, 1] == 5           # the corrected aim pots the 1 in the corner


def test_successive_halving_samples_the_better_candidate_more():
    """Two candidates on one table, worth 0.7 and 0.3 with noise: after the first round only the better one
    keeps drawing."""
    truth = np.array([0.3, 0.7])

    def judge(idx, draws):
        return truth[idx] + 0.1 * draws[:, 0]

    mean, count = halve(judge, np.zeros(2, int), 1, np.zeros(2), np.ones(2, bool), np.random.default_rng(0))
    assert count[1] > count[0] > 0
    assert abs(mean[1] - 0.7) < 0.05


def test_searched_break_beats_the_fixed_break():
    """The break searched on 16 racks, judged on 32 other racks under tournament noise, is worth more to the
    breaker (``values``: the leave, a foul handing over ball in hand) than ghost's standard break."""
    n = 48
    core = GameCore(GameConfig(game="nine_ball", noise="tournament"), n)
    core.streams.seed(np.arange(n), 500 + np.arange(n))
    core.reset_tables(np.arange(n), np.zeros(n, dtype=np.int64))
    view = core.view(np.arange(n))
    bot = Champion(seed=0)
    search = BreakSearch()
    best = search.search(bot, view, np.arange(16), np.random.default_rng(1), n=96,
                         rounds=((1.0, 1), (0.25, 4), (0.06, 12)))
    held = np.repeat(np.arange(16, n), 8)
    rng = np.random.default_rng(2)
    worth = []
    for strike in (best, np.array(NOMINAL)):
        plan = bot.la.break_plan(view, held, np.broadcast_to(strike, (len(held), 4)))
        worth.append(bot.values(view, view.preview(plan, held, noise="env", rng=rng)).mean())
    assert worth[0] > worth[1], worth


def test_registry_loads_and_games_repeat():
    """``champion`` and the frozen ``lookahead-2026.12`` load by name and play a seeded game the same twice."""
    bots = make_bot("champion", seed=1), make_bot("lookahead-2026.12", seed=2)
    assert isinstance(bots[0], Champion) and bots[1].name == "lookahead-2026.12"
    runs = [play_pairing("champion", "lookahead-2026.12", "nine_ball", n_racks=1, seed=3, max_shots=12)
            for _ in range(2)]
    assert np.array_equal(runs[0].winner, runs[1].winner)
    assert runs[0].summary() == runs[1].summary()


def test_without_noise_the_next_shot_is_searched_exactly():
    """With the env's noise off, champion values its best candidates by the next shot searched from each one's
    exact outcome: with the 8 and the 9 left it finds the 8 played so that the 9 drops next (value 1, a win),
    where the one-ply leave (``exact_plies=1``) can say no more than 0.9; the env then plays both and the game
    is won."""
    core = game_table("nine_ball", {0: (0.64, 1.6), 8: (0.4, 2.2), 9: (0.9, 0.6)})
    assert not core.view([0]).noise.enabled
    _, _, one = Champion(seed=0, exact_plies=1).decide(core.view([0]), np.arange(1))
    bot = Champion(seed=0)
    c, best, val = bot.decide(core.view([0]), np.arange(1))
    assert one[0] <= 0.9 + 1e-6 and val[0] == 1.0
    out = core.step(core.actions_of(bot.plan(c, best), [0]), [0])
    assert out["info"]["pocketed"][0, 8] and core.game.shooter[0] == 0 and not core.game.over[0]
    plan = bot.act(core.view([0]))
    out = core.step(core.actions_of(plan, [0]), [0])
    assert core.game.over[0] and core.game.winner[0] == 0


def test_without_noise_the_break_is_searched_on_each_rack():
    """With the env's noise off, champion searches its break on the rack in front of it (its searched strike
    and others over the same ranges, each previewed exactly): on 16 seeded 9-ball racks every break keeps the
    table or wins, where the one searched strike kept it on 9."""
    n = 16
    kept = {}
    for exact_breaks in (64, 0):
        core = GameCore(GameConfig(game="nine_ball", noise="none"), n)
        core.streams.seed(np.arange(n), np.arange(n) + 500)
        core.reset_tables(np.arange(n), breaker=np.zeros(n, dtype=np.int64))
        plan = Champion(seed=0, exact_breaks=exact_breaks).act(core.view(np.arange(n)))
        rec = core.step(core.actions_of(plan, np.arange(n)), np.arange(n))["record"]
        kept[exact_breaks] = int(((~rec.turn_over) | (rec.game_over & (rec.winner == 0))).sum())
    assert kept[64] == n and kept[0] < n, kept


def test_escapes_jump_and_masse_out_of_a_hook_where_balls_fly():
    """Hooked (the 1 straight behind the 5, no open pot): with balls flying (``effects={"airborne": True}``) the
    search adds jump and massé strokes at the legal ball (``candidates.escapes``), and some of them clear the
    blocker and strike the 1 first, as the preview (the env's own turn) plays them; on planar equipment, and
    with ``Parts(escapes=False)``, there are none. The chosen plan is worth at least the best escape."""
    from billiards_env.bots.planner.bot import Parts
    balls = {0: (0.635, 0.6), 5: (0.635, 0.75), 1: (0.635, 1.2), 9: (1.1, 2.2)}
    core = game_table("nine_ball", balls, effects={"airborne": True})
    view = core.view([0])
    bot = Champion(seed=1)
    c = bot.candidates(view, np.array([0]))
    esc = c["theta"] > 0
    assert esc.sum() >= 20 and (c["prob"][~c["safe"]] < 0.2).all()
    assert ((c["a"][esc] != 0) & (c["theta"][esc] > np.radians(59))).any()  # massé strokes among them
    pv = view.preview(bot.plan(c, np.flatnonzero(esc)), c["row"][esc])
    over = (pv.first_contact == 1)
    assert over.any(), pv.first_contact  # a jump over the 5 (or a massé around it) meets the 1 first
    plan = bot.act(view)
    assert bot.last_value[0] >= bot.values(view, pv)[over].max() - 1e-12
    flat = game_table("nine_ball", balls).view([0])
    assert not (Champion(seed=1).candidates(flat, np.array([0]))["theta"] > 0).any()
    assert not (Champion(seed=1, parts=Parts(escapes=False)).candidates(view, np.array([0]))["theta"] > 0).any()
    assert plan.theta.shape == (1,)
    # every stroke is one the env's action can carry (its steepest cue, contract.codec): the chosen plan encodes
    assert max(CAND.JUMP_THETAS + CAND.MASSE_THETAS) <= MAX_ACTION_ELEVATION
    assert core.actions_of(plan, [0]).shape == (1, 9)


# a 10-ball table from a match (seed 1): the 4 (the lowest ball) on the foot cushion with no open pot, the 5
# between it and the table's centre, the 7-10 along the foot cushion
HIDDEN_FOUR = {4: (0.4307, 2.5026), 5: (0.5458, 2.1198), 7: (1.0740, 2.4808), 8: (0.3788, 2.4532),
               9: (0.9251, 2.4753), 10: (1.1732, 2.4958)}


def test_ten_ball_ball_in_hand_safety_is_played_from_a_spot_that_sees_the_lowest_ball():
    """Ball in hand with no open pot: lookahead's ball-in-hand starts fall back to the table's centre, where the
    5 hides the 4, and every safety from there fouled (the 5 or another ball first). Champion adds safeties
    from spots around the 4 that see it (``candidates.hand_safeties``) and values the opponent's ball in hand
    at ``HAND_VALUE`` at least; its safety is then legal under tournament noise."""
    from billiards_env.bots.planner.bot import Parts
    from billiards_env.rules import records as RR
    core = game_table("ten_ball", HIDDEN_FOUR, hand=RR.IN_HAND_ANYWHERE, noise="tournament")
    view = core.view([0])

    def fouls(bot):
        c, best, _ = bot.decide(view, np.arange(1))
        idx = np.full(32, best[0])
        pv = view.preview(bot.plan(c, idx), np.zeros(32, np.int64), noise=bot.la.noise(view),
                          draws=np.random.default_rng(5).normal(size=(32, 4)))
        return c["placement"][best[0]], (pv.record.foul > 0).mean()

    spot, rate = fouls(Champion(seed=0))
    assert np.hypot(*(spot - HIDDEN_FOUR[4])) < 0.8 and rate < 0.25
    old_spot, old_rate = fouls(Champion(seed=0, parts=Parts(hand_safe=False, option=False)))
    assert np.allclose(old_spot, [0.635, 1.27]) and old_rate > 0.75


def test_kick_scan_finds_the_legal_kicks_of_a_hooked_table():
    """Hooked (the 1 straight behind the 5, the cue ball where it lies): ``candidates.kick_scan`` previews
    ``SCAN_DIRS`` directions without noise and keeps the runs of directions whose shot is legal, the widest
    first; every run's centre struck at ``SCAN_SPEED`` meets the 1 first, legally. A table whose cue ball sees
    its legal ball full gets no scan, and neither does a placed cue ball."""
    from billiards_env.rules import records as RR
    core = game_table("nine_ball", {0: (0.635, 0.6), 5: (0.635, 0.75), 1: (0.635, 1.2), 9: (1.1, 2.2)},
                      noise="tournament")
    view = core.view([0])
    bot = Champion(seed=3)
    rows, cue = np.arange(1), view.pos[:, 0].copy()
    c = CAND.kick_scan(bot, view, rows, cue, np.zeros(1, bool))
    assert c is not None and c["safe"].all() and (c["row"] == 0).all()
    mid = c["speed"] == CAND.SCAN_SPEED
    assert mid.sum() >= 3, c
    pv = view.preview(bot.plan(c, np.flatnonzero(mid)), c["row"][mid])
    centre = pv.record.foul == RR.FOUL_NONE
    assert (pv.first_contact[centre] == 1).all() and centre.mean() >= 0.5, (pv.record.foul, pv.first_contact)
    assert CAND.kick_scan(bot, view, rows, cue, np.ones(1, bool)) is None
    open_view = game_table("nine_ball", {0: (0.3, 0.6), 5: (0.635, 0.75), 1: (0.635, 1.2), 9: (1.1, 2.2)}).view([0])
    assert CAND.kick_scan(bot, open_view, rows, open_view.pos[:, 0].copy(), np.zeros(1, bool)) is None
    # the runs of a circular scan: the one across the end of the array is joined, the widest comes first
    assert CAND._runs(np.array([1, 1, 0, 0, 1, 1, 1, 0, 1], bool)) == [(4, 3), (8, 3)]
    assert CAND._runs(np.zeros(4, bool)) == [] and CAND._runs(np.ones(4, bool)) == [(0, 4)]


def test_safety_grid_covers_the_soft_shots_at_the_nearest_legal_balls():
    """``candidates.safety_grid``: at the nearest legal ball(s), every contact offset from full to 0.95 of the
    thinnest hit at every grid speed and tip height, all safeties; on a table with no open pot (the 1 on the
    foot cushion behind the 9's line, the cue ball far up the table) the grid's best noise-free safety is worth
    at least lookahead's best random one, and champion's chosen shot is legal under tournament noise on most of
    32 seeded draws."""
    from billiards_env.rules import records as RR
    core = game_table("nine_ball", {0: (0.4, 0.7), 1: (0.9, 2.48), 9: (0.7, 2.2)}, noise="tournament")
    view = core.view([0])
    bot = Champion(seed=2)
    rows, cue = np.arange(1), view.pos[:, 0].copy()
    g = CAND.safety_grid(bot, view, rows, cue, np.zeros(1, bool))
    n = CAND.GRID_CUTS * len(CAND.GRID_SPEEDS) * len(CAND.GRID_HEIGHTS)
    assert len(g["row"]) == n and g["safe"].all()   # one legal ball in 9-ball
    to = np.subtract(view.pos[0, 1], cue[0])
    half = np.arcsin(2 * view.params.R / np.hypot(*to)) * 0.95
    off = (g["phi"] - np.arctan2(to[1], to[0]) + np.pi) % (2 * np.pi) - np.pi
    assert np.isclose(off.max(), half) and np.isclose(off.min(), -half) and np.isclose(np.abs(off).min(), 0)
    assert set(np.round(g["speed"], 6)) == set(CAND.GRID_SPEEDS)
    lo = bot.la.safeties(view, rows, cue, np.zeros(1, bool))
    v_grid = bot.values(view, view.preview(bot.plan(g, np.arange(n)), g["row"])).max()
    lo_idx = np.arange(len(lo["row"]))
    lo_plan = ShotPlan.of(Shots(lo["phi"], lo["speed"], lo["a"], lo["b"]), placement=lo["placement"])
    v_la = bot.values(view, view.preview(lo_plan, lo["row"][lo_idx])).max()
    assert v_grid >= v_la - 1e-9, (v_grid, v_la)
    c, best, _ = bot.decide(view, rows)
    idx = np.full(32, best[0])
    pv = view.preview(bot.plan(c, idx), np.zeros(32, np.int64), noise=bot.la.noise(view),
                      draws=np.random.default_rng(5).normal(size=(32, 4)))
    assert (pv.record.foul == RR.FOUL_NONE).mean() >= 0.75
