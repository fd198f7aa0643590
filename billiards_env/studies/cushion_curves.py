"""How the cushion models differ on the same impacts: rebound angle and
speed against the incoming angle for a rolling, a stun and a side-spin
ball, one curve per model of ``physics.cushion.MODELS`` (docs/models.md;
``scripts/cushion_curves.py`` draws them).

Angles are measured from the cushion's normal (0 = straight in), positive
along the cushion's +x; the rebound angle is the outgoing velocity's, the
speed ratio |v_out| / |v_in|. Balls: ``rolling`` (omega = z x v / R),
``stun`` (no spin), ``side spin`` (stun plus w_z = SIDE_SPIN V / R: its
contact point with the cushion slips along +x, reverse english for a ball
arriving with +x velocity, which the cushion throws back towards -x)."""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from billiards_env.physics import PhysicsParams
from billiards_env.physics.cushion import MODELS

SPEED = 2.0          # incoming speed (m/s): a firm bank shot
SIDE_SPIN = 1.0      # side spin in units of V / R (a full tip of english is ~1.25)
BALLS = ("rolling", "stun", "side spin")


def incoming(kind: str, angle_deg: float, P: PhysicsParams, speed: float = SPEED) -> tuple:
    """(vx, vy, wx, wy, wz) of a ball hitting the cushion y = 0 (normal
    (0, 1)) at ``angle_deg`` from the normal."""
    a = math.radians(angle_deg)
    vx, vy = speed * math.sin(a), -speed * math.cos(a)
    if kind == "rolling":
        return vx, vy, -vy / P.R, vx / P.R, 0.0   # omega = z x v / R
    if kind == "stun":
        return vx, vy, 0.0, 0.0, 0.0
    if kind == "side spin":
        return vx, vy, 0.0, 0.0, SIDE_SPIN * speed / P.R
    raise ValueError(f"unknown ball {kind!r}; choose one of {BALLS}")


def curves(angles, P: PhysicsParams | None = None) -> list[dict]:
    """One row per (model, ball, incoming angle): rebound angle (degrees
    from the normal) and speed ratio."""
    P = P or PhysicsParams.standard()
    p = P.as_array()
    rows = []
    for name in sorted(MODELS):
        resolve = MODELS[name].resolve
        for kind in BALLS:
            for ang in angles:
                v = incoming(kind, float(ang), P)
                out = resolve(*v, 0.0, 1.0, -v[1], P.e_c, p)
                rows.append(dict(model=name, ball=kind, angle_in=float(ang),
                                 angle_out=math.degrees(math.atan2(out[0], out[1])),
                                 speed_ratio=math.hypot(out[0], out[1]) / SPEED))
    return rows


def write(rows: list[dict], out_png: Path) -> list[Path]:
    """The figure (2 x 3 panels) and the numbers beside it (.csv)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out_png.parent.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), sharex=True)
    for j, kind in enumerate(BALLS):
        for name in sorted(MODELS):
            rs = [r for r in rows if r["model"] == name and r["ball"] == kind]
            x = [r["angle_in"] for r in rs]
            axes[0, j].plot(x, [r["angle_out"] for r in rs], label=name)
            axes[1, j].plot(x, [r["speed_ratio"] for r in rs], label=name)
        axes[0, j].plot(x, x, "k:", lw=0.8, label="mirror")
        axes[0, j].set_title(f"{kind} ball, {SPEED:g} m/s")
        axes[1, j].set_xlabel("incoming angle from the normal (deg)")
    axes[0, 0].set_ylabel("rebound angle from the normal (deg)")
    axes[1, 0].set_ylabel("rebound speed / incoming speed")
    axes[0, 0].legend(fontsize=8)
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
    fig.suptitle("Cushion models on the same impacts (standard physics, python scripts/cushion_curves.py)")
    fig.tight_layout()
    fig.savefig(out_png, dpi=100)
    plt.close(fig)
    out_csv = out_png.with_suffix(".csv")
    with out_csv.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()} for r in rows)
    return [out_png, out_csv]


def default_angles(quick: bool) -> np.ndarray:
    return np.linspace(0.0, 80.0, 5 if quick else 81)
