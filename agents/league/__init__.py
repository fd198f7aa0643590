"""The league that trains the value network of ``value-lookahead`` (``agents.league.league``), and its numpy fit
(``agents.league.fit``). ``scripts/league.py`` is its command line; docs/league.md says how it was run."""
from .fit import FitConfig, fit_value
from .league import LeagueConfig, load_state, run_league, ship, weights_hash

__all__ = ["FitConfig", "fit_value", "LeagueConfig", "load_state", "run_league", "ship", "weights_hash"]
