"""Rendering: image shape/dtype, balls drawn where the state says, paths, animation."""
import imageio.v3 as iio
import numpy as np
import pytest

import billiards_env  # noqa: F401
from billiards_env.envs import NineBallEnv, PotOneEnv, RunOutVectorEnv
from billiards_env.rendering import Animation, FELT_COLOR, ball_color, ball_paths, image_size, save_shot_animation, world_to_pixel
from billiards_env.rendering.draw import NUMBER_DISC_RADIUS, NUMBER_MIN_RADIUS, PPM


def ball_body_pixel(table, p, i, R, ppm):
    """(column, row) of a pixel inside ball i's body colour: its centre, or
    beside its number (on the stripe band of balls 9-15) when numbers are drawn."""
    cx, cy = world_to_pixel(table, p, ppm)
    rp = R * ppm
    dx = 0.0
    if i > 0 and rp >= NUMBER_MIN_RADIUS:
        dx = (0.82 if rp >= NUMBER_DISC_RADIUS else 0.72) * rp
    return int(round(cx + dx)), int(round(cy))


def _check_balls(img, env, state_pos, pocket, ppm=PPM):
    for i, (p, pk) in enumerate(zip(state_pos, pocket)):
        if pk >= 0:
            continue
        c, r = ball_body_pixel(env.table, p, i, env.params.R, ppm)
        assert tuple(img[r, c]) == ball_color(i), f"ball {i} at {p}: pixel {img[r, c]}"


def test_rgb_array_shape_and_balls_at_state_positions():
    env = NineBallEnv(render_mode="rgb_array")
    env.reset(seed=2)
    img = env.render()
    assert img.dtype == np.uint8 and img.shape == image_size(env.table, PPM) + (3,)
    _check_balls(img, env, env.state.pos[0], env.state.pocket[0])
    # a pocketed ball is not drawn
    s = env.state
    pk = s.pocket.copy(); pk[0, 3] = 1
    from billiards_env.physics import BallState
    env.set_state(BallState(s.pos.copy(), s.vel, s.omega, pk))
    img = env.render()
    c, r = ball_body_pixel(env.table, s.pos[0, 3], 3, env.params.R, PPM)
    assert tuple(img[r, c]) != ball_color(3)
    # the felt is drawn mid-table away from the balls
    empty = np.array([env.table.width / 2, 0.05 * env.table.length])
    if np.min(np.hypot(*(s.pos[0] - empty).T)) > 0.1:
        c, r = np.round(world_to_pixel(env.table, empty)).astype(int)
        assert tuple(img[r, c]) == FELT_COLOR


def test_paths_of_last_shot():
    env = PotOneEnv(render_mode="rgb_array")
    env.reset(seed=5)
    start = env.state.pos[0].copy()
    no_path = env.render()
    env.step(np.array([0.0, -0.5, 0.0, 0.0], np.float32))
    log = env.last_events
    paths = ball_paths(log, env.params, 2)
    np.testing.assert_allclose(paths[0][0], start[0], atol=1e-12)
    if env.state.pocket[0, 0] < 0:  # the cue path ends where the cue ball rests
        np.testing.assert_allclose(paths[0][-1], env.state.pos[0, 0], atol=1e-9)
    img = env.render()
    _check_balls(img, env, env.state.pos[0], env.state.pocket[0])
    # the cue ball's path is drawn in white: a point halfway along it (away from any ball)
    mid = paths[0][len(paths[0]) // 2]
    if np.min(np.hypot(*(env.state.pos[0] - mid).T)) > 0.05 and np.hypot(*(mid - start[0])) > 0.05:
        c, r = np.round(world_to_pixel(env.table, mid)).astype(int)
        assert tuple(img[r, c]) == ball_color(0)
    assert not np.array_equal(img, no_path)


def test_vector_render_and_human_headless(monkeypatch):
    v = RunOutVectorEnv(num_envs=3, render_mode="rgb_array", render_ppm=100)
    v.reset(seed=0)
    frames = v.render()
    assert len(frames) == 3 and all(f.shape == image_size(v.table, 100) + (3,) for f in frames)
    for k, f in enumerate(frames):
        _check_balls(f, v, v.state.pos[k], v.state.pocket[k], ppm=100)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    env = PotOneEnv(render_mode="human")
    with pytest.warns(UserWarning, match="needs a display"):
        env.reset(seed=0)  # human mode renders on reset; headless it warns once and shows nothing
    assert env.render() is None


def test_save_shot_animation_gif(tmp_path):
    env = PotOneEnv(render_mode="rgb_array")
    env.reset(seed=1)
    env.step(np.array([0.0, -0.6, 0.0, 0.0], np.float32))
    path = save_shot_animation(tmp_path / "shot.gif", env.table, env.params, env.last_events, 2,
                               Animation(fps=10, ppm=60, speedup=4.0))
    frames = iio.imread(path)
    assert frames.ndim == 4 and frames.shape[0] > 1
    assert frames.shape[1:3] == image_size(env.table, 60)
