"""Reusable, seeded scene builders for studies of the physics (accuracy, cost)."""
