"""Training and playing with stable-baselines3 on the native vector env.

- ``vec_env``: the SB3 ``VecEnv`` adapter (one batched simulator call per step);
- ``training``: PPO / SAC training, held-seed evaluation during training,
  the final evaluation (``scripts/train.py``);
- ``checkpoints``: periodic checkpoints and resuming a killed run;
- ``policy``: ``SB3Policy``, a saved model as a policy of the evaluation harness.

Imports nothing here: stable-baselines3 (and torch) load with the submodules."""
