"""The agent's side of the env, shared by the stable-baselines3 and RLlib
backends and by the evaluation of trained models: the training wrappers of
the agent-side features and action modes (``features``), the shot menu of
``action_mode: choice`` (``choice``) and the one-player view of a two-player
game with the helpers that find the native env under wrappers
(``game_view``). The features, the menu and the view themselves live in the
library (``billiards_env.bots.learned``, numpy only) and are re-exported.

Imports nothing (``features`` needs stable-baselines3, the others do not)."""
