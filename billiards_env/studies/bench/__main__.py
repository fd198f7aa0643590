"""``python -m billiards_env.studies.bench``: ``scripts/benchmark.py`` without
the rllib section (agents/, above the library, plugs it in from the script)."""
from . import main

main()
