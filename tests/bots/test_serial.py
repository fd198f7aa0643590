"""``bots.serial``: a decision on a few tables runs on one thread, and plays the same plans as on all threads."""
import numba
import numpy as np
import pytest

from billiards_env.bots import make_bot
from billiards_env.bots import serial as SE
from billiards_env.bots.learned.proposal_bot import shipped_games
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.play import play_round


def _plan(p) -> np.ndarray:
    return np.column_stack([p.phi, p.speed, p.a, p.b, p.placement, p.declare, p.pocket, p.ball])


def test_serial_sets_one_thread_for_few_tables_and_restores():
    blas = SE.blas_threads()
    before = numba.get_num_threads(), blas[1]() if blas else None
    with SE.serial(1):
        assert numba.get_num_threads() == 1
        assert blas is None or blas[1]() == 1
    assert (numba.get_num_threads(), blas[1]() if blas else None) == before
    with SE.serial(SE.SERIAL_TABLES + 1):
        assert numba.get_num_threads() == before[0]


@pytest.mark.parametrize("name", ["champion", "lookahead-2026.12", "exit-fast"])
def test_one_table_plans_do_not_depend_on_the_threads(name, monkeypatch):
    """One table at a time, the plans on one thread (``serial``) and on every thread are the same, bit for bit
    (seeded 9-ball tables after a ghost shot, both noise levels)."""
    if name == "exit-fast" and "nine_ball" not in shipped_games(name):
        pytest.skip("no shipped exit-fast network")
    plans = {}
    for serial_tables in (SE.SERIAL_TABLES, 0):
        monkeypatch.setattr(SE, "SERIAL_TABLES", serial_tables)
        for noise in ("tournament", "none"):
            core = GameCore(GameConfig(game="nine_ball", noise=noise), 3)
            core.streams.seed(np.arange(3), 11 + np.arange(3))
            core.reset_tables(np.arange(3), np.zeros(3, dtype=np.int64))
            play_round(core, [make_bot("ghost", 0), make_bot("ghost", 1)], np.arange(3))
            bot = make_bot(name, seed=0)
            plans[serial_tables, noise] = np.concatenate([_plan(bot.act(core.view(np.array([i])))) for i in range(3)])
    for noise in ("tournament", "none"):
        np.testing.assert_array_equal(plans[SE.SERIAL_TABLES, noise], plans[0, noise])
