"""The agent's side of the env, shared by the stable-baselines3 and RLlib
backends and by the evaluation of trained models: the agent-side
observation features and the action modes (``features``: ghost-ball features,
direct / residual actions), the shot menu of ``action_mode: choice``
(``choice``), and the one-player view of a two-player game with the helpers
that find the native env under wrappers (``game_view``).

Imports nothing (``features`` needs stable-baselines3, the others do not)."""
