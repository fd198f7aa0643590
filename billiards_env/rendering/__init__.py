"""Rendering of pool tables (numpy + Pillow): still images, shot paths and animations."""
from .draw import (BALL_COLORS, FELT_COLOR, ball_color, ball_paths, image_size, positions_at, render_table,
                   save_shot_animation, world_to_pixel)

__all__ = ["BALL_COLORS", "FELT_COLOR", "ball_color", "ball_paths", "image_size", "positions_at", "render_table",
           "save_shot_animation", "world_to_pixel"]
