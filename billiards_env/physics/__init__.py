"""Batched numba billiards physics: strike, felt friction, collisions, pockets.

Public API: PhysicsParams, Effects, Models, Table, BallState, rack, random_placement,
strike, strike_velocity, simulate, SimOptions, SimResult, EventLog.
"""
from .effects import Effects
from .models import Models
from .params import PhysicsParams
from .simulate import EventLog, SimOptions, SimResult, set_num_threads, simulate
from .state import BallState, rack, random_placement
from .strike import strike, strike_velocity
from .table import Table

__all__ = ["Effects", "Models", "PhysicsParams", "EventLog", "SimOptions", "SimResult", "simulate", "set_num_threads",
           "BallState", "rack", "random_placement", "strike", "strike_velocity", "Table"]
