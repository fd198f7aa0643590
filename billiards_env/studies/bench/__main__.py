"""``python -m billiards_env.studies.bench`` (the same as ``scripts/benchmark.py``)."""
from . import main

main()
