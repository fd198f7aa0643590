"""PPO whose update overlaps the next rollout (``train.overlap_updates``).

``OverlappedPPO`` is stable-baselines3's PPO with one change of schedule:
while the update of rollout ``k`` runs in a thread, rollout ``k + 1`` is
collected in the calling thread with the policy as it was before that
update (a copy, ``acting``); then the copy takes the updated weights and the
two rollout buffers swap. So every rollout after the first is collected one
update behind the policy that learns from it (its stored log-probabilities
and values are the acting policy's, which PPO's clipped ratio then corrects
for), and there is one update per rollout as in PPO. With the tables in
worker processes (``train.env_workers``) the update then runs while the
workers step instead of before: the trainer's CPU (the updates) and the
workers' (the env) overlap. torch and the pipes release the GIL, so the two
threads do run at once.

While an update runs, ``model.policy`` read from any other thread is the
acting copy (with its optimiser state as of the last swap): the callbacks
(held-seed evaluations, logging) see a consistent policy, never one half
updated. Checkpoints are sync points: when a callback's ``checkpoint_due``
says the next rollout starts with a checkpoint, that rollout's update runs
before it, not beside it, so the checkpoint holds every update of the steps
it counts, and the rollout after it is collected with those weights. A run
resumed from it (whose first rollout has no update to overlap either) then
follows the uninterrupted run's schedule, one update behind from the second
rollout on.
"""
from __future__ import annotations

import copy
import threading

from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import CallbackList


def _checkpoint_checks(callback) -> list:
    """The ``checkpoint_due(num_timesteps)`` methods of ``callback`` and the callbacks it holds."""
    if isinstance(callback, CallbackList):
        return [c for sub in callback.callbacks for c in _checkpoint_checks(sub)]
    due = getattr(callback, "checkpoint_due", None)
    return [due] if due is not None else []


class OverlappedPPO(PPO):
    """PPO updating rollout k while it collects rollout k + 1 (module docstring)."""

    _updating: threading.Thread | None = None

    @property
    def policy(self):
        d = self.__dict__
        upd = d.get("_updating")
        if upd is not None and threading.current_thread() is not upd:
            return d["_acting"]
        return d.get("_policy")

    @policy.setter
    def policy(self, value) -> None:
        self.__dict__["_policy"] = value

    def _setup_model(self) -> None:
        super()._setup_model()
        self._acting = copy.deepcopy(self.policy)
        self._spare_buffer = copy.deepcopy(self.rollout_buffer)

    def _excluded_save_params(self) -> list[str]:
        return super()._excluded_save_params() + ["_policy", "_acting", "_spare_buffer", "_updating",
                                                  "_update_error"]

    def _sync_acting(self) -> None:
        """The acting copy takes the learner's weights and optimiser state."""
        learner = self.__dict__["_policy"]
        self._acting.load_state_dict(learner.state_dict())
        self._acting.optimizer.load_state_dict(learner.optimizer.state_dict())

    def _train_in_thread(self) -> None:
        try:
            self.train()
        except BaseException as exc:  # noqa: BLE001 (re-raised in the calling thread)
            self._update_error = exc

    def learn(self, total_timesteps: int, callback=None, log_interval: int = 1, tb_log_name: str = "PPO",
              reset_num_timesteps: bool = True, progress_bar: bool = False):
        iteration = 0
        total_timesteps, callback = self._setup_learn(total_timesteps, callback, reset_num_timesteps, tb_log_name,
                                                      progress_bar)
        callback.on_training_start(locals(), globals())
        checks = _checkpoint_checks(callback)
        self._sync_acting()  # a loaded model set the learner's weights after _setup_model
        going = self.collect_rollouts(self.env, callback, self.rollout_buffer, n_rollout_steps=self.n_steps)
        while going:
            iteration += 1
            self._update_current_progress_remaining(self.num_timesteps, total_timesteps)
            if log_interval is not None and iteration % log_interval == 0:
                self.dump_logs(iteration)
            if self.num_timesteps >= total_timesteps:  # the last rollout: nothing to overlap it with
                self.train()
                break
            if any(due(self.num_timesteps) for due in checks):  # a sync point: update, then the checkpoint
                self.train()
                self._sync_acting()
                going = self.collect_rollouts(self.env, callback, self.rollout_buffer, n_rollout_steps=self.n_steps)
                continue
            self._update_error = None
            self._updating = threading.Thread(target=self._train_in_thread, name="ppo-update", daemon=True)
            self._updating.start()
            try:
                going = self.collect_rollouts(self.env, callback, self._spare_buffer, n_rollout_steps=self.n_steps)
            finally:
                self._updating.join()
                self._updating = None
            if self._update_error is not None:
                raise self._update_error
            self._sync_acting()
            self.rollout_buffer, self._spare_buffer = self._spare_buffer, self.rollout_buffer
        callback.on_training_end()
        return self
