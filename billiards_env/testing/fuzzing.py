"""Random shots for fuzzing (tests/physics/test_fuzz.py, scripts/fuzz.py) and their
JSON regression files."""
from __future__ import annotations

import json
import pathlib
import time

import numpy as np

from billiards_env.physics import BallState, Effects, Models, PhysicsParams, SimOptions, Table, rack, simulate, strike
from .invariants import check_invariants

LAYOUTS = ("nine", "eight", "random")
CAROM_LAYOUTS = ("carom",)  # three balls on the carom table (carom_batch)
CAROM_CONTACTS = 64         # the carom fuzz keeps the cue ball's contacts, as three-cushion does
CAROM_FROZEN = 0.3          # chance a carom ball is frozen to a ball placed before it
CAROM_ON_CUSHION = 0.3      # chance a carom ball is frozen to a cushion (its centre exactly R from the nose)
CAROM_EXTREME_SPIN = 0.5    # chance a carom shot's tip offset sits at the miscue limit (extreme spin)


def carom_batch(rng, n_envs, pockets=False):
    """``n_envs`` carom tables (``Table.carom()``, ``PhysicsParams.carom()``)
    of three balls with the hard cases of the carom table: balls frozen to a
    ball (centres exactly 2R apart) or to a cushion (exactly R from its
    nose), and strikes at the miscue limit (extreme spin) with any draw."""
    params, table = PhysicsParams.carom(), Table.carom()
    R, w, l = params.R, table.width, table.length
    pos = np.empty((n_envs, 3, 2))
    for b in range(3):
        todo = np.arange(n_envs)
        while len(todo):
            p = rng.uniform((R, R), (w - R, l - R), size=(len(todo), 2))
            u = rng.random(len(todo))
            if b:
                k = rng.integers(0, b, len(todo))
                ang = rng.uniform(0, 2 * np.pi, len(todo))
                snap = u < CAROM_FROZEN
                p[snap] = pos[todo[snap], k[snap]] + 2 * R * np.stack([np.cos(ang[snap]), np.sin(ang[snap])], 1)
            wall = (u >= CAROM_FROZEN) & (u < CAROM_FROZEN + CAROM_ON_CUSHION)
            side = rng.integers(0, 4, len(todo))
            p[wall & (side == 0), 0], p[wall & (side == 1), 0] = R, w - R
            p[wall & (side == 2), 1], p[wall & (side == 3), 1] = R, l - R
            ok = (p[:, 0] >= R) & (p[:, 0] <= w - R) & (p[:, 1] >= R) & (p[:, 1] <= l - R)
            if b:
                d = np.hypot(*(pos[todo, :b] - p[:, None]).transpose(2, 0, 1))
                ok &= (d >= 2 * R - 1e-12).all(1)
            pos[todo[ok], b] = p[ok]
            todo = todo[~ok]
    return random_strikes(BallState.from_positions(pos), rng, params, CAROM_EXTREME_SPIN), table, params


def random_strikes(s, rng, params, extreme_spin: float = 0.0):
    """``s`` struck at random: any aim, the draw's square root uniform, tip
    offsets uniform over the miscue disc, a fraction ``extreme_spin`` of them
    moved onto its edge (drawn only when asked for: the pool fuzzing's draws
    stay as they were)."""
    n = s.n_envs
    phi = rng.uniform(0, 2 * np.pi, n)
    draw = params.max_draw * rng.uniform(0, 1, n) ** 0.5
    r = params.miscue_limit * np.sqrt(rng.uniform(0, 1, n)) * (1 - 1e-12)
    if extreme_spin:
        r = np.where(rng.random(n) < extreme_spin, params.miscue_limit * (1 - 1e-12), r)
    ang = rng.uniform(0, 2 * np.pi, n)
    return strike(s, phi, draw, r * np.cos(ang), r * np.sin(ang), params)
# On the snooker table: the frozen 22-ball frame opening, random balls, and random balls of which about half lie
# in a pocket's mouth or jaws (within JAW_REACH of a pocket's capture circle centre).
SNOOKER = "snooker"  # the equipment's name: its table, preset and opening layout
SNOOKER_LAYOUTS = (SNOOKER, "random", "jaws")
JAW_REACH = 0.09  # m: a corner jaw reaches ~0.06 m from its pocket's centre, a middle jaw ~0.05 m
TABLES = {"pool9": lambda: Table.pool(9), "snooker": Table.snooker}


def random_batch(rng, n_envs, layout, preset, n_balls=None, pockets=True, table_name="pool9"):
    """``n_envs`` tables of one layout, each with a random cue strike.
    ``pockets=False``: random balls lie inside the closed box (a ball in a
    pocket mouth would be off that table). ``table_name``: ``pool9`` (the
    9 ft pool table) or ``snooker`` (``SNOOKER_LAYOUTS``). ``layout="carom"``: ``carom_batch``."""
    if layout == "carom":
        return carom_batch(rng, n_envs, pockets)
    params = PhysicsParams.preset(preset)
    table = TABLES[table_name]()
    R = params.R
    if layout in ("nine", "eight", "snooker"):
        s = rack(table, params, layout, n_envs, gap=0.0, seed=rng)
        if layout == "snooker":  # the cue ball anywhere in the D, clear of the yellow, brown and green
            m = table.marks
            todo = np.arange(n_envs)
            while len(todo):
                r, a = m.d_radius * np.sqrt(rng.uniform(0, 1, len(todo))), rng.uniform(np.pi, 2 * np.pi, len(todo))
                p = np.stack([m.d_centre[0] + r * np.cos(a), m.d_centre[1] + r * np.sin(a)], 1)
                ok = (np.hypot(*(s.pos[todo, 1:] - p[:, None]).transpose(2, 0, 1)) >= 2 * R).all(1)
                s.pos[todo[ok], 0] = p[ok]
                todo = todo[~ok]
    else:
        B = n_balls or int(rng.integers(2, 17))
        pos = np.empty((n_envs, B, 2))
        lo, hi = np.array([R, R]), np.array([table.width - R, table.length - R])
        for b in range(B):
            todo = np.arange(n_envs)
            while len(todo):
                p = rng.uniform(lo, hi, size=(len(todo), 2))
                if layout == "jaws" and pockets and rng.random() < 0.5:  # in a pocket's mouth or jaws
                    k = rng.integers(0, len(table.pockets), len(todo))
                    p = table.pockets[k, :2] + rng.uniform(-JAW_REACH, JAW_REACH, size=(len(todo), 2))
                # exactly frozen contacts are a hard case: sometimes snap to a neighbour
                if b and rng.random() < 0.3:
                    k = rng.integers(0, b)
                    ang = rng.uniform(0, 2 * np.pi, len(todo))
                    p = pos[todo, k] + 2 * R * np.stack([np.cos(ang), np.sin(ang)], 1)
                ok = table.contains(p, R, 0.0, pockets)
                if b:
                    d = np.hypot(*(pos[todo, :b] - p[:, None]).transpose(2, 0, 1))
                    ok &= (d >= 2 * R - 1e-12).all(1)
                pos[todo[ok], b] = p[ok]
                todo = todo[~ok]
        s = BallState.from_positions(pos)
    return random_strikes(s, rng, params), table, params


TABLE_KINDS = ("pool", "carom", SNOOKER)


def table_layout(rng, kind: str):
    """A random layout for a batch on a table of ``kind`` (``TABLE_KINDS``):
    pool, 9-ball and 8-ball racks and random balls on the 9 ft table
    (standard physics, the seed's one time in five); carom, three balls on
    the carom match table (``carom_batch``); snooker, the opening, random
    balls and balls in the jaws on the 12 ft table. Returns ``random_batch``'s
    (layout, preset, table_name) and the table's name for ``case_dict``
    (None: picked by the equipment)."""
    if kind not in TABLE_KINDS:
        raise ValueError(f"unknown table kind {kind!r}; choose one of {TABLE_KINDS}")
    if kind == SNOOKER:  # its layouts, preset, table and case table all bear the equipment's name
        return SNOOKER_LAYOUTS[int(rng.integers(len(SNOOKER_LAYOUTS)))], SNOOKER, SNOOKER, SNOOKER
    layouts = CAROM_LAYOUTS if kind == "carom" else LAYOUTS
    layout = layouts[int(rng.integers(len(layouts)))]
    preset = "seed" if rng.random() < 0.2 else "standard"
    return layout, preset, "pool9", None  # carom: its layout picks the table


def run_batch(state, table, params, solver, dt=1e-3, effects=None, models=None):
    """Simulate with diagnostics under ``effects`` (default: all) and
    ``models`` (default: ``Models()``) and check every invariant; a closed
    box (pockets off) must keep every ball."""
    effects = effects or Effects.all()
    kw = {} if solver == "event" else {"dt": dt}
    if table.style == "carom":  # the kernel three-cushion runs: the contact order kept
        kw["options"] = SimOptions(contacts=CAROM_CONTACTS)
    res = simulate(state, table, params, solver=solver, effects=effects, diagnostics=True,
                   models=models or Models(), **kw)
    return res, check_invariants(res, state, table, params, pockets=effects.pockets)


def case_dict(state, e, params, solver, dt, violations, effects=None, models=None, table_name=None):
    """A failing case; ``table_name`` (``TABLES``, or ``carom``) defaults to the carom table for carom
    equipment, else pool9."""
    if table_name is None:
        table_name = "carom" if params == PhysicsParams.carom() else "pool9"
    case = {"solver": solver, "dt": dt, "table": table_name, "params": params.to_dict(),
            "effects": (effects or Effects.all()).to_dict(),
            "pos": state.pos[e].tolist(), "vel": state.vel[e].tolist(),
            "omega": state.omega[e].tolist(), "pocket": state.pocket[e].tolist(),
            "violations": violations}
    if state.air is not None:
        case["air"] = state.air[e].tolist()
    if models is not None and models != Models():
        case["models"] = models.to_dict()
    return case


def save_case(case, directory, tag="fuzz"):
    """Write a failing case as JSON into ``directory`` (tests/regressions/ in
    this repository, replayed by tests/physics/test_regressions.py)."""
    directory = pathlib.Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / f"{tag}_{case['solver']}_{time.strftime('%Y%m%d_%H%M%S')}_{abs(hash(json.dumps(case['pos']))) % 10**8:08d}.json"
    path.write_text(json.dumps(case, indent=1))
    return path


def load_case(path):
    """A saved case: (case dict, state, table, params). Its effect set is
    ``Effects.from_dict(case.get("effects"))`` (cases saved before effects
    existed ran with all of them), its models
    ``Models.from_dict(case.get("models"))`` (absent: the default models)."""
    c = json.loads(pathlib.Path(path).read_text())
    params = PhysicsParams(**c["params"])
    table = (TABLES[c["table"]]() if c["table"] in TABLES else Table.carom() if c["table"] == "carom"
             else Table.pocketless(*c.get("size", (1.27, 2.54))))
    s = BallState(np.array(c["pos"])[None], np.array(c["vel"])[None], np.array(c["omega"])[None],
                  np.array(c["pocket"], dtype=np.int64)[None], np.array(c["air"])[None] if "air" in c else None)
    return c, s, table, params


def report(summary: dict, path=None) -> None:
    """Print a fuzz run's ``summary`` as JSON, and write it to ``path`` (its folder made) when one is given."""
    text = json.dumps(summary, indent=1)
    print(text)
    if path:
        path = pathlib.Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text + "\n")
