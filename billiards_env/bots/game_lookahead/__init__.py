"""``lookahead`` for the two-player games: shots chosen by the position they leave, under sampled noise.

One job per module: ``pots`` (the geometric kernels), ``candidates`` (the shots tried), ``valuation`` (a
previewed shot's value), ``breaks`` (the searched break), ``budget`` (the search's sizes) and ``search``
(``GameLookahead``: the search over them, with the opponent's reply).

For every table where the bot is to move (all tables at once, in batched ``GameView.preview`` calls):

1. **Starts.** The cue ball where it lies, or, with ball in hand, ``hand_pots`` x ``len(HAND_BACKS)`` x
   ``len(HAND_TURNS)`` searched spots: behind the ghost ball of each of the easiest pots (by ``pot_table``, the
   cue ball placed ideally), at two distances and three angles (a straight-in pot and two cuts that send the cue
   ball different ways), each made legal by ``view.legal_placement``.
2. **Candidates.** From each start: the ``n_pots`` easiest open ghost-ball pots on the legal targets (every
   legal ball and pocket weighed by ``pot_table``'s success probability), each in ``len(THROW)`` aims (the ghost
   ball's and one overcut against collision-induced throw), ``len(SPEEDS)`` speeds (factors of the speed that just
   drops the ball) and ``len(HEIGHTS)`` tip heights (draw, stun, follow); from the cue ball where it lies (or the
   first ball-in-hand spot) also ``n_safe`` safeties (soft shots across the legal targets), ``n_bank`` one-rail
   kicks (aimed at a legal ball's mirror image in a cushion's line) and ``n_kick`` shots in any direction. On
   the 8 the pot's pocket is called; a safety calls the pocket the 8 is easiest into.
3. **Rules and leave.** Every candidate is previewed once without noise and judged by the rules. Its value for
   the mover: 1 for a win, 0 for a loss; if the mover keeps the table, ``position_value`` of the leave (the ease
   of the mover's best next pot, ``leave_ease``); if the turn passes, 1 minus the opponent's ``position_value``
   (their best pot's ease, with ball in hand after a foul). ``position_value(e) = V_NONE + (V_FULL - V_NONE) e``:
   a table with no pot is worth ``V_NONE`` (a safety battle), a sure pot ``V_FULL``.
4. **Noise.** The ``n_eval`` best candidates (``n_eval_safe`` of them kept for safeties and kicks) are previewed
   again ``n_samples`` times each under sampled execution noise (the env's own noise; the ``tournament`` preset
   when the env has none) and valued the same way; the best mean is played.
   **Two plies** (``reply_eval`` > 0): the ``reply_eval`` best of them per table (``reply_safe`` kept for
   safeties and kicks) are judged again on their first ``reply_samples`` noisy outcomes where the turn passes:
   the opponent's reply is searched from the leave with this same machinery at the smaller ``REPLY_BUDGET``
   (``GameView.after`` builds the opponent's view from the preview), and the leave is worth 1 minus that reply's
   noisy value. Each such candidate's mean moves by the mean change over those outcomes, and the best of them is
   played (``replies``). With ``reply_keep`` (off; ``BUDGETS["deep"]``) the outcomes where the mover keeps the table
   are searched too: the leave is worth the mover's own searched next shot (a third ply along a run).
5. **Declarations (9-ball).** Where a push-out is allowed, ``n_push`` soft pushes are previewed; a push leaving
   ease ``e`` is worth ``min(v, 1 - v)`` with ``v = position_value(e)`` (the opponent chooses whether to shoot),
   and is declared when it beats the best shot's value. After the opponent's push-out, the shot is passed back
   when the best shot's value is below 1/2 (the opponent would then shoot the same table).
6. **Breaks** are searched once per game and table and kept (``searched_break``): ``break_search`` candidate
   strikes (the cue ball along the head string, the aim across the front ball, speed, tip height), each
   previewed under noise on the first ``break_racks`` breaking racks and valued as any shot; with
   ``break_search=0``, ``GhostBot``'s seeded standard break.

``pot_table`` and ``leave_ease`` are the geometric part (numba kernels here): the ghost-ball shot of a ball into a
pocket; a pot is open when both paths are clear of other balls (by 2R + ``BLOCK_CLEAR``), the cut is below
``MAX_CUT`` and the approach to the pocket is within its mouth (``CORNER_APPROACH``, ``SIDE_APPROACH``); its
success probability is ``erf(tol / (sqrt(2) sigma))`` with the pocket's angular tolerance ``tol`` (its accepted
half-width over the ball's distance to it) and the object ball's direction error ``sigma`` (the aim error
propagated through the contact, ``sigma_aim d_cg / (2R cos cut)``, plus ``SIGMA_MODEL``).

Cost per decision: about ``starts x n_pots x variants + n_safe + n_bank + n_kick (+ n_push)`` noise-free previews plus
``n_eval x n_samples`` noisy ones, plus with two plies a reply search (``REPLY_BUDGET``) per searched leave
(``sims`` counts them all).
"""
from .budget import BUDGETS, REPLY_BUDGET, Budget
from .pots import V_FULL, V_NONE, PocketModel, PotArrays, balls_left, position_value
from .search import GameLookahead, game_lookahead, lookahead_fast, lookahead_medium

__all__ = ["BUDGETS", "REPLY_BUDGET", "Budget", "V_FULL", "V_NONE", "PocketModel", "PotArrays", "balls_left",
           "position_value", "GameLookahead", "game_lookahead", "lookahead_fast", "lookahead_medium"]
