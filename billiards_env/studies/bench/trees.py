"""Git trees: a tree's revision, a temporary worktree of another revision,
and sharing numba's on-disk kernels between two identical packages."""
from __future__ import annotations

import contextlib
import shutil
import subprocess
import tempfile
from pathlib import Path

from .options import ROOT


def revision(tree: Path) -> str:
    """The tree's commit (short hash), ``+dirty`` if tracked files differ from it."""
    try:
        sha = subprocess.run(["git", "-C", str(tree), "rev-parse", "--short=10", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(tree), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return sha + ("+dirty" if dirty else "")


@contextlib.contextmanager
def checked_out(rev: str, repo: Path = ROOT):
    """A temporary git worktree of ``rev`` (detached), removed afterwards."""
    sha = subprocess.run(["git", "-C", str(repo), "rev-parse", "--verify", f"{rev}^{{commit}}"],
                         capture_output=True, text=True, check=True).stdout.strip()
    tmp = Path(tempfile.mkdtemp(prefix="billiards-bench-"))
    tree = tmp / "tree"
    subprocess.run(["git", "-C", str(repo), "worktree", "add", "--detach", str(tree), sha],
                   capture_output=True, text=True, check=True)
    try:
        yield tree
    finally:
        removed = subprocess.run(["git", "-C", str(repo), "worktree", "remove", "--force", str(tree)],
                                 capture_output=True).returncode == 0
        shutil.rmtree(tmp, ignore_errors=True)
        if not removed:  # drop the registration of the deleted directory
            subprocess.run(["git", "-C", str(repo), "worktree", "prune"], capture_output=True)


def share_numba_cache(src: Path, dst: Path) -> int:
    """Copy numba's on-disk kernels of ``src``'s package into ``dst`` when every
    source file of the package is byte-identical in both trees (then every
    kernel is the same code; numba keys a cached kernel on its own file only,
    not on the files of the helpers compiled into it, so with any difference
    nothing is shared). Returns the number of files copied."""
    pkg_a, pkg_b = src / "billiards_env", dst / "billiards_env"
    sources_a = sorted(p.relative_to(pkg_a) for p in pkg_a.rglob("*.py"))
    sources_b = sorted(p.relative_to(pkg_b) for p in pkg_b.rglob("*.py"))
    if sources_a != sources_b or any((pkg_a / p).read_bytes() != (pkg_b / p).read_bytes() for p in sources_a):
        return 0
    copied = 0
    for cache_dir in pkg_a.rglob("__pycache__"):
        target = pkg_b / cache_dir.relative_to(pkg_a)
        for f in cache_dir.iterdir():
            if f.suffix in (".nbi", ".nbc"):
                target.mkdir(parents=True, exist_ok=True)
                shutil.copy2(f, target / f.name)
                copied += 1
    return copied
