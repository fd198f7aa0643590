"""League and ladder matches in this process and on Ray (agents.evaluation.distributed).

Without Ray: ``play_jobs`` in this process gives the match harness's
results (``studies.matches.tournament``) and one game per (job, rack, side);
bad jobs fail before anything is played. With Ray (the ``ray`` extra;
skipped without it, except under CI, where a missing Ray fails): on a
two-node ``ray.cluster_utils.Cluster`` (a head and one more node, one CPU
each) the jobs give the same per-game results as in this process, and a
job whose bot kills its own worker process once (a marker file says it has)
has its chunk played again, with totals equal to the local path's: nothing
counted twice. ``scripts/match.py`` gives the same JSON with and without
``--address local``; ``scripts/match_throughput.py --quick`` runs.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from agents.evaluation.distributed import MatchJob, chunks, pairing_results, play_jobs, tournament

# one Ray user at a time: with pytest-xdist, every test of this group runs in the same worker, one after another
pytestmark = pytest.mark.xdist_group("ray")

ROOT = Path(__file__).resolve().parents[2]
SHOTS = 16  # shot cap of the tiny matches (games cut there are draws)

# A bot that is ghost but, in a process other than the test's, kills that process
# on its third decision unless the marker file exists (it creates it first): the
# first chunk that plays it on Ray loses its worker once.
KILLER = """
import os
from billiards_env.bots import make_bot

MARKER = {marker!r}
DRIVER = {driver}


class Killer:
    name = "killer"

    def __init__(self, seed):
        self.inner, self.calls = make_bot("ghost", seed=seed), 0

    def act(self, view):
        self.calls += 1
        if self.calls == 3 and os.getpid() != DRIVER and _first():
            os._exit(1)
        return self.inner.act(view)


def _first():
    try:  # atomic: of chunks running at once, one creates the marker
        os.close(os.open(MARKER, os.O_CREAT | os.O_EXCL))
        return True
    except FileExistsError:
        return False


def make(seed=0):
    return Killer(seed)
"""


def _jobs():
    return [MatchJob("ghost", "ghost-safety", "nine_ball", racks=3, seed=11, noise="tournament", max_shots=SHOTS,
                     chunk_racks=2),
            MatchJob("ladder-1", "random", "eight_ball", racks=2, seed=12, noise="none", max_shots=SHOTS,
                     chunk_racks=1)]


# ------------------------------------------------------------ no ray needed --
def test_local_play_jobs_equals_the_match_harness():
    from billiards_env.studies.matches import tournament as harness

    names = ["random", "ghost", "ghost-safety"]
    base, base_table = harness(names, "nine_ball", 2, 3, "tournament", max_shots=SHOTS)
    res, table = tournament(names, "nine_ball", 2, 3, "tournament", max_shots=SHOTS)
    assert [r.summary() for r in res] == [r.summary() for r in base] and table == base_table
    for r, b in zip(res, base):
        np.testing.assert_array_equal(r.winner, b.winner)
        np.testing.assert_array_equal(r.a_broke, b.a_broke)


def test_chunks_key_every_game_once():
    jobs = _jobs()
    assert chunks(jobs[0]) == [(0, 2), (2, 3)] and chunks(jobs[1]) == [(0, 1), (1, 2)]
    seen = []
    games = play_jobs(jobs, progress=lambda done, total: seen.append((done, total)))
    assert sorted(games) == sorted((j, r, s) for j, job in enumerate(jobs) for r in range(job.racks) for s in (0, 1))
    assert seen == [(1, 4), (2, 4), (3, 4), (4, 4)]
    res = pairing_results(jobs, games)
    assert [r.n for r in res] == [6, 4] and res[0].a_broke.tolist() == [True] * 3 + [False] * 3
    assert all(g.winner in (-1, 0, 1) and 1 <= g.shots <= SHOTS for g in games.values())


def _decisions(job, bots, result):
    """What a chunk's bots saw: their names and the tables it played."""
    return [b.name for b in bots], result.n


def test_extra_runs_per_chunk_and_comes_back_once_in_chunk_order():
    jobs = _jobs()
    got = []
    games = play_jobs(jobs, extra=_decisions, on_extra=lambda chunk, value: got.append((chunk, value)))
    assert [c for c, _ in got] == [(0, 0, 2), (0, 2, 3), (1, 0, 1), (1, 1, 2)]
    assert [v for _, v in got] == [(["ghost", "ghost-safety"], 4), (["ghost", "ghost-safety"], 2),
                                   (["ladder-1", "random"], 2), (["ladder-1", "random"], 2)]
    assert games == play_jobs(jobs)  # looking does not change the games
    with pytest.raises(TypeError, match="go together"):
        play_jobs(jobs, extra=_decisions)


def test_bad_jobs_fail_before_any_game():
    with pytest.raises(ValueError, match="racks must be at least 1"):
        MatchJob("ghost", "random", racks=0)
    with pytest.raises(ValueError, match="chunk_racks"):
        MatchJob("ghost", "random", chunk_racks=0)
    with pytest.raises(TypeError, match="entrants are names"):
        MatchJob(object(), "random")
    with pytest.raises(ValueError, match="unknown bot|unknown entrant"):
        play_jobs([MatchJob("ghost", "no-such-bot", racks=1)])
    with pytest.raises(ValueError, match="game must be one of"):
        play_jobs([MatchJob("ghost", "random", game="pinball", racks=1)])
    with pytest.raises(TypeError, match="unknown options"):
        play_jobs([], adress="local")


# ---------------------------------------------------------------- ray tests --
@pytest.mark.slow
def test_match_script_gives_the_same_results_with_and_without_ray(tmp_path, ray_module):
    docs = []
    for extra in ([], ["--address", "local"]):
        out = tmp_path / ("ray" if extra else "here")
        cmd = [sys.executable, str(ROOT / "scripts" / "match.py"), "--policies", "ghost", "ghost-safety", "--racks", "2",
               "--max-shots", str(SHOTS), "--chunk-racks", "1", "--out", str(out)] + extra
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        r = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=240)
        assert r.returncode == 0, r.stderr[-2000:]
        assert "chunks played: 2/2" in r.stderr
        docs.append(json.loads((out / "nine_ball_tournament.json").read_text()))
    assert docs[0]["pairings"] == docs[1]["pairings"] and docs[0]["ratings"] == docs[1]["ratings"]
    for doc in docs:  # compute per shot, timed where the games were played (Ray workers too), the same shot counts
        assert set(doc["compute"]) == {"ghost", "ghost-safety"} and doc["compute"]["ghost"]["shots"] > 0
    assert {k: v["shots"] for k, v in docs[0]["compute"].items()} == {k: v["shots"] for k, v in docs[1]["compute"].items()}


@pytest.mark.slow
def test_throughput_script_quick_mode(tmp_path, two_nodes):
    """The script starts its own Ray instance (``--num-cpus 2``) even with another cluster's head running on the
    machine (the two-node Cluster, alive here on purpose): a bare ``ray.init()`` would join that head and refuse
    ``num_cpus``."""
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "match_throughput.py"), "--quick", "--num-cpus", "2",
                        "--out", str(tmp_path)], cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)},
                       capture_output=True, text=True, timeout=240)
    assert r.returncode == 0, r.stderr[-2000:]
    doc = json.loads((tmp_path / "match_throughput.json").read_text())
    assert doc["games"] == 4 and doc["chunks"] == 2 and doc["ray_cpus"] == 2 and doc["same_results"]
    assert all(v > 0 for v in doc["median_games_per_s"].values())


@pytest.fixture(scope="module")
def two_nodes(tmp_path_factory, ray_module):
    """A two-node Cluster (one CPU each) whose workers can import the killer bot."""
    ray = ray_module
    from ray.cluster_utils import Cluster

    folder = tmp_path_factory.mktemp("killer")
    marker = folder / "killed"
    (folder / "killer_bot.py").write_text(KILLER.format(marker=str(marker), driver=os.getpid()))
    old_path, old_env = list(sys.path), os.environ.get("PYTHONPATH")
    sys.path.insert(0, str(folder))
    os.environ["PYTHONPATH"] = os.pathsep.join([str(folder)] + ([old_env] if old_env else []))
    ray.shutdown()
    cluster = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    try:
        cluster.add_node(num_cpus=1)
        cluster.wait_for_nodes()
        from agents.rllib.backend import start_ray
        start_ray(cluster.address)
        yield cluster, marker
    finally:
        ray.shutdown()
        cluster.shutdown()
        sys.path[:] = old_path
        if old_env is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = old_env


@pytest.mark.slow
def test_two_node_cluster_gives_the_local_results(two_nodes):
    import ray

    cluster, _ = two_nodes
    assert len([n for n in ray.nodes() if n["Alive"]]) == 2
    jobs = _jobs()
    local = play_jobs(jobs)
    on_ray = play_jobs(jobs, cluster.address)
    assert on_ray == local and len(on_ray) == 10


@pytest.mark.slow
def test_a_killed_worker_has_its_games_replayed_and_counted_once(two_nodes):
    cluster, marker = two_nodes
    jobs = [MatchJob("killer_bot:make", "ghost", "nine_ball", racks=3, seed=21, noise="tournament",
                     max_shots=SHOTS, chunk_racks=1),
            MatchJob("ghost-safety", "random", "nine_ball", racks=2, seed=22, noise="none", max_shots=SHOTS)]
    local = play_jobs(jobs)  # in this process: the killer never kills here
    assert not marker.exists()
    retried, extras = [], []

    def tables(job, bots, result):  # nested: sent to the workers by value
        return result.n

    on_ray = play_jobs(jobs, cluster.address, on_retry=lambda chunk, exc: retried.append((chunk, type(exc).__name__)),
                       extra=tables, on_extra=lambda chunk, n: extras.append((chunk, n)))
    assert marker.exists()  # a worker did die
    assert extras == [((0, 0, 1), 2), ((0, 1, 2), 2), ((0, 2, 3), 2), ((1, 0, 2), 4)]  # once per chunk
    assert len(retried) == 1 and retried[0][0][0] == 0 and retried[0][1] == "WorkerCrashedError", retried
    assert on_ray == local and len(on_ray) == 10
    a, b = pairing_results(jobs, local), pairing_results(jobs, on_ray)
    assert [r.summary() for r in a] == [r.summary() for r in b]
    assert sum(r.n for r in b) == 2 * 3 + 2 * 2


@pytest.mark.slow
def test_an_error_in_a_chunk_is_raised_not_replayed(two_nodes):
    from agents.rllib.evaluation import ray_map

    def bad(x):
        raise ValueError(f"bad chunk {x}")

    retried = []
    with pytest.raises(ValueError, match="bad chunk 1"):
        ray_map(bad, [(1,)], on_retry=lambda i, exc: retried.append(i))
    assert retried == []


@pytest.mark.slow
def test_a_league_on_the_cluster_ends_as_one_played_here(two_nodes, tmp_path):
    """The league's games (recording bots, samples collected per chunk) on
    the two-node Cluster: the same snapshots (weight hashes), game counts
    and seeds as the league played in this process."""
    from agents.league import LeagueConfig, run_league

    cluster, _ = two_nodes
    cfg = LeagueConfig.from_dict(dict(game="nine_ball", generations=1, racks=2, opponents=["ghost"],
                                      noises=["tournament"], max_shots=10, fit=dict(hidden=[6], epochs=2),
                                      max_snapshots=1))
    quiet = lambda s: None  # noqa: E731
    here = run_league(tmp_path / "here", cfg, log=quiet)
    there = run_league(tmp_path / "there", cfg, address=cluster.address, log=quiet)
    assert [s["sha256"] for s in there["snapshots"]] == [s["sha256"] for s in here["snapshots"]]
    assert there["games"] == here["games"] and there["seeds"] == here["seeds"]
    assert sum(c["games"] for c in there["games"].values()) == 4
