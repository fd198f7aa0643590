"""The two-player games as PettingZoo users look for them: one module per
game, each with the module-level factories of PettingZoo's own games
(``pettingzoo.classic``), built on the AEC classes of ``games.aec``:

    from billiards_env.envs.games.pz import nine_ball_v0
    env = nine_ball_v0.env()                  # AEC, with PettingZoo's order checks
    env = nine_ball_v0.raw_env(max_shots=40)  # the AEC class itself
    env = nine_ball_v0.parallel_env()         # a turn-based ParallelEnv

Modules: ``nine_ball_v0``, ``eight_ball_v0``, ``ten_ball_v0``,
``three_cushion_v0``, ``snooker_v0`` (each module's name is its env's
``metadata["name"]`` less ``billiards_``). Needs the ``games`` extra.
"""
MODULES = ("nine_ball_v0", "eight_ball_v0", "ten_ball_v0", "three_cushion_v0", "snooker_v0")
