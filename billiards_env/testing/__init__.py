"""Invariant checks and random-shot generators for testing simulations
(the hard-case suite, hypothesis fuzzing and scripts/fuzz.py use them)."""
from .invariants import assert_invariants, check_invariants, initial_energy, run_checked
from .fuzzing import CAROM_LAYOUTS, LAYOUTS, carom_batch, case_dict, load_case, random_batch, run_batch, save_case

__all__ = ["assert_invariants", "check_invariants", "initial_energy", "run_checked",
           "CAROM_LAYOUTS", "LAYOUTS", "carom_batch", "case_dict", "load_case", "random_batch", "run_batch", "save_case"]
