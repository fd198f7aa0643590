"""``action_mode: choice``, the shot menu: the library's
``billiards_env.bots.learned.menu`` (its docstring describes the menu),
re-exported for the training code."""
from billiards_env.bots.learned.menu import *  # noqa: F401,F403
from billiards_env.bots.learned.menu import _MENUS, _build_menu  # noqa: F401
