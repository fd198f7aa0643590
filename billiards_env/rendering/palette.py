"""Ball colours of the tables that do not use pool's numbered set (the
renderer's ``draw.ball_colors`` and the replay viewer's JSON read them)."""
from __future__ import annotations

# Snooker: the white, 15 reds (balls 1..15), then yellow, green, brown, blue, pink, black (16..21).
SNOOKER_COLORS = ((255, 255, 255),) + ((200, 20, 20),) * 15 + (
    (250, 215, 0), (0, 130, 60), (120, 70, 30), (0, 70, 200), (250, 130, 170), (15, 15, 15))


def snooker_colors(table, n_balls: int) -> list | None:
    """Snooker's colours [n_balls] on a table with snooker marks; None on any other table."""
    if getattr(table, "marks", None) is None:
        return None
    return [SNOOKER_COLORS[i] for i in range(n_balls)]
