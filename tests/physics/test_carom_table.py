"""The carom match table and carom equipment (physics.table.Table.carom, PhysicsParams.carom)."""
import numpy as np

from billiards_env.physics.params import PhysicsParams
from billiards_env.physics.simulate import simulate
from billiards_env.physics.state import BallState
from billiards_env.physics.strike import strike_velocity
from billiards_env.physics.table import Table
from billiards_env.rendering import ball_color, render_table
from billiards_env.rendering.draw import world_to_pixel


def test_carom_table_is_the_umb_match_table_without_pockets():
    t, p = Table.carom(), PhysicsParams.carom()
    assert (t.width, t.length) == (1.42, 2.84) and not t.has_pockets and t.style == "carom"
    assert len(t.segments) == 4 and len(t.tips) == 0
    assert 0.0605 / 2 < p.R <= 0.0615 / 2 and 0.205 <= p.m <= 0.220 and p.h_c == 0.037
    assert PhysicsParams.preset("carom") == p
    assert abs(p.max_speed - PhysicsParams.standard().max_speed) < 1e-3  # the cue still reaches ~10 m/s


def test_a_hard_shot_on_the_carom_table_stays_on_it():
    t, p = Table.carom(), PhysicsParams.carom()
    s = BallState.from_positions([[0.71, 0.7], [0.4, 1.5], [1.0, 2.2]])
    s = strike_velocity(s, 0.3, 6.0, 0.0, 0.3, params=p)
    r = simulate(s, t, p)
    assert not r.truncated[0] and r.cushion_hits[0].sum() > 3
    assert (r.state.pocket == -1).all()
    x, y = r.state.pos[0, :, 0], r.state.pos[0, :, 1]
    assert (x >= p.R - 1e-9).all() and (x <= t.width - p.R + 1e-9).all()
    assert (y >= p.R - 1e-9).all() and (y <= t.length - p.R + 1e-9).all()


def test_render_draws_carom_balls_without_numbers_and_the_diamonds():
    t, p = Table.carom(), PhysicsParams.carom()
    pos = np.array([[0.3, 0.5], [0.7, 1.4], [1.1, 2.3]])
    img = render_table(t, p, pos, ppm=300)
    for i in range(3):
        c, r = world_to_pixel(t, pos[i], 300).round().astype(int)
        assert tuple(img[r, c]) == ball_color(i, "carom")  # a plain ball: its centre is its colour, no number disc
    assert ball_color(2, "carom")[0] > 150 and ball_color(2, "carom")[1] < 60  # red
    # a sight on the long rail, halfway across the drawn rail at 1/8 of the length
    c, r = world_to_pixel(t, (-0.04, t.length / 8), 300).round().astype(int)
    assert tuple(img[r, c]) == (232, 220, 192)
    pool = render_table(Table.pool(9), PhysicsParams.standard(), pos[:2], ppm=300)
    c, r = world_to_pixel(Table.pool(9), pos[1], 300).round().astype(int)
    assert tuple(pool[r, c]) == (255, 255, 255)  # a pool ball keeps its number on a white disc


def test_carom_hard_cases_keep_every_invariant():
    """The fuzzer's carom tables (frozen pairs, cushion-frozen balls, extreme spin), with the contact order
    kept: every invariant of billiards_env.testing holds."""
    from billiards_env.testing import carom_batch, run_batch
    rng = np.random.default_rng(5)
    s, t, p = carom_batch(rng, 256)
    d = np.linalg.norm(s.pos[:, :, None] - s.pos[:, None], axis=-1) + np.eye(3) * 9
    assert (np.abs(d - 2 * p.R) < 1e-9).any()  # some balls are frozen together
    assert (np.isclose(s.pos, p.R) | np.isclose(s.pos[..., 0:1], t.width - p.R)).any()  # some on a cushion
    res, viol = run_batch(s, t, p, "event")
    assert res.contacts is not None and not any(viol), [v for v in viol if v][:3]


def test_fuzz_script_quick_on_the_carom_table(tmp_path):
    """scripts/fuzz.py --table carom at a tiny size: runs, fuzzes the carom table, finds nothing."""
    import json
    import pathlib
    import subprocess
    import sys
    root = pathlib.Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, str(root / "scripts" / "fuzz.py"), "--table", "carom", "--shots", "64",
                          "--batch", "32", "--seed", "3", "--summary", str(tmp_path / "s.json"), "--regressions",
                          str(tmp_path / "reg")], capture_output=True, text=True, timeout=900, cwd=root)
    assert out.returncode == 0, out.stderr[-2000:]
    s = json.loads((tmp_path / "s.json").read_text())
    assert s["table"] == "carom" and s["shots"] == 64 and s["shots_with_violations"] == 0 and s["events"] > 64
