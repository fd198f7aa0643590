"""Rendering of pool tables: still images, shot paths and animations
(numpy + Pillow), exact replays as JSON and a self-contained HTML viewer."""
from .draw import (BALL_COLORS, Animation, FELT_COLOR, ball_color, ball_paths, balls_at, image_size, positions_at,
                   render_table, save_replay_animation, save_shot_animation, world_to_pixel, write_animation)
from .game_replay import GameRecorder
from .html import replay_html, save_replay_html
from .recorder import RecordReplay
from .replay import Replay, evolve_state, record_env_shot, replay_for_env

__all__ = ["Animation", "BALL_COLORS", "FELT_COLOR", "ball_color", "ball_paths", "balls_at", "image_size",
           "positions_at", "render_table", "save_replay_animation", "save_shot_animation", "world_to_pixel",
           "write_animation", "replay_html", "save_replay_html", "GameRecorder", "RecordReplay", "Replay",
           "evolve_state", "record_env_shot", "replay_for_env"]
