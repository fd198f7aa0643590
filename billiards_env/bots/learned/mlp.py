"""A trained shot policy's network as numpy arrays: observation
normalisation, an MLP and the deterministic action of a ``MultiDiscrete``
head, without torch or stable-baselines3.

It reproduces stable-baselines3's ``ActorCriticPolicy.predict(obs,
deterministic=True)`` for PPO over the shot menu (``MlpPolicy``, separate
actor and critic networks, ``FlattenExtractor``): the observation normalised
as ``VecNormalize.normalize_obs`` does, ``clip((obs - mean) / sqrt(var +
eps), -clip, clip)`` in float64 and then cast to float32 (the policy's
input dtype); the actor's hidden layers ``h = act(W h + b)`` in float32; the
action logits ``W h + b``, split per ``nvec`` component, and each
component's argmax (the mode of SB3's ``MultiCategoricalDistribution``;
ties go to the first index, as torch's ``argmax``). The critic is not kept.
"""
from __future__ import annotations

import dataclasses

import numpy as np

ACTIVATIONS = {"tanh": np.tanh, "relu": lambda x: np.maximum(x, 0.0)}
NORM_EPS = 1e-8  # VecNormalize's default epsilon under the square root


@dataclasses.dataclass(frozen=True)
class ObsNorm:
    """Running observation statistics of the training run."""
    mean: np.ndarray      # [D] float64
    var: np.ndarray       # [D] float64
    clip: float = 10.0
    eps: float = NORM_EPS

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        return np.clip((obs - self.mean) / np.sqrt(self.var + self.eps), -self.clip, self.clip)


@dataclasses.dataclass(frozen=True)
class MLPPolicy:
    """``weights[k]`` [out, in] and ``biases[k]`` [out] (float32) of the
    hidden layers then the action head; ``nvec``: the ``MultiDiscrete``
    sizes the head's logits split into."""
    weights: tuple
    biases: tuple
    activation: str
    nvec: tuple
    norm: ObsNorm | None = None

    def __post_init__(self):
        if self.activation not in ACTIVATIONS:
            raise ValueError(f"activation must be one of {sorted(ACTIVATIONS)}, got {self.activation!r}")
        if len(self.weights) != len(self.biases) or not self.weights:
            raise ValueError("weights and biases must be non-empty and of the same length")
        if self.weights[-1].shape[0] != sum(self.nvec):
            raise ValueError(f"the head gives {self.weights[-1].shape[0]} logits, nvec {list(self.nvec)} "
                             f"needs {sum(self.nvec)}")

    @property
    def obs_dim(self) -> int:
        return self.weights[0].shape[1]

    def logits(self, obs: np.ndarray) -> np.ndarray:
        """Action logits [N, sum(nvec)] of observations [N, obs_dim]."""
        obs = np.asarray(obs)
        if obs.ndim != 2 or obs.shape[1] != self.obs_dim:
            raise ValueError(f"the policy takes observations [N, {self.obs_dim}], got {list(obs.shape)}")
        x = self.norm(obs) if self.norm is not None else obs
        h = np.asarray(x, dtype=np.float32)
        act = ACTIVATIONS[self.activation]
        for w, b in zip(self.weights[:-1], self.biases[:-1]):
            h = act(h @ w.T + b)
        return h @ self.weights[-1].T + self.biases[-1]

    def act(self, obs: np.ndarray) -> np.ndarray:
        """Deterministic actions int64 [N, len(nvec)]."""
        z = self.logits(obs)
        edges = np.cumsum((0,) + tuple(self.nvec))
        return np.stack([z[:, edges[i]:edges[i + 1]].argmax(axis=1) for i in range(len(self.nvec))], axis=1)

    def arrays(self) -> dict:
        """The arrays of an ``.npz`` (``from_arrays`` reads them back)."""
        out = {f"w{k}": w for k, w in enumerate(self.weights)}
        out.update({f"b{k}": b for k, b in enumerate(self.biases)})
        if self.norm is not None:
            out.update(obs_mean=self.norm.mean, obs_var=self.norm.var)
        return out

    @classmethod
    def from_arrays(cls, arrays, activation: str, nvec, clip: float = 10.0, eps: float = NORM_EPS) -> "MLPPolicy":
        n = sum(1 for k in arrays if k.startswith("w"))
        norm = ObsNorm(np.asarray(arrays["obs_mean"], np.float64), np.asarray(arrays["obs_var"], np.float64),
                       clip, eps) if "obs_mean" in arrays else None
        return cls(tuple(np.asarray(arrays[f"w{k}"], np.float32) for k in range(n)),
                   tuple(np.asarray(arrays[f"b{k}"], np.float32) for k in range(n)), activation,
                   tuple(int(v) for v in nvec), norm)
