"""Learned shot policies as bots, numpy only: what a policy trained over the
shot menu reads and how its action becomes the game's (``features``,
``menu``, ``game_view``), its network without torch (``mlp``), a network
playing a bot view (``policy``) and the shipped ladder of frozen agents
(``ladder``: ``make_bot("ladder-3")``)."""
