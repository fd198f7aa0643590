"""Play the two-player games against the bots in your browser (docs/play.md).

    python scripts/play.py                 # http://127.0.0.1:8765/, opens the browser
    python scripts/play.py --no-browser --port 0
"""
from billiards_env.play.server import main

if __name__ == "__main__":
    raise SystemExit(main())
