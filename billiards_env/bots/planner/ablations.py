"""``champion`` with one part taken out, as ``module:factory`` entrants of ``scripts/match.py`` (docs/games.md,
"champion"): ``--policies billiards_env.bots.planner.ablations:no_throw lookahead-2026.12``."""
from __future__ import annotations

from .bot import Champion, Parts


def _named(bot: Champion, name: str) -> Champion:
    bot.name = name
    return bot


def no_windows(seed: int = 0) -> Champion:
    """Lookahead's own pots (aimed at pocket centres, its 2-degree overcut variant) instead of the window-aimed,
    throw-corrected ones."""
    return _named(Champion(seed=seed, parts=Parts(windows=False)), "champion-no-windows")


def no_throw(seed: int = 0) -> Champion:
    """Window-aimed pots at the ghost-ball aim, not corrected for throw."""
    return _named(Champion(seed=seed, parts=Parts(throw=False)), "champion-no-throw")


def no_halving(seed: int = 0) -> Champion:
    """The first round's entrants all sampled 16 times (no halving; about the same number of noisy previews)."""
    return _named(Champion(seed=seed, rounds=(16,)), "champion-no-halving")


def one_ply(seed: int = 0) -> Champion:
    """Without lookahead's reply search on the best survivors."""
    return _named(Champion(seed=seed, parts=Parts(replies=False)), "champion-one-ply")


def one_exact(seed: int = 0) -> Champion:
    """Without noise, only the shot itself searched exactly (its one-ply leave), not the next shooter's shot."""
    return _named(Champion(seed=seed, exact_plies=1), "champion-one-exact")


def exact12(seed: int = 0) -> Champion:
    """Without noise, the next shot searched from the 12 best candidates' outcomes (the default 6)."""
    return _named(Champion(seed=seed, exact_k=12), "champion-exact12")


def exact3(seed: int = 0) -> Champion:
    """Without noise, two more shots searched exactly from the 4 best candidates' outcomes at each level."""
    return _named(Champion(seed=seed, exact_plies=3, exact_k=4), "champion-exact3")


def no_exact_break(seed: int = 0) -> Champion:
    """Without noise, the searched break as under noise, not searched again on each rack."""
    return _named(Champion(seed=seed, exact_breaks=0), "champion-no-exact-break")


def no_escapes(seed: int = 0) -> Champion:
    """Where balls fly (``scripts/match.py --airborne``), without the jump and massé strokes out of a hook."""
    return _named(Champion(seed=seed, parts=Parts(escapes=False)), "champion-no-escapes")


def no_safety_grid(seed: int = 0) -> Champion:
    """Without the grid of soft shots (``candidates.safety_grid``), 8 safeties in the first noisy round: champion
    before the grid (with the kick scan)."""
    return _named(Champion(seed=seed, parts=Parts(safety_grid=False), first_safe=8), "champion-no-safety-grid")


def no_kick_scan(seed: int = 0) -> Champion:
    """Without the kicks found by scanning the simulator on hooked tables (``candidates.kick_scan``), the spare
    first-round places given to the safeties (``Parts.safe_fill``) and the safety grid: champion before all three."""
    return _named(Champion(seed=seed, parts=Parts(kick_scan=False, safe_fill=False, safety_grid=False), first_safe=8),
                  "champion-no-kick-scan")
